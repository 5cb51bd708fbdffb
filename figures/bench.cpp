// figures/bench.cpp — `shadowlab bench`: error against run time (issue 8 items 1 and 2).
//
// For each benchmark scene:
//   1. renderReferences  — reference.hard and reference.soft at the bench's window size, and
//                          the shadow-boundary band of each (core/metrics.h boundaryBand)
//   2. measureVariant    — per technique and parameter variant: one context, warm-up frames,
//                          then timed frames (median of the pass-time sums and of each pass)
//                          and the errors of the last frame's visibility mask against both
//                          references (RMSE, max, share above 0.5, the same in the band, leak)
//   3. outputs           — a JSON object per row on stdout, CSV (--csv), one gnuplot plot per
//                          scene (error against time, log axes, Pareto front), claim checks
#include "figures/bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <glm/glm.hpp>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>

#include "apps/registry.h"
#include "core/errors.h"
#include "core/plan.h"
#include "core/scene_library.h"
#include "imaging/imaging.h"
#include "reference/reference.h"

namespace sl::figures {
namespace fs = std::filesystem;

namespace {

// Window sizes: quick keeps the whole run under 2 minutes on two cores; full is the papers'
// 800x600 halved in each direction (llvmpipe fill bounds the run time, DESIGN.md).
constexpr int kQuickWidth = 256, kQuickHeight = 192;
constexpr int kFullWidth = 400, kFullHeight = 300;
constexpr int kQuickWarmup = 1, kQuickTimed = 3;
constexpr int kFullWarmup = 2, kFullTimed = 7;
// The shadow-boundary band: pixels within 2 pixels of a reference edge (where aliasing and
// filtering errors live; everything else is either all right or a gross failure).
constexpr int kBandRadiusPixels = 2;
// A pixel of the reference's umbra "leaks" when the technique shows it more than 20% lit.
constexpr float kLeakThreshold = 0.2f;
// --quick: a variant whose warm-up frame takes longer than this is timed once, not 3 times
// (CSM on llvmpipe takes 0.3-2 s per frame; its median of 3 would take the whole budget).
constexpr double kSlowFrameMs = 250.0;
constexpr int kPlannerShadowMapTexels = 2048;  // the planner scene's map (what a skip saves)

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

bool contains(const std::vector<std::string>& v, const std::string& s) {
  return std::find(v.begin(), v.end(), s) != v.end();
}

bool isReference(const Technique& t) {
  return t.name.rfind("reference.", 0) == 0;
}
bool usesShadowMap(const Technique& t) {
  return !isReference(t) && t.name.find("volumes") == std::string::npos;
}
bool usesFilterFootprint(const Technique& t) {  // Brabec–Seidel §3-4 and their GLSL twins
  return t.name == "legacy.pcf" || t.name == "legacy.fast-pcf" || t.name == "modern.pcf" ||
         t.name == "modern.fast-pcf";
}
// Techniques whose result approximates an area light (the soft reference is their truth).
bool approximatesSoftShadows(const Technique& t) {
  return t.name.find("smoothie") != std::string::npos || t.name == "reference.soft";
}

// The values swept for each --param key a technique may declare (only declared keys are
// swept; a value a technique rejects becomes a row with its InputError as the status).
struct ParamAxis {
  std::string key;
  std::vector<std::string> quick, full;
};
const std::vector<ParamAxis>& paramAxes() {
  static const std::vector<ParamAxis> kAxes = {
      {"order", {"4"}, {"4", "8", "32", "64"}},       // CSM truncation order M
      {"blur", {"0"}, {"0", "5", "7"}},               // CSM/VSM Gaussian taps
      {"storage", {"float"}, {"8", "16", "float"}},   // CSM/VSM basis precision
      {"samples", {"1"}, {"1", "4"}},                 // GPU Gems PCF samples
      {"compare", {"nearest"}, {"nearest"}},          // hardware 2x2 compare off
      {"width", {"0.01"}, {"0.01", "0.04", "0.08"}},  // smoothie width t
      {"smoothie-width", {}, {"0.01", "0.04", "0.08"}},
      {"t", {}, {"0.01", "0.04", "0.08"}},
      {"bleed-reduction", {}, {"0", "0.4"}},       // VSM light-bleeding reduction
      {"alpha", {}, {"0", "4"}},                   // CSM attenuation
      {"filtering", {}, {"bilinear", "nearest"}},  // CSM/VSM mip-mapping
      {"plan", {"off"}, {"off"}},                  // the pass planner's omissions
  };
  return kAxes;
}

std::string describe(const RenderParams& p) {
  std::ostringstream s;
  s << "size=" << p.width << "x" << p.height << " shadow-map=" << p.shadowMapTexels
    << " filter=" << p.filter << " precision=" << precisionName(p.precision);
  for (const auto& [k, v] : p.extra) s << " " << k << "=" << v;
  return s.str();
}

std::string key(const std::string& scene, const std::string& technique,
                const std::string& variant) {
  return scene + "|" + technique + "|" + variant;
}

// Pass 1: both references and their boundary bands.
struct References {
  Frame hard, soft;
  Image hardBand, softBand;  // the edge band, within the region
  Image region;              // where the light can reach (reference::kDirectLightRegionPass)
};
Image regionBand(const Image& mask, const Image& region) {
  Image band = boundaryBand(mask, kBandRadiusPixels);
  for (size_t i = 0; i < band.data.size(); ++i) band.data[i] *= region.data[i] > 0.5f ? 1.0f : 0.0f;
  return band;
}
References renderReferences(const Scene& scene, const RenderParams& base) {
  References r;
  RenderParams p = base;
  p.extra.clear();
  p.capturePasses = true;  // for the direct-light region
  r.hard = renderTechnique(findTechnique("reference.hard"), scene, p);
  r.soft = renderTechnique(findTechnique("reference.soft"), scene, p);
  for (const PassImage& i : r.hard.intermediates)
    if (i.name == reference::kDirectLightRegionPass) r.region = i.image;
  if (r.region.empty()) r.region = Image(p.width, p.height, 1, 1.0f);
  r.hardBand = regionBand(r.hard.visibility, r.region);
  r.softBand = regionBand(r.soft.visibility, r.region);
  return r;
}

// Pass 2: one variant, timed on one context.
BenchRow measureVariant(const Technique& t, const Scene& scene, const BenchVariant& v,
                        const References& refs, int warmup, int timed, bool quick, Image& maskOut) {
  BenchRow row;
  row.scene = scene.name;
  row.technique = t.name;
  row.variant = v.label;
  row.params = v.params;
  row.primaryReference = approximatesSoftShadows(t) ? "reference.soft" : "reference.hard";
  if (refs.hard.visibility.width > 0 &&
      (t.name == "reference.hard" || t.name == "reference.soft") && v.params.extra.empty()) {
    // The references were rendered once for this scene (pass 1): their row is that frame.
    const Frame& f = t.name == "reference.hard" ? refs.hard : refs.soft;
    row.frameMs = row.wallMs = f.totalMilliseconds();
    row.passes = f.passes;
    row.counters = f.counters;
    row.hard = measureErrors(f.visibility, refs.hard.visibility, refs.region, refs.hardBand);
    row.soft = measureErrors(f.visibility, refs.soft.visibility, refs.region, refs.softBand);
    maskOut = f.visibility;
    return row;
  }
  try {
    checkParams(t, v.params, 0);
    auto context = GlContext::create(contextFor(t, v.params));
    checkParams(t, v.params, context->caps().maxTextureSize);
    if (t.needs.profile == Profile::kCompatibility) imaging::install(*context);
    Frame last;
    std::vector<double> totals, walls;
    std::map<std::string, std::vector<double>> perPass;
    std::vector<std::string> passOrder;
    int frames = warmup + timed;
    for (int i = 0; i < frames; ++i) {
      const double start = nowMilliseconds();
      last = t.render(*context, scene, v.params);
      const double wall = nowMilliseconds() - start;
      // A variant slower than kSlowFrameMs after warm-up is timed once (quick mode's budget).
      if (quick && i == warmup - 1 && wall > kSlowFrameMs) frames = warmup + 1;
      if (i < warmup) continue;
      totals.push_back(last.totalMilliseconds());
      walls.push_back(wall);
      for (const PassTime& p : last.passes) {
        if (!perPass.count(p.name)) passOrder.push_back(p.name);
        perPass[p.name].push_back(p.milliseconds);
      }
    }
    row.frameMs = median(totals);
    row.wallMs = median(walls);
    for (const std::string& name : passOrder) row.passes.push_back({name, median(perPass[name])});
    row.counters = last.counters;
    if (!allFinite(last.visibility)) throw GlError("visibility mask has NaN or Inf");
    row.hard = measureErrors(last.visibility, refs.hard.visibility, refs.region, refs.hardBand);
    row.soft = measureErrors(last.visibility, refs.soft.visibility, refs.region, refs.softBand);
    maskOut = std::move(last.visibility);
  } catch (const InputError& e) {
    row.status = std::string("invalid: ") + e.what();
  } catch (const GlError& e) {
    row.status = std::string("GL error: ") + e.what();
  }
  return row;
}

nlohmann::json errorJson(const ErrorSet& e) {
  return {{"rmse", e.all.rmse},
          {"max_abs", e.all.maxAbs},
          {"share_above_half", e.all.shareAboveHalf},
          {"band_rmse", e.band.rmse},
          {"band_max_abs", e.band.maxAbs},
          {"band_share_above_half", e.band.shareAboveHalf},
          {"leak_share", e.leakShare}};
}

nlohmann::json rowJson(const BenchRow& r) {
  nlohmann::json j = {
      {"scene", r.scene},   {"technique", r.technique},     {"variant", r.variant},
      {"status", r.status}, {"params", describe(r.params)}, {"reference", r.primaryReference}};
  if (r.status != "ok") return j;
  j["frame_ms"] = r.frameMs;
  j["wall_ms"] = r.wallMs;
  j["error"] = errorJson(r.primary());
  j["vs_reference_hard"] = errorJson(r.hard);
  j["vs_reference_soft"] = errorJson(r.soft);
  for (const PassTime& p : r.passes) j["passes"][p.name] = p.milliseconds;
  for (const auto& [k, v] : r.counters) j["counters"][k] = v;
  return j;
}

}  // namespace

std::vector<std::string> benchScenes(bool quick) {
  if (quick) return {"brabec", "fence"};
  return builtinSceneNames();
}

std::vector<BenchVariant> sweepVariants(const Technique& t, const RenderParams& base, bool quick) {
  std::vector<BenchVariant> out = {{"default", base}};
  std::set<std::string> seen = {describe(base)};
  auto add = [&](const std::string& label, const RenderParams& p) {
    if (seen.insert(describe(p)).second) out.push_back({label, p});
  };
  if (isReference(t)) return out;  // the references are the truth; their cost is measured once
  if (usesShadowMap(t)) {
    const std::vector<int> sides =
        quick ? std::vector<int>{256, 1024} : std::vector<int>{128, 256, 512, 1024, 2048};
    for (int n : sides) {
      RenderParams p = base;
      p.shadowMapTexels = n;
      add("shadow-map=" + std::to_string(n), p);
    }
  }
  if (usesFilterFootprint(t)) {
    for (int k : quick ? std::vector<int>{1, 4} : std::vector<int>{1, 2, 3, 4}) {
      RenderParams p = base;
      p.filter = k;
      add("filter=" + std::to_string(k), p);
    }
  }
  if (t.needs.colorFromPrecision) {
    for (Precision q :
         quick ? std::vector<Precision>{Precision::kFloat}
               : std::vector<Precision>{Precision::k8, Precision::k12, Precision::kFloat}) {
      RenderParams p = base;
      p.precision = q;
      add(std::string("precision=") + precisionName(q), p);
    }
  }
  for (const ParamAxis& axis : paramAxes()) {
    if (!contains(t.paramKeys, axis.key)) continue;
    for (const std::string& value : quick ? axis.quick : axis.full) {
      RenderParams p = base;
      p.extra[axis.key] = value;
      add(axis.key + "=" + value, p);
    }
  }
  // Annen et al. Table 1: shadow map side x order M x blur (full mode only).
  if (!quick && contains(t.paramKeys, "order") && contains(t.paramKeys, "blur")) {
    for (int n : {256, 512, 1024, 2048})
      for (const char* m : {"4", "8", "16"})
        for (const char* blur : {"0", "3", "7"}) {
          RenderParams p = base;
          p.shadowMapTexels = n;
          p.extra["order"] = m;
          p.extra["blur"] = blur;
          add("table1 shadow-map=" + std::to_string(n) + " order=" + m + " blur=" + blur, p);
        }
  }
  return out;
}

ErrorSet measureErrors(const Image& mask, const Image& reference, const Image& region,
                       const Image& band) {
  ErrorSet e;
  e.all = compareMasksWithin(mask, reference, region);
  e.band = compareMasksWithin(mask, reference, band);
  long long umbra = 0, leaking = 0;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      if (region.at(x, y) <= 0.5f || reference.at(x, y) != 0.0f || band.at(x, y) > 0.5f) continue;
      ++umbra;
      if (mask.at(x, y) > kLeakThreshold) ++leaking;
    }
  e.leakShare = umbra > 0 ? double(leaking) / double(umbra) : 0.0;
  return e;
}

