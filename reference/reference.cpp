// reference.hard and reference.soft — ray-traced visibility, the ground truth of every error
// figure (Chan 2004 §4.5 compares smoothies against ray-traced soft shadows the same way).
//
// Passes:
//   1. rasteriseSurfacePoints — GL: world position, normals, object per camera pixel
//                               (reference/surface_buffer.cpp)
//   2. buildOcclusionScene    — Embree 3: the casters (Object::castsShadow) as triangle meshes
//   3. castShadowRays         — per pixel, shadow rays from the surface point to the light:
//                               hard: one ray to the point light; soft: stratified rays to a
//                               disk of SpotLight::radius facing the point (the silhouette of
//                               the spherical light), split in two independent halves
//   4. shadeFromVisibility    — ambient + visibility * direct, the lighting of
//                               modern/shaders/hw_shadow.frag.glsl, for figures
//
// With --param pixel=area (the pixel-integrated form: the antialiasing metric's truth,
// docs/error.md) pass 3 becomes:
//   3. integratePixelArea     — for each of the N x N sub-pixel strata (their centres: an
//                               ordered-grid supersampling of the pixel's box filter, i.e.
//                               the mean visibility over the part of the pixel's area that
//                               shows the surface its centre sees, sampleShowsCentreSurface):
//      3a. SurfaceRasteriser::rasterise — pass 1 again with the projection shifted by the
//                               stratum's offset: each sample has its own surface point
//      3b. castHardShadowRays / castSoftShadowRaysFromSubsample — the rays of pass 3 from
//                               those points; hard: one ray per sample, averaged; soft: the
//                               light's strata dealt out to the sub-pixel points
// Pass 1's pixel-centre points still give the shading, the direct-light region and the pixel
// categories (kPixelCategoriesPass), so the scored pixels are the same in both forms.
// The passes are declared once in referencePasses().
#include "reference/reference.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>
#include <memory>
#include <optional>
#include <random>
#include <thread>

#include "core/base/errors.h"
#include "core/technique/passes.h"
#include "reference/surface_buffer.h"

