#include "modern/silhouettes.h"

#include <map>
#include <tuple>

#include "core/errors.h"

namespace sl::modern {

EdgeAdjacency buildEdgeAdjacency(const Mesh& mesh, const std::string& objectName) {
  EdgeAdjacency out;
  // Weld positions that are exactly equal (flat-shaded boxes and cylinders repeat them).
  std::map<std::tuple<float, float, float>, unsigned> weld;
  std::vector<unsigned> id(mesh.positions.size());
  for (size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& p = mesh.positions[i];
    auto [it, added] = weld.emplace(std::make_tuple(p.x, p.y, p.z), unsigned(out.positions.size()));
    if (added) out.positions.push_back(p);
    id[i] = it->second;
  }
  // Directed edge (a, b) -> the triangle that walks it; its twin (b, a) must exist exactly once.
  std::map<std::pair<unsigned, unsigned>, unsigned> directed;
  const auto notClosed = [&](const std::string& why) {
    return InputError("object '" + objectName + "' is not a closed 2-manifold mesh (" + why +
                      "); shadow volumes and smoothies need closed blockers (Chan §3.1)");
  };
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::uvec3 tri(id[mesh.indices[t]], id[mesh.indices[t + 1]], id[mesh.indices[t + 2]]);
    const unsigned index = unsigned(out.triangles.size());
    out.triangles.push_back(tri);
    for (int e = 0; e < 3; ++e) {
      const unsigned a = tri[e], b = tri[(e + 1) % 3];
      if (a == b) throw notClosed("degenerate triangle");
      if (!directed.emplace(std::make_pair(a, b), index).second)
        throw notClosed("an edge is used twice in the same direction");
    }
  }
  for (const auto& [edge, triangle] : directed) {
    if (edge.first > edge.second) continue;  // each undirected edge once, from its a < b half
    auto twin = directed.find({edge.second, edge.first});
    if (twin == directed.end()) throw notClosed("an edge has only one triangle");
    out.edges.push_back({edge.first, edge.second, triangle, twin->second});
  }
  for (const auto& [edge, triangle] : directed)
    if (edge.first > edge.second && !directed.count({edge.second, edge.first}))
      throw notClosed("an edge has only one triangle");
  if (out.edges.empty()) throw notClosed("no triangles");
  return out;
}

SceneCasters collectClosedCasters(const Scene& scene) {
  SceneCasters out;
  for (const Object& o : scene.objects) {
    if (!o.castsShadow) continue;
    if (!o.mesh->closed) {
      ++out.openSkipped;
      out.openNames += (out.openNames.empty() ? "" : ", ") + o.name;
      continue;
    }
    out.closed.push_back({&o, buildEdgeAdjacency(*o.mesh, o.name)});
  }
  return out;
}

Silhouette findSilhouette(const EdgeAdjacency& mesh, const glm::vec3& light) {
  Silhouette s;
  s.facesLight.resize(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    const glm::vec3 p0 = mesh.positions[tri[0]];
    const glm::vec3 n = glm::cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
    s.facesLight[t] = glm::dot(n, light - p0) > 0.0f;
  }
  // Brute force over every edge (Chan §4.2 step 2).
  for (const EdgeAdjacency::Edge& e : mesh.edges) {
    const bool firstFaces = s.facesLight[e.first];
    if (firstFaces == s.facesLight[e.second]) continue;
    // Orient the edge as it runs in its light-facing triangle.
    if (firstFaces)
      s.edges.emplace_back(e.a, e.b);
    else
      s.edges.emplace_back(e.b, e.a);
  }
  return s;
}

std::vector<glm::vec4> buildShadowVolume(const EdgeAdjacency& mesh, const Silhouette& silhouette,
                                         const glm::vec3& light) {
  std::vector<glm::vec4> v;
  v.reserve(mesh.triangles.size() * 3 + silhouette.edges.size() * 6);
  const auto finite = [&](unsigned i) { return glm::vec4(mesh.positions[i], 1.0f); };
  // A point at infinity in the direction away from the light (Everitt–Kilgard, w = 0).
  const auto infinite = [&](unsigned i) { return glm::vec4(mesh.positions[i] - light, 0.0f); };
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    for (int k = 0; k < 3; ++k)
      v.push_back(silhouette.facesLight[t] ? finite(tri[k]) : infinite(tri[k]));
  }
  // Side quads: for the edge a -> b of a light-facing triangle, (b, a, a_inf, b_inf) faces away
  // from that triangle's interior, i.e. out of the volume.
  for (const auto& [a, b] : silhouette.edges) {
    for (const glm::vec4& p : {finite(b), finite(a), infinite(a)}) v.push_back(p);
    for (const glm::vec4& p : {finite(b), infinite(a), infinite(b)}) v.push_back(p);
  }
  return v;
}

}  // namespace sl::modern