BenchResult runBenchmark(const BenchOptions& options, std::ostream& json) {
  BenchResult result;
  RenderParams base;
  base.width = options.width > 0 ? options.width : (options.quick ? kQuickWidth : kFullWidth);
  base.height = options.height > 0 ? options.height : (options.quick ? kQuickHeight : kFullHeight);
  base.backend = options.backend;
  const int warmup = options.warmupFrames > 0 ? options.warmupFrames
                                              : (options.quick ? kQuickWarmup : kFullWarmup);
  const int timed =
      options.timedFrames > 0 ? options.timedFrames : (options.quick ? kQuickTimed : kFullTimed);
  std::vector<const Technique*> techniques;
  for (const Technique& t : allTechniques())
    if (!options.technique || t.name == *options.technique) techniques.push_back(&t);
  if (options.technique && techniques.empty()) findTechnique(*options.technique);  // throws
  const std::vector<std::string> scenes =
      options.scenes.empty() ? benchScenes(options.quick) : options.scenes;
  std::vector<Scene> sceneList;
  for (const std::string& name : scenes) sceneList.push_back(loadScene(name));
  // What the planner's omissions save (issue 8 item 4): a purpose-built scene where no caster
  // reaches the light frustum, measured with the planner on and off for every technique that
  // consults it (declares --param plan).
  if (options.scenes.empty() || contains(options.scenes, kDefaultScene)) {
    Scene away = loadScene(kDefaultScene);
    away.name = std::string(kDefaultScene) + "-light-away";
    away.light.target = away.light.position + glm::vec3(0, 5, 0);  // the light looks up
    away.light.up = {0, 0, -1};
    sceneList.push_back(away);
  }
  for (const Scene& scene : sceneList) {
    const bool plannerScene = scene.name.find("-light-away") != std::string::npos;
    if (options.progress) std::cerr << "bench: " << scene.name << ": references\n";
    const References refs = renderReferences(scene, base);
    result.texelsPerPixel[scene.name] = 0.0;
    for (const Technique* t : techniques) {
      std::vector<BenchVariant> variants;
      if (plannerScene) {
        if (!contains(t->paramKeys, "plan")) continue;
        // A 2048 map: the full pass clears and fills it, the planned frame does neither.
        RenderParams on = base;
        on.shadowMapTexels = kPlannerShadowMapTexels;
        RenderParams off = on;
        off.extra["plan"] = "off";
        variants = {{"plan=on", on}, {"plan=off", off}};
      } else {
        variants = sweepVariants(*t, base, options.quick);
      }
      for (const BenchVariant& v : variants) {
        Image mask;
        // The references are measured once, without warm-up: they are the truth, not a
        // contender, and reference.soft costs seconds per frame.
        const bool truth = isReference(*t);
        BenchRow row = measureVariant(*t, scene, v, refs, truth ? 0 : warmup, truth ? 1 : timed,
                                      options.quick, mask);
        if (row.status == "ok") {
          result.masks[key(scene.name, t->name, v.label)] = std::move(mask);
          result.texelsPerPixel[scene.name] =
              std::max(result.texelsPerPixel[scene.name],
                       planFrame(scene, *t, v.params).maxShadowTexelsPerPixel);
        }
        json << rowJson(row).dump() << "\n" << std::flush;
        if (options.progress)
          std::cerr << "bench: " << scene.name << " " << t->name << " " << v.label << ": "
                    << (row.status == "ok" ? std::to_string(row.frameMs) + " ms, rmse " +
                                                 std::to_string(row.primary().all.rmse)
                                           : row.status)
                    << "\n";
        result.rows.push_back(std::move(row));
      }
    }
  }
  return result;
}

