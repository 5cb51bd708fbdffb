#include "modern/silhouettes.h"

#include <cstdlib>
#include <map>
#include <tuple>

#include "core/base/errors.h"

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
  for (unsigned index : mesh.indices)
    if (index >= mesh.positions.size())
      throw InputError("object '" + objectName + "': index " + std::to_string(index) +
                       " beyond its " + std::to_string(mesh.positions.size()) + " positions");
  // Zero-area triangles first: a repeated welded corner, or corners on one line (the cross
  // product of two sides is exactly zero in float).
  for (size_t t = 0; t + 2 < mesh.indices.size(); t += 3) {
    const glm::uvec3 tri(id[mesh.indices[t]], id[mesh.indices[t + 1]], id[mesh.indices[t + 2]]);
    const glm::vec3 p0 = out.positions[tri[0]];
    const glm::vec3 n = glm::cross(out.positions[tri[1]] - p0, out.positions[tri[2]] - p0);
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[2] == tri[0] || n == glm::vec3(0.0f)) {
      ++out.droppedDegenerate;
      continue;
    }
    out.triangles.push_back(tri);
  }
  // Directed edge (a, b) -> the triangles that walk it. Closed 2-manifold: each directed edge
  // is walked by exactly one triangle and its twin (b, a) by exactly one other.
  std::map<std::pair<unsigned, unsigned>, std::vector<unsigned>> directed;
  for (size_t t = 0; t < out.triangles.size(); ++t)
    for (int e = 0; e < 3; ++e)
      directed[{out.triangles[t][e], out.triangles[t][(e + 1) % 3]}].push_back(unsigned(t));
  out.closed = !out.triangles.empty();
  for (const auto& [edge, walkers] : directed) {
    auto twin = directed.find({edge.second, edge.first});
    const bool paired = walkers.size() == 1 && twin != directed.end() && twin->second.size() == 1;
    if (!paired) {
      out.closed = false;
      continue;
    }
    if (edge.first < edge.second)  // each undirected edge once, from its a < b half
      out.edges.push_back({edge.first, edge.second, walkers[0], twin->second[0]});
  }
  return out;
}

SceneCasters collectCasters(const Scene& scene) {
  SceneCasters out;
  for (const Object& o : scene.objects) {
    if (!o.castsShadow) continue;
    EdgeAdjacency adjacency = buildEdgeAdjacency(*o.mesh, o.name);
    if (adjacency.triangles.empty()) continue;  // nothing left that could block a ray
    if (adjacency.closed) {
      ++out.closed;
    } else {
      ++out.open;
      out.openNames += (out.openNames.empty() ? "" : ", ") + o.name;
    }
    out.casters.push_back({&o, std::move(adjacency)});
  }
  return out;
}

const char* const kOpenMeshTwoSidedDeviation =
    "DEVIATION (Chan §3.1, Everitt–Kilgard §\"Shadow volume construction\": blockers must be "
    "closed): an open mesh is taken as the closed, zero-thickness solid made of both faces of "
    "each of its triangles. Each triangle then has one light-facing face (front cap) and one "
    "facing away (back cap at infinity), and the silhouette is the sum of every light-facing "
    "face's boundary loop: edges walked both ways cancel, so what remains is every boundary edge "
    "(always a potential silhouette: its two faces are the two sides of one triangle) once, and "
    "every edge where the surface folds over as seen from the light (one neighbour faces the "
    "light, the other away) twice, as the solid has two sheets there. The volume is closed, so "
    "z-fail counting is exact; the same works for non-manifold edges.";

Silhouette findSilhouette(const EdgeAdjacency& mesh, const glm::vec3& light) {
  Silhouette s;
  s.facesLight.resize(mesh.triangles.size());
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    const glm::vec3 p0 = mesh.positions[tri[0]];
    const glm::vec3 n = glm::cross(mesh.positions[tri[1]] - p0, mesh.positions[tri[2]] - p0);
    s.facesLight[t] = glm::dot(n, light - p0) > 0.0f;
  }
  if (mesh.closed) {
    // Brute force over every edge (Chan §4.2 step 2).
    for (const EdgeAdjacency::Edge& e : mesh.edges) {
      const bool firstFaces = s.facesLight[e.first];
      if (firstFaces == s.facesLight[e.second]) continue;
      // Orient the edge as it runs in its light-facing triangle.
      if (firstFaces)
        s.edges.emplace_back(e.a, e.b);
      else
        s.edges.emplace_back(e.b, e.a);
      s.quads.push_back(1);
    }
    return s;
  }
  // Open mesh (see the DEVIATION in silhouettes.h): the sum of the boundary loops of every
  // triangle's light-facing face, as a signed count per undirected edge (+1 for a -> b, a < b).
  s.twoSided = true;
  std::map<std::pair<unsigned, unsigned>, int> walked;
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    const glm::uvec3 facing = s.facesLight[t] ? tri : glm::uvec3(tri[0], tri[2], tri[1]);
    for (int e = 0; e < 3; ++e) {
      const unsigned a = facing[e], b = facing[(e + 1) % 3];
      if (a < b)
        ++walked[{a, b}];
      else
        --walked[{b, a}];
    }
  }
  for (const auto& [edge, count] : walked) {
    if (count == 0) continue;
    s.edges.push_back(count > 0 ? edge : std::make_pair(edge.second, edge.first));
    s.quads.push_back(std::abs(count));
  }
  return s;
}

std::vector<glm::vec4> buildShadowVolume(const EdgeAdjacency& mesh, const Silhouette& silhouette,
                                         const glm::vec3& light) {
  std::vector<glm::vec4> v;
  v.reserve(mesh.triangles.size() * (silhouette.twoSided ? 6 : 3) + silhouette.edges.size() * 6);
  const auto finite = [&](unsigned i) { return glm::vec4(mesh.positions[i], 1.0f); };
  // A point at infinity in the direction away from the light (Everitt–Kilgard, w = 0).
  const auto infinite = [&](unsigned i) { return glm::vec4(mesh.positions[i] - light, 0.0f); };
  for (size_t t = 0; t < mesh.triangles.size(); ++t) {
    const glm::uvec3& tri = mesh.triangles[t];
    if (!silhouette.twoSided) {
      for (int k = 0; k < 3; ++k)
        v.push_back(silhouette.facesLight[t] ? finite(tri[k]) : infinite(tri[k]));
      continue;
    }
    // Two-sided: the light-facing face at w = 1 (in the mesh's own corner order when it is the
    // mesh's front face, so that its depth is bit-identical to the camera pass's) and the face
    // turned away at infinity.
    const glm::uvec3 reversed(tri[0], tri[2], tri[1]);
    const glm::uvec3& front = silhouette.facesLight[t] ? tri : reversed;
    const glm::uvec3& back = silhouette.facesLight[t] ? reversed : tri;
    for (int k = 0; k < 3; ++k) v.push_back(finite(front[k]));
    for (int k = 0; k < 3; ++k) v.push_back(infinite(back[k]));
  }
  // Side quads: for the edge a -> b of a light-facing triangle, (b, a, a_inf, b_inf) faces away
  // from that triangle's interior, i.e. out of the volume.
  for (size_t e = 0; e < silhouette.edges.size(); ++e) {
    const auto [a, b] = silhouette.edges[e];
    for (int q = 0; q < silhouette.quads[e]; ++q) {
      for (const glm::vec4& p : {finite(b), finite(a), infinite(a)}) v.push_back(p);
      for (const glm::vec4& p : {finite(b), infinite(a), infinite(b)}) v.push_back(p);
    }
  }
  return v;
}

}  // namespace sl::modern