namespace sl::reference {
namespace {

constexpr float kPi = 3.14159265358979f;
constexpr float kSpecularExponent = 32.0f;  // as in hw_shadow.frag.glsl
constexpr int kMinSoftRays = 4;
constexpr int kMaxSoftRays = 16384;
constexpr unsigned kSoftSeed = 20011u;  // fixed: the reference is deterministic
constexpr int kRowsPerTask = 4;         // work unit of the worker threads
// pixel=area, soft: the seed of the per-pixel dealing of light strata to sub-pixel points.
constexpr unsigned long long kDealSeed = 0x9E3779B97F4A7C15ull;

// The passes of reference.hard (soft = false) and reference.soft, declared once: none is a
// paper's, they are ours (the ground truth). The CPU passes are timed like the GL ones.
PassTable referencePasses(bool soft) {
  // The paper section of the ray passes: none, they are ours.
  const std::string raySection =
      "ours (the ground truth): Embree shadow rays from each surface point to the light (point "
      "light), or stratified over the light's sphere (reference.soft)";
  const std::string rays = soft ? "soft shadow rays" : "shadow rays";
  return {
      {.id = "1",
       .name = "surface points (GL)",
       .reference = "ours (the ground truth, no paper's pass): the camera view rasterised to "
                    "world positions and normals, the rays' start points",
       .writes = {{.name = "surface-normals", .caption = "surface normals from the GL pass"}},
       .shaders = {"surface-points"}},
      // Its buffers come from pass 1's points; the error metrics find them by name
      // (kDirectLightRegionPass = "2-direct-light-region", kPixelCategoriesPass).
      {.id = "2",
       .name = "build occluder BVH (Embree)",
       .reference = "ours (the ground truth): Embree's BVH over every caster",
       .writes = {{.name = "direct-light-region", .caption = "surface points the light can reach"},
                  {.name = "pixel-categories",
                   .caption = "pixel categories of the error metrics: white = scored (faces the "
                              "light inside its frustum), light grey = faces away from the light "
                              "(terminator, not scored), dark grey = outside the light's "
                              "frustum, black = no receiver"}}},
      {.id = "3",
       .name = rays + " (Embree)",
       .reference = raySection,
       .writes = {{.name = "visibility", .caption = "ray-traced visibility"}}},
      // pixel=area: pass 3 as 3a and 3b, once per sub-pixel position, interleaved.
      {.id = "3a",
       .name = "sub-pixel surface points",  // + " (GL, NxN)"
       .reference =
           "ours (the ground truth): the surface points of each sub-pixel position (pixel = area)",
       .shaders = {"surface-points"}},
      {.id = "3b",
       .name = rays,  // + " from NxN sub-pixel points (Embree)"
       .reference = raySection,
       .writes = {{.name = "visibility", .caption = "ray-traced visibility"}}},
      {.id = "4",
       .name = "shade",
       .reference = "ours (the ground truth): the modern techniques' lighting "
                    "(modern/shaders/lighting.glsl) x the rays' visibility"},
  };
}

const PassTable& passTable(bool soft) {
  static const PassTable hard = referencePasses(false);
  static const PassTable softTable = referencePasses(true);
  return soft ? softTable : hard;
}

struct DeviceDeleter {
  void operator()(RTCDevice d) const { rtcReleaseDevice(d); }
};
struct SceneDeleter {
  void operator()(RTCScene s) const { rtcReleaseScene(s); }
};
using DevicePtr = std::unique_ptr<std::remove_pointer_t<RTCDevice>, DeviceDeleter>;
using ScenePtr = std::unique_ptr<std::remove_pointer_t<RTCScene>, SceneDeleter>;

struct Occluders {
  DevicePtr device;
  ScenePtr scene;
};

// Pass 2: every caster's triangles in world space in one Embree scene (robust mode: rays that
// graze an edge shared by two triangles are not let through).
Occluders buildOcclusionScene(const Scene& scene) {
  Occluders o;
  o.device.reset(rtcNewDevice("threads=2"));
  if (!o.device) throw GlError("Embree: cannot create a device");
  o.scene.reset(rtcNewScene(o.device.get()));
  rtcSetSceneFlags(o.scene.get(), RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(o.scene.get(), RTC_BUILD_QUALITY_HIGH);
  for (const Object& object : scene.objects) {
    if (!object.castsShadow || !object.mesh || object.mesh->indices.empty()) continue;
    const Mesh& mesh = *object.mesh;
    RTCGeometry geometry = rtcNewGeometry(o.device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.positions.size()));
    for (size_t i = 0; i < mesh.positions.size(); ++i) {
      const glm::vec3 w = glm::vec3(object.model * glm::vec4(mesh.positions[i], 1.0f));
      vertices[3 * i] = w.x;
      vertices[3 * i + 1] = w.y;
      vertices[3 * i + 2] = w.z;
    }
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.indices.size() / 3));
    std::copy(mesh.indices.begin(), mesh.indices.begin() + (mesh.indices.size() / 3) * 3, indices);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(o.scene.get(), geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(o.scene.get());
  if (rtcGetDeviceError(o.device.get()) != RTC_ERROR_NONE)
    throw GlError("Embree: building the occluder scene failed");
  return o;
}

// True when the segment from `origin` to `target` crosses a caster.
bool occluded(RTCScene scene, const glm::vec3& origin, const glm::vec3& target) {
  const glm::vec3 d = target - origin;
  const float length = glm::length(d);
  if (!(length > 0.0f)) return false;
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay ray;
  ray.org_x = origin.x;
  ray.org_y = origin.y;
  ray.org_z = origin.z;
  ray.dir_x = d.x / length;
  ray.dir_y = d.y / length;
  ray.dir_z = d.z / length;
  ray.tnear = 0.0f;
  ray.tfar = length;
  ray.time = 0.0f;
  ray.mask = 0xFFFFFFFFu;
  ray.id = 0;
  ray.flags = 0;
  rtcOccluded1(scene, &context, &ray);
  return ray.tfar < 0.0f;  // Embree sets tfar = -inf on a hit
}

// Inside the light's square frustum (cone x cone), in front of the light.
bool insideLightFrustum(const SpotLight& light, const glm::mat4& view, const glm::vec3& p) {
  const glm::vec3 l = glm::vec3(view * glm::vec4(p, 1.0f));
  if (l.z >= 0.0f) return false;
  const float t = std::tan(glm::radians(0.5f * light.coneDegrees));
  return std::fabs(l.x) <= -l.z * t && std::fabs(l.y) <= -l.z * t;
}

// The surface at `s` faces the light: its geometric (triangle) normal points to the light's
// side. Where it does not, the lighting term is 0 whatever the visibility (the terminator and
// the self-shadowed side of a caster).
bool facesLight(const SpotLight& light, const SurfacePoint& s) {
  return glm::dot(s.geometricNormal, light.position - s.position) > 0.0f;
}

// The error definition's category of a pixel-centre surface point (reference.h
// kPixelCategoriesPass).
float pixelCategory(const Scene& scene, const glm::mat4& lightViewMatrix, const SurfacePoint& s) {
  if (s.object < 0 || !scene.objects[s.object].receivesShadow) return kCategoryNoReceiver;
  if (!insideLightFrustum(scene.light, lightViewMatrix, s.position)) return kCategoryOutsideLight;
  return facesLight(scene.light, s) ? kCategoryScored : kCategoryFacesAway;
}

// pixel=area: whether a sub-pixel sample `sample` shows the surface the pixel centre `centre`
// sees (reference.h kSameSurfacePixelFootprints): the same object, near the centre's tangent
// plane, facing the light inside its frustum (the terminator rule of the scored pixels).
bool sampleShowsCentreSurface(const Scene& scene, const glm::mat4& lightViewMatrix,
                              const SurfacePoint& centre, const SurfacePoint& sample,
                              float pixelFootprintPerDistance) {
  if (sample.object != centre.object) return false;
  if (pixelCategory(scene, lightViewMatrix, sample) != kCategoryScored) return false;
  const float footprint =
      pixelFootprintPerDistance * glm::length(centre.position - scene.camera.position);
  return std::fabs(glm::dot(sample.position - centre.position, centre.geometricNormal)) <=
         kSameSurfacePixelFootprints * footprint;
}

// The world size of one pixel per unit of distance from the camera (vertical field of view
// over the window's rows; pixels are square).
float pixelFootprintPerDistance(const Scene& scene, const RenderParams& params) {
  return 2.0f * std::tan(glm::radians(0.5f * scene.camera.fovyDegrees)) / float(params.height);
}

// Runs body(y) for every row on all cores (std::thread; the rows are handed out in chunks).
template <class Body>
void forEachRow(int height, Body body) {
  const unsigned workers = std::max(1u, std::min(std::thread::hardware_concurrency(), 16u));
  std::atomic<int> next{0};
  auto work = [&] {
    for (int start; (start = next.fetch_add(kRowsPerTask)) < height;)
      for (int y = start; y < std::min(height, start + kRowsPerTask); ++y) body(y);
  };
  std::vector<std::thread> threads;
  for (unsigned i = 1; i < workers; ++i) threads.emplace_back(work);
  work();
  for (std::thread& t : threads) t.join();
}

struct Visibility {
  Image mask;           // 1 channel
  double noiseRms = 0;  // soft only: RMS estimated standard error over penumbra pixels
  double noiseMax = 0;  // soft only: largest per-pixel estimated standard error
  long long penumbraPixels = 0;
  long long rays = 0;
};

// The shadow-ray origin: the surface point moved off the surface along its geometric normal.
glm::vec3 rayOrigin(const SurfacePoint& s, float offset) {
  return s.position + offset * s.geometricNormal;
}

float sceneDiagonal(const Scene& scene) {
  const Bounds b = sceneBounds(scene);
  return b.empty() ? 1.0f : std::max(glm::length(b.hi - b.lo), 1e-30f);
}

// Pass 3 (hard): one shadow ray per pixel to the point light.
Visibility castHardShadowRays(const Scene& scene, const std::vector<SurfacePoint>& points,
                              const RenderParams& params, RTCScene occluders) {
  Visibility v;
  v.mask = Image(params.width, params.height, 1, kNoGeometryVisibility);
  const float offset = kRayOffsetPerSceneDiagonal * sceneDiagonal(scene);
  const glm::mat4 view = lightView(scene.light);
  std::atomic<long long> rays{0};
  forEachRow(params.height, [&](int y) {
    long long count = 0;
    for (int x = 0; x < params.width; ++x) {
      const SurfacePoint& s = points[size_t(y) * params.width + x];
      if (s.object < 0 || !scene.objects[s.object].receivesShadow) continue;
      if (!insideLightFrustum(scene.light, view, s.position)) continue;
      ++count;
      v.mask.at(x, y) =
          occluded(occluders, rayOrigin(s, offset), scene.light.position) ? 0.0f : 1.0f;
    }
    rays += count;
  });
  v.rays = rays;
  return v;
}

// A point of the unit disk from a point of the unit square (Shirley–Chiu concentric map: keeps
// the strata of the square compact and of equal area on the disk).
glm::vec2 concentricDisk(float u, float v) {
  const float a = 2.0f * u - 1.0f, b = 2.0f * v - 1.0f;
  if (a == 0.0f && b == 0.0f) return {0.0f, 0.0f};
  float r, phi;
  if (std::fabs(a) > std::fabs(b)) {
    r = a;
    phi = (kPi / 4.0f) * (b / a);
  } else {
    r = b;
    phi = (kPi / 2.0f) - (kPi / 4.0f) * (a / b);
  }
  return {r * std::cos(phi), r * std::sin(phi)};
}

// The two independent stratified estimates A and B (n x n strata each) of the visible fraction
// of the light's disk from `origin` (castSoftShadowRays' comment); none when the origin is the
// light's centre.
std::optional<std::array<float, 2>> softVisibilityHalves(const SpotLight& light,
                                                         const glm::vec3& origin, int n,
                                                         std::mt19937& rng, RTCScene occluders) {
  std::uniform_real_distribution<float> jitter(0.0f, 1.0f);
  const glm::vec3 toLight = light.position - origin;
  const float distance = glm::length(toLight);
  if (!(distance > 0.0f)) return std::nullopt;
  // An orthonormal frame of the disk facing the point.
  const glm::vec3 w = toLight / distance;
  const glm::vec3 helper = std::fabs(w.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const glm::vec3 e1 = glm::normalize(glm::cross(w, helper));
  const glm::vec3 e2 = glm::cross(w, e1);
  int litHalf[2] = {0, 0};
  for (int half = 0; half < 2; ++half)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        const glm::vec2 d = concentricDisk((i + jitter(rng)) / n, (j + jitter(rng)) / n);
        const glm::vec3 target = light.position + light.radius * (d.x * e1 + d.y * e2);
        if (!occluded(occluders, origin, target)) ++litHalf[half];
      }
  return std::array<float, 2>{float(litHalf[0]) / float(n * n), float(litHalf[1]) / float(n * n)};
}

// Pass 3 (soft): the spherical light of radius r seen from a surface point is a disk of
// radius r facing the point (its silhouette; for r much smaller than the distance, the disk
// and the sphere's solid angle agree to O((r/d)^2)). Its visible fraction is estimated with
// `rays` stratified samples: two independent jittered estimates A and B on an n x n grid of
// equal-area strata each (n*n = rays/2); the mask is (A + B) / 2 and |A - B| / 2 estimates its
// standard error per pixel (E[(A-B)^2]/4 = Var((A+B)/2) for independent, equally distributed
// A and B).
Visibility castSoftShadowRays(const Scene& scene, const std::vector<SurfacePoint>& points,
                              const RenderParams& params, RTCScene occluders, int rays) {
  Visibility v;
  v.mask = Image(params.width, params.height, 1, kNoGeometryVisibility);
  const int n = std::max(1, int(std::lround(std::sqrt(rays / 2.0))));
  const float offset = kRayOffsetPerSceneDiagonal * sceneDiagonal(scene);
  const glm::mat4 view = lightView(scene.light);
  const SpotLight& light = scene.light;
  std::vector<double> rowNoiseSquares(params.height, 0.0), rowNoiseMax(params.height, 0.0);
  std::vector<long long> rowPenumbra(params.height, 0), rowRays(params.height, 0);
  forEachRow(params.height, [&](int y) {
    std::mt19937 rng(kSoftSeed + unsigned(y));  // per row: the result is thread-count independent
    for (int x = 0; x < params.width; ++x) {
      const SurfacePoint& s = points[size_t(y) * params.width + x];
      if (s.object < 0 || !scene.objects[s.object].receivesShadow) continue;
      if (!insideLightFrustum(light, view, s.position)) continue;
      const std::optional<std::array<float, 2>> halves =
          softVisibilityHalves(light, rayOrigin(s, offset), n, rng, occluders);
      if (!halves) continue;
      const float a = (*halves)[0], b = (*halves)[1];
      const float value = 0.5f * (a + b);
      v.mask.at(x, y) = value;
      rowRays[y] += 2LL * n * n;
      if (value > 0.0f && value < 1.0f) {
        const double standardError = 0.5 * std::fabs(a - b);
        rowNoiseSquares[y] += standardError * standardError;
        rowNoiseMax[y] = std::max(rowNoiseMax[y], standardError);
        ++rowPenumbra[y];
      }
    }
  });
  double squares = 0;
  for (int y = 0; y < params.height; ++y) {
    squares += rowNoiseSquares[y];
    v.noiseMax = std::max(v.noiseMax, rowNoiseMax[y]);
    v.penumbraPixels += rowPenumbra[y];
    v.rays += rowRays[y];
  }
  v.noiseRms = v.penumbraPixels > 0 ? std::sqrt(squares / double(v.penumbraPixels)) : 0.0;
  return v;
}

// Defined with pass 1's helpers below; every sub-pixel surface buffer is repaired the same way.
void repairNormals(std::vector<SurfacePoint>& points, const glm::vec3& eye);

// Pass 3b (soft, pixel area): the rays of castSoftShadowRays, but each pixel's 2 n^2 light
// strata are dealt out to its S sub-pixel points: stratum k of half h goes to sub-pixel point
// (k + o_h) mod S, with o_h a per-pixel, per-half offset drawn uniformly from [0, S). Every
// stratum is used once per half and every sub-pixel point gets n^2 / S of them; averaged over
// o_h each stratum meets every sub-pixel point equally often, so each half is an unbiased
// estimate of the visible fraction over pixel area x light disk, and the two halves stay
// independent (their offsets and jitters are), so |A - B| / 2 still estimates the standard
// error. Called once per sub-pixel point s with that point's surface buffer; adds the lit
// rays of each half to litHalves[pixel][half] (sub-samples that see no geometry, a
// non-receiver or a point outside the frustum count all their rays as lit, the conventions
// of reference.h). At a scored pixel (`restricted[p]`) a sub-pixel point that does not show the
// centre's surface (sampleShowsCentreSurface) casts nothing and its strata are not counted:
// castHalves[p] counts the strata each half did use, and the estimate is lit / cast over the
// points that show the surface (a ratio estimator; the dealing stays random per pixel).
void castSoftShadowRaysFromSubsample(const Scene& scene, const std::vector<SurfacePoint>& points,
                                     const std::vector<SurfacePoint>& centre,
                                     const std::vector<char>& restricted,
                                     const RenderParams& params, RTCScene occluders, int n,
                                     int subsamples, int subsample,
                                     std::vector<std::array<int, 2>>& litHalves,
                                     std::vector<std::array<int, 2>>& castHalves,
                                     std::atomic<long long>& rays) {
  const float offset = kRayOffsetPerSceneDiagonal * sceneDiagonal(scene);
  const float footprintPerDistance = pixelFootprintPerDistance(scene, params);
  const glm::mat4 view = lightView(scene.light);
  const SpotLight& light = scene.light;
  const int strata = n * n;
  forEachRow(params.height, [&](int y) {
    // Per row and sub-pixel point: the result is thread-count independent.
    std::seed_seq seed{kSoftSeed, unsigned(y), unsigned(subsample)};
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> jitter(0.0f, 1.0f);
    long long count = 0;
    for (int x = 0; x < params.width; ++x) {
      const size_t p = size_t(y) * params.width + x;
      int mine[2];
      for (int half = 0; half < 2; ++half) {
        // splitmix64 of (pixel, half): the per-pixel offset o_h of the dealing.
        unsigned long long z = kDealSeed * (2 * p + half + 1);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        z ^= z >> 31;
        const int o = int(z % unsigned(subsamples));
        // Strata k in [0, n^2) with (k + o) mod S == subsample.
        const int first = ((subsample - o) % subsamples + subsamples) % subsamples;
        mine[half] = first < strata ? (strata - 1 - first) / subsamples + 1 : 0;
        const SurfacePoint& s = points[p];
        if (restricted[p] &&
            !sampleShowsCentreSurface(scene, view, centre[p], s, footprintPerDistance))
          continue;  // another surface, or this one facing away: not this pixel's truth
        castHalves[p][half] += mine[half];
        if (s.object < 0 || !scene.objects[s.object].receivesShadow ||
            !insideLightFrustum(light, view, s.position)) {
          litHalves[p][half] += mine[half];  // lit by convention
          continue;
        }
        const glm::vec3 origin = rayOrigin(s, offset);
        const glm::vec3 toLight = light.position - origin;
        const float distance = glm::length(toLight);
        if (!(distance > 0.0f)) {
          litHalves[p][half] += mine[half];
          continue;
        }
        const glm::vec3 w = toLight / distance;
        const glm::vec3 helper = std::fabs(w.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
        const glm::vec3 e1 = glm::normalize(glm::cross(w, helper));
        const glm::vec3 e2 = glm::cross(w, e1);
        for (int k = first; k < strata; k += subsamples) {
          const int i = k / n, j = k % n;
          const glm::vec2 d = concentricDisk((i + jitter(rng)) / n, (j + jitter(rng)) / n);
          const glm::vec3 target = light.position + light.radius * (d.x * e1 + d.y * e2);
          if (!occluded(occluders, origin, target)) ++litHalves[p][half];
          ++count;
        }
      }
    }
    rays += count;
  });
}

// The centre of sub-pixel stratum (i, j) of an N x N grid, relative to the pixel centre.
glm::vec2 stratumOffset(int i, int j, int n) {
  return {(float(i) + 0.5f) / float(n) - 0.5f, (float(j) + 0.5f) / float(n) - 0.5f};
}

// Pass 3 (pixel area): the mean visibility over the N x N sub-pixel strata (see the header
// comment); the sub-pixel surface buffers are made and used one at a time. At a scored pixel
// (the centre's category, kPixelCategoriesPass) only the samples that show the centre's surface
// count (sampleShowsCentreSurface); when none does (a sliver of surface between the strata'
// centres), the pixel centre's own point visibility stands in.
Visibility integratePixelArea(const Scene& scene, const RenderParams& params, RTCScene occluders,
                              bool soft, int perSide, int softRays,
                              const std::vector<SurfacePoint>& centre, Passes& passes) {
  SurfaceRasteriser rasteriser(scene, params);
  const int subsamples = perSide * perSide;
  const size_t pixels = size_t(params.width) * params.height;
  const int n = std::max(1, int(std::lround(std::sqrt(softRays / 2.0))));
  const glm::mat4 view = lightView(scene.light);
  const float footprintPerDistance = pixelFootprintPerDistance(scene, params);
  std::vector<char> restricted(pixels, 0);
  for (size_t p = 0; p < pixels; ++p)
    restricted[p] = pixelCategory(scene, view, centre[p]) == kCategoryScored;
  std::vector<double> sum(pixels, 0.0);
  std::vector<int> counted(pixels, 0);
  std::vector<std::array<int, 2>> litHalves(pixels, {0, 0}), castHalves(pixels, {0, 0});
  std::atomic<long long> softRayCount{0};
  long long hardRays = 0;
  const std::string grid = std::to_string(perSide) + "x" + std::to_string(perSide);
  for (int i = 0; i < perSide; ++i)
    for (int j = 0; j < perSide; ++j) {
      std::vector<SurfacePoint> points;
      const auto rasterise = [&] {
        points = rasteriser.rasterise(stratumOffset(i, j, perSide));
        repairNormals(points, scene.camera.position);
      };
      const auto castRays = [&] {
        if (soft) {
          castSoftShadowRaysFromSubsample(scene, points, centre, restricted, params, occluders, n,
                                          subsamples, i * perSide + j, litHalves, castHalves,
                                          softRayCount);
          return;
        }
        const Visibility v = castHardShadowRays(scene, points, params, occluders);
        for (size_t p = 0; p < pixels; ++p) {
          if (restricted[p] &&
              !sampleShowsCentreSurface(scene, view, centre[p], points[p], footprintPerDistance))
            continue;
          sum[p] += v.mask.data[p];
          ++counted[p];
        }
        hardRays += v.rays;
      };
      // Passes 3a and 3b, a piece of each per sub-pixel position: the first position runs
      // them, the others resume them (one entry each, its time the sum of its pieces).
      if (i == 0 && j == 0) {
        passes.run("3a", rasterise, {}, " (GL, " + grid + ")");
        passes.run("3b", castRays, {}, " from " + grid + " sub-pixel points (Embree)");
      } else {
        passes.resume("3a", rasterise);
        passes.resume("3b", castRays);
      }
    }
  // The scored pixels none of whose samples showed the centre's surface: the centre's own rays.
  const float offset = kRayOffsetPerSceneDiagonal * sceneDiagonal(scene);
  long long fallbacks = 0;
  passes.resume("3b", [&] {
    for (size_t p = 0; p < pixels; ++p) {
      if (!restricted[p]) continue;
      if (!soft && counted[p] == 0) {
        sum[p] =
            occluded(occluders, rayOrigin(centre[p], offset), scene.light.position) ? 0.0 : 1.0;
        counted[p] = 1;
        ++hardRays;
        ++fallbacks;
      } else if (soft && (castHalves[p][0] == 0 || castHalves[p][1] == 0)) {
        std::seed_seq seed{kSoftSeed, unsigned(p), unsigned(subsamples)};
        std::mt19937 rng(seed);
        const auto halves =
            softVisibilityHalves(scene.light, rayOrigin(centre[p], offset), n, rng, occluders);
        const int strata = n * n;
        castHalves[p] = {strata, strata};
        litHalves[p] = {halves ? int(std::lround((*halves)[0] * strata)) : strata,
                        halves ? int(std::lround((*halves)[1] * strata)) : strata};
        softRayCount += 2LL * strata;
        ++fallbacks;
      }
    }
  });
  passes.frame().counters["area_centre_fallback_pixels"] = double(fallbacks);
  Visibility v;
  v.mask = Image(params.width, params.height, 1, kNoGeometryVisibility);
  if (!soft) {
    for (size_t p = 0; p < pixels; ++p)
      v.mask.data[p] = counted[p] > 0 ? float(sum[p] / double(counted[p])) : kNoGeometryVisibility;
    v.rays = hardRays;
    return v;
  }
  double squares = 0;
  for (size_t p = 0; p < pixels; ++p) {
    const float a = float(litHalves[p][0]) / float(castHalves[p][0]);
    const float b = float(litHalves[p][1]) / float(castHalves[p][1]);
    const float value = 0.5f * (a + b);
    v.mask.data[p] = value;
    if (value > 0.0f && value < 1.0f) {
      const double standardError = 0.5 * std::fabs(a - b);
      squares += standardError * standardError;
      v.noiseMax = std::max(v.noiseMax, standardError);
      ++v.penumbraPixels;
    }
  }
  v.noiseRms = v.penumbraPixels > 0 ? std::sqrt(squares / double(v.penumbraPixels)) : 0.0;
  v.rays = softRayCount;
  return v;
}

// Pass 4: OpenGL spotlight lighting split into ambient + visibility * direct, exactly the terms
// of modern/shaders/hw_shadow.frag.glsl (glspec121 §2.13.1).
Image shadeFromVisibility(const Scene& scene, const std::vector<SurfacePoint>& points,
                          const Image& visibility) {
  Image color(visibility.width, visibility.height, 3, 0.0f);
  const SpotLight& l = scene.light;
  const glm::vec3 spotDirection = glm::normalize(l.target - l.position);
  const float cosCutoff = std::cos(glm::radians(0.5f * l.coneDegrees));
  for (size_t p = 0; p < points.size(); ++p) {
    const SurfacePoint& s = points[p];
    if (s.object < 0) continue;
    const Object& o = scene.objects[s.object];
    const glm::vec3 n = s.shadingNormal;
    const glm::vec3 toLight = glm::normalize(l.position - s.position);
    const float spot = glm::dot(-toLight, spotDirection) >= cosCutoff ? 1.0f : 0.0f;
    const float diffuse = std::max(glm::dot(n, toLight), 0.0f);
    const glm::vec3 toEye = glm::normalize(scene.camera.position - s.position);
    const float specular =
        diffuse > 0.0f ? std::pow(std::max(glm::dot(n, glm::normalize(toLight + toEye)), 0.0f),
                                  kSpecularExponent)
                       : 0.0f;
    const glm::vec3 direct =
        spot * l.color * (o.diffuse * diffuse + glm::vec3(o.specular) * specular);
    const glm::vec3 ambient = l.ambient * l.color * o.diffuse;
    const glm::vec3 c = ambient + visibility.data[p] * direct;
    for (int k = 0; k < 3; ++k) color.data[p * 3 + k] = std::isfinite(c[k]) ? c[k] : 0.0f;
  }
  return color;
}

// Surface points with unusable normals (a mesh without normals, a zero-area triangle) get the
// other normal, or the direction to the camera: never a NaN ray.
void repairNormals(std::vector<SurfacePoint>& points, const glm::vec3& eye) {
  auto usable = [](const glm::vec3& n) {
    return std::isfinite(n.x) && std::isfinite(n.y) && std::isfinite(n.z) && glm::length(n) > 0.5f;
  };
  for (SurfacePoint& s : points) {
    if (s.object < 0) continue;
    if (!usable(s.geometricNormal))
      s.geometricNormal =
          usable(s.shadingNormal) ? s.shadingNormal : glm::normalize(eye - s.position);
    if (!usable(s.shadingNormal)) s.shadingNormal = s.geometricNormal;
    if (!usable(s.geometricNormal)) s.geometricNormal = s.shadingNormal = glm::vec3(0, 1, 0);
  }
}

// The --params of the references, declared once (Technique::params).
ParamSpec raysParam() {
  return integerParam("rays", kDefaultSoftRays, kMinSoftRays, kMaxSoftRays,
                      "stratified rays per pixel towards the spherical light");
}
ParamSpec pixelParam() {
  return choiceParam(kPixelParam, kPixelCentre, {kPixelCentre, kPixelArea},
                     "visibility at the pixel centre, or integrated over the pixel's area");
}
ParamSpec pixelSamplesParam(bool soft) {
  return integerParam(kPixelSamplesParam,
                      soft ? kDefaultSoftPixelSamplesPerSide : kDefaultHardPixelSamplesPerSide, 1,
                      kMaxPixelSamplesPerSide, "sub-pixel samples per side with pixel=area");
}

Frame renderReference(const Scene& scene, const RenderParams& params, bool soft) {
  const int softRays = soft ? params.integer(raysParam()) : kDefaultSoftRays;
  const bool area = params.text(pixelParam()) == kPixelArea;
  const int perSide = params.integer(pixelSamplesParam(soft));
  Frame frame;
  Passes passes(frame, params, passTable(soft));
  std::vector<SurfacePoint> points;
  passes.run("1", [&] {
    points = rasteriseSurfacePoints(scene, params);
    repairNormals(points, scene.camera.position);
  });
  Occluders occluders;
  passes.run("2", [&] { occluders = buildOcclusionScene(scene); });
  Visibility v;
  if (area) {
    v = integratePixelArea(scene, params, occluders.scene.get(), soft, perSide, softRays, points,
                           passes);
  } else {
    passes.run("3", [&] {
      v = soft ? castSoftShadowRays(scene, points, params, occluders.scene.get(), softRays)
               : castHardShadowRays(scene, points, params, occluders.scene.get());
    });
  }
  passes.run("4", [&] {
    frame.color = shadeFromVisibility(scene, points, v.mask);
    frame.visibility = std::move(v.mask);
  });
  frame.counters["rays"] = double(v.rays);
  frame.counters["ray_offset_world"] = kRayOffsetPerSceneDiagonal * sceneDiagonal(scene);
  if (area) frame.counters["pixel_samples"] = double(perSide * perSide);
  if (soft) {
    const long n = std::max(1L, std::lround(std::sqrt(softRays / 2.0)));
    frame.counters["rays_per_pixel"] = double(2 * n * n);
    frame.counters["penumbra_pixels"] = double(v.penumbraPixels);
    frame.counters["noise_rms_standard_error"] = v.noiseRms;
    frame.counters["noise_max_standard_error"] = v.noiseMax;
  }
  passes.capture("1", "surface-normals", [&] {
    Image normals(params.width, params.height, 3, 0.0f);
    for (size_t p = 0; p < points.size(); ++p)
      if (points[p].object >= 0)
        for (int k = 0; k < 3; ++k)
          normals.data[p * 3 + k] = 0.5f + 0.5f * points[p].shadingNormal[k];
    return normals;
  });
  const glm::mat4 view = lightView(scene.light);
  // Where direct light can arrive: the surface faces the light (geometric normal) inside the
  // light's frustum. Elsewhere the direct term is 0 and visibility does not change the image
  // (second-depth maps rely on this; behind the light, Everitt's techniques force 0).
  passes.capture("2", "direct-light-region", [&] {
    Image region(params.width, params.height, 1, 0.0f);
    for (size_t p = 0; p < points.size(); ++p)
      if (points[p].object >= 0 &&
          glm::dot(points[p].geometricNormal, scene.light.position - points[p].position) > 0.0f &&
          insideLightFrustum(scene.light, view, points[p].position))
        region.data[p] = 1.0f;
    return region;
  });
  // The error definition's pixel categories (docs/error.md), from the same centre points.
  passes.capture("2", "pixel-categories", [&] {
    Image categories(params.width, params.height, 1, kCategoryNoReceiver);
    for (size_t p = 0; p < points.size(); ++p)
      categories.data[p] = pixelCategory(scene, view, points[p]);
    return categories;
  });
  passes.capture(area ? "3b" : "3", "visibility", [&] { return frame.visibility; });
  return frame;
}

}  // namespace

std::vector<Technique> techniques() {
  Technique hard;
  hard.name = "reference.hard";
  hard.paper = "ray traced (Embree 3)";
  hard.summary = "exact point-light visibility: one shadow ray per camera pixel (pixel=area: " +
                 std::to_string(kDefaultHardPixelSamplesPerSide * kDefaultHardPixelSamplesPerSide) +
                 " stratified sub-pixel rays, averaged)";
  hard.params = {pixelParam(), pixelSamplesParam(false)};
  hard.reads = {};  // ray traced: no shadow map, no filter, no colour-encoded depth
  hard.status = "complete";
  hard.needs.profile = Profile::kCore;
  hard.plan.shadowWork = PlanTraits::ShadowWork::kRays;
  hard.passes = passTable(false);
  hard.render = [](GlContext&, const Scene& s, const RenderParams& p) {
    return renderReference(s, p, false);
  };
  Technique soft = hard;
  soft.name = "reference.soft";
  soft.light = Technique::Light::kArea;
  soft.summary = "Monte Carlo visibility of a spherical light of SpotLight::radius, " +
                 std::to_string(kDefaultSoftRays) + " stratified rays per pixel";
  soft.params = {raysParam(), pixelParam(), pixelSamplesParam(true)};
  soft.reads = {};  // ray traced: no shadow map, no filter, no colour-encoded depth
  soft.passes = passTable(true);
  soft.render = [](GlContext&, const Scene& s, const RenderParams& p) {
    return renderReference(s, p, true);
  };
  return {hard, soft};
}

}  // namespace sl::reference