std::vector<size_t> paretoFront(const std::vector<BenchRow>& rows, const std::string& scene) {
  std::vector<size_t> candidates;
  for (size_t i = 0; i < rows.size(); ++i)
    if (rows[i].scene == scene && rows[i].status == "ok" &&
        rows[i].technique.rfind("reference.", 0) != 0)
      candidates.push_back(i);
  std::sort(candidates.begin(), candidates.end(), [&](size_t a, size_t b) {
    return rows[a].frameMs != rows[b].frameMs
               ? rows[a].frameMs < rows[b].frameMs
               : rows[a].primary().all.rmse < rows[b].primary().all.rmse;
  });
  std::vector<size_t> front;
  double best = 1e300;
  for (size_t i : candidates)
    if (rows[i].primary().all.rmse < best) {
      best = rows[i].primary().all.rmse;
      front.push_back(i);
    }
  return front;
}

void writeCsv(const std::string& path, const std::vector<BenchRow>& rows) {
  std::ofstream out(path);
  if (!out) throw InputError("cannot write " + path);
  out << "scene,technique,variant,status,reference,width,height,shadow_map,filter,precision,"
         "params,frame_ms,wall_ms";
  for (const char* ref : {"hard", "soft"})
    for (const char* m : {"rmse", "max_abs", "share_above_half", "band_rmse", "band_max_abs",
                          "band_share_above_half", "leak_share"})
      out << "," << ref << "_" << m;
  out << ",passes\n";
  auto quoted = [](std::string s) {
    for (char& c : s)
      if (c == '"') c = '\'';
    return "\"" + s + "\"";
  };
  for (const BenchRow& r : rows) {
    std::string extra;
    for (const auto& [k, v] : r.params.extra) extra += (extra.empty() ? "" : " ") + k + "=" + v;
    out << r.scene << "," << r.technique << "," << quoted(r.variant) << "," << quoted(r.status)
        << "," << r.primaryReference << "," << r.params.width << "," << r.params.height << ","
        << r.params.shadowMapTexels << "," << r.params.filter << ","
        << precisionName(r.params.precision) << "," << quoted(extra) << "," << r.frameMs << ","
        << r.wallMs;
    for (const ErrorSet* e : {&r.hard, &r.soft})
      out << "," << e->all.rmse << "," << e->all.maxAbs << "," << e->all.shareAboveHalf << ","
          << e->band.rmse << "," << e->band.maxAbs << "," << e->band.shareAboveHalf << ","
          << e->leakShare;
    std::string passes;
    for (const PassTime& p : r.passes)
      passes += (passes.empty() ? "" : "; ") + p.name + "=" + std::to_string(p.milliseconds);
    out << "," << quoted(passes) << "\n";
  }
  if (!out) throw InputError("cannot write " + path);
}

namespace {
bool gnuplotHasTerminal(const std::string& terminal) {
  const std::string command =
      "gnuplot -e 'set terminal " + terminal + "' > /dev/null 2>&1 < /dev/null";
  return std::system(command.c_str()) == 0;
}
}  // namespace

std::vector<std::string> writePlots(const std::string& outDir, const BenchResult& result) {
  if (std::system("command -v gnuplot > /dev/null 2>&1") != 0)
    throw InputError("gnuplot is not installed (apt-get install gnuplot-nox): no plots written");
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec) throw InputError("cannot create " + outDir + ": " + ec.message());
  const std::string terminal =
      gnuplotHasTerminal("pngcairo") ? "pngcairo size 1200,800 font ',10'" : "png size 1200,800";
  std::set<std::string> scenes;
  for (const BenchRow& r : result.rows) scenes.insert(r.scene);
  std::vector<std::string> written;
  for (const std::string& scene : scenes) {
    const fs::path base = fs::path(outDir) / ("bench-" + scene);
    // One data block per technique (gnuplot index), then the Pareto front.
    std::ofstream data(base.string() + ".dat");
    std::vector<std::string> techniques;
    for (const BenchRow& r : result.rows)
      if (r.scene == scene && r.status == "ok" && r.primary().all.rmse > 0 &&
          !contains(techniques, r.technique))
        techniques.push_back(r.technique);
    for (const std::string& t : techniques) {
      data << "# " << t << "\n";
      for (const BenchRow& r : result.rows)
        if (r.scene == scene && r.technique == t && r.status == "ok" && r.primary().all.rmse > 0)
          data << r.frameMs << " " << r.primary().all.rmse << " \"" << r.variant << "\"\n";
      data << "\n\n";
    }
    data << "# pareto front\n";
    for (size_t i : paretoFront(result.rows, scene)) {
      const BenchRow& r = result.rows[i];
      if (r.primary().all.rmse <= 0) continue;
      data << r.frameMs << " " << r.primary().all.rmse << " \"" << r.technique << " " << r.variant
           << "\"\n";
    }
    data.close();
    std::ofstream script(base.string() + ".gp");
    script << "set terminal " << terminal << "\n"
           << "set output '" << base.string() << ".png'\n"
           << "set title 'shadowlab bench, scene " << scene
           << ": visibility error against frame time (Pareto front joined)'\n"
           << "set logscale xy\nset grid\nset key outside right\n"
           << "set xlabel 'median frame time [ms] (sum of pass times)'\n"
           << "set ylabel 'RMSE of the visibility mask against its reference'\n"
           << "plot ";
    for (size_t i = 0; i < techniques.size(); ++i)
      script << "'" << base.string() << ".dat' index " << i << " using 1:2 with points pt "
             << (i % 13) + 1 << " ps 1.5 title '" << techniques[i] << "', ";
    script << "'" << base.string() << ".dat' index " << techniques.size()
           << " using 1:2 with steps lw 2 lc rgb 'black' title 'Pareto front', '' index "
           << techniques.size() << " using 1:2 with points lc rgb 'black' pt 6 ps 2.5 notitle, "
           << "'' index " << techniques.size()
           << " using 1:2:3 with labels offset 1,0.8 left font ',7' notitle\n";
    script.close();
    const std::string command = "gnuplot '" + base.string() + ".gp' 2>&1";
    if (techniques.empty() || std::system(command.c_str()) != 0) {
      std::cerr << "bench: no plot for " << scene << " (no measured rows or gnuplot failed)\n";
      continue;
    }
    written.push_back(base.string() + ".png");
  }
  return written;
}

int runBenchCommand(const cli::Args& args) {
  BenchOptions options;
  options.quick = args.has("quick");
  if (auto s = args.value("scene")) options.scenes = {*s};
  options.technique = args.value("technique");
  options.csvPath = args.value("csv");
  if (auto out = args.value("out")) options.outDir = *out;
  if (auto size = args.value("size")) cli::parseSize(*size, options.width, options.height);
  if (auto b = args.value("backend")) options.backend = parseBackend(*b);
  if (auto r = args.value("repeat"))
    options.timedFrames = cli::parsePositiveInt("--repeat", *r, 1000);
  if (options.csvPath) cli::checkWritable(*options.csvPath);
  for (const std::string& s : options.scenes) loadScene(s);  // bad names fail before any work
  if (options.technique) findTechnique(*options.technique);
  const BenchResult result = runBenchmark(options, std::cout);
  if (options.csvPath) {
    writeCsv(*options.csvPath, result.rows);
    std::cerr << "bench: wrote " << *options.csvPath << "\n";
  }
  try {
    for (const std::string& p : writePlots(options.outDir, result))
      std::cerr << "bench: wrote " << p << "\n";
  } catch (const InputError& e) {
    std::cerr << "bench: " << e.what() << "\n";
  }
  for (const ClaimCheck& c : checkClaims(result)) {
    std::cout << nlohmann::json{{"claim", c.id},          {"source", c.source},
                                {"statement", c.claim},   {"scene", c.scene},
                                {"measured", c.measured}, {"verdict", c.verdict}}
                     .dump()
              << "\n";
    std::cerr << "claim " << c.id << " (" << c.source << ") on " << c.scene << ": " << c.verdict
              << "\n    " << c.claim << "\n    measured: " << c.measured << "\n";
  }
  return 0;
}

}  // namespace sl::figures
