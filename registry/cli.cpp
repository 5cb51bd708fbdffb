#include "registry/cli.h"

#include <CLI/CLI.hpp>
#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <iostream>

#include "core/base/decimal.h"
#include "core/base/errors.h"

namespace sl::cli {

bool Args::has(const std::string& key) const {
  return options.count(key) != 0 || std::find(flags.begin(), flags.end(), key) != flags.end();
}

std::optional<std::string> Args::value(const std::string& key) const {
  auto it = options.find(key);
  if (it == options.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}

std::string Args::required(const std::string& key) const {
  auto v = value(key);
  if (!v) throw InputError(command + " needs --" + key);
  return *v;
}

namespace {

// One option of a command: its name (without "--"), its value's form, and its help line.
struct OptionSpec {
  const char* name;
  const char* value;  // what the value looks like in the help ("WxH"); nullptr: a flag
  const char* help;
};
struct CommandSpec {
  const char* name;
  const char* summary;
  std::vector<OptionSpec> options;
  // A positional argument (`shadowlab lesson TECHNIQUE`): its name in Args::options, or nullptr.
  const char* positional = nullptr;
  const char* positionalHelp = nullptr;
};

// The rendering options shared by render, compare and plan (docs/design.md, CLI).
std::vector<OptionSpec> renderOptions() {
  return {
      {"scene", "S", "scene name (shadowlab list) or a scene .json file [brabec]"},
      {"size", "WxH", "window WxH [800x600]"},
      {"shadow-map", "N", "shadow map side in texels [512]"},
      {"filter", "K", "PCF footprint K (K x K samples) [2]"},
      {"precision", "8|12|float", "colour precision of the legacy passes: 8, 12 or float [8]"},
      {"param", "KEY=VALUE", "key=value, repeatable (shadowlab list shows each technique's keys)"},
      {"orbit", "AZ,EL,DIST",
       "camera orbit around its target: azimuth and elevation in degrees, distance in world "
       "units [the scene's camera]"},
      {"backend", "NAME", "osmesa, reference (Mesa 7.8.2, native imaging) or egl [osmesa]"},
      {"imaging", "native|emulated",
       "imaging subset of the legacy techniques: native (the back end's own; reference only) or "
       "emulated (imaging/, on any back end) [native where the back end has it, else emulated]"},
      {"camera-distance", "X",
       "times the camera's distance from its target, along its view direction (> 1: farther, "
       "as in csm-fig1/csm-fig10) [1]"},
      {"light-radius", "R",
       "the light's radius in world units, read by reference.soft (chan-4-9) [the scene's]"},
      {"light-position", "X,Y,Z",
       "the light's position in world units; it keeps aiming at its target [the scene's]"},
  };
}

// The value form of an option that names a PNG file to write: parse() refuses any other name.
constexpr const char* kPngValue = "PNG";

// An image output whose name does not end in .png would get PNG bytes under another format's
// name (a.jpg): refused before anything runs, naming the option.
void requirePngName(const std::string& option, const std::string& path) {
  std::string extension = std::filesystem::path(path).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  if (extension != ".png")
    throw InputError("--" + option + " " + path + ": PNG only (the name must end in .png)");
}

std::vector<OptionSpec> join(std::vector<OptionSpec> a, const std::vector<OptionSpec>& b) {
  a.insert(a.end(), b.begin(), b.end());
  return a;
}

// Every command and its options: the single source of `--help` and of what parse() accepts.
const std::vector<CommandSpec>& commandSpecs() {
  static const std::vector<CommandSpec> kCommands = {
      {"list", "techniques (with their --param keys), scenes and figures", {}},
      {"render",
       "render one technique into an image (and its visibility mask and intermediate buffers)",
       join({{"technique", "T", "technique name (shadowlab list), required"},
             {"out", kPngValue, "colour image, PNG only (the name ends in .png), required"},
             {"mask", kPngValue,
              "light visibility (1 = lit, 0 = umbra) as a 16-bit grey PNG, PNG only (the name "
              "ends in .png)"},
             {"dump-passes", "DIR",
              "directory for every intermediate buffer, one PNG each in pipeline order, with "
              "passes.json and index.html (made or replaced as a whole at the end; an existing "
              "DIR must be empty or hold only a previous dump)"}},
            renderOptions())},
      {"compare",
       "render two techniques and compare their visibility masks (one JSON line). When one is\n"
       "a ray-traced reference, the other's error against it with the one definition of\n"
       "docs/error.md (pixel=centre: point metric, pixel=area: area metric), as bench scores;\n"
       "otherwise the masks' difference over the same scored pixels; all_pixels: every pixel",
       join({{"a", "T1", "first technique, required"},
             {"b", "T2", "second technique, required"},
             {"a-param", "KEY=VALUE",
              "a --param for T1 only, repeatable; over --param (which goes to both)"},
             {"b-param", "KEY=VALUE",
              "a --param for T2 only, repeatable (--b-param pixel=area: the area metric's truth)"},
             {"diff", kPngValue, "difference heat map, PNG only (the name ends in .png)"},
             {"threshold", "X", "pixels differing by more than this count as mismatching [0]"}},
            renderOptions())},
      {"bench",
       "error against run time for every technique and a sweep of its parameters\n"
       "Scenes: quick = brabec, fence; full = every built-in scene (analytic, brabec, fence,\n"
       "trees, dueling, long); both add brabec-light-away (planner on/off) and trees-far\n"
       "(minification claim), full also fill-bound (assets/scenes). Each variant is measured\n"
       "against the ray-traced references (pixel=area): RMSE, band RMSE (2 px of an edge),\n"
       "leak, temporal change (light moved by a fifth of a texel). Not swept: values a\n"
       "technique rejects (fast PCF --filter 1 and 3, modern.vsm storage=8) and repeats of\n"
       "its defaults.\n"
       "Written: stdout, one JSON line per variant (sorted by scene, then frame time, with\n"
       "pareto_rank), then one per paper claim; stderr, progress, the claims' verdicts and\n"
       "the --budget-ms table; --csv FILE, one row per variant (same order and columns);\n"
       "--out PATH, per scene bench-SCENE.png (error against time, Pareto front),\n"
       "bench-SCENE.dat (its data) and bench-SCENE.gp (its gnuplot script).",
       {{"quick", nullptr, "the quick sweep (two scenes, 256x192; the main job's report uses it)"},
        {"scene", "S", "only these scenes: repeatable, or S1,S2 [the benchmark scenes above]"},
        {"technique", "T",
         "only these techniques (all their variants): repeatable, or T1,T2 [every technique]"},
        {"csv", "FILE", "also write every row as CSV [none]"},
        {"size", "WxH", "window WxH [quick 256x192, full 400x300]"},
        {"backend", "NAME", "osmesa, reference or egl [osmesa]"},
        {"repeat", "N",
         "timed frames per variant, after the warm-up frames [quick 3 after 1, full 7 after 2]"},
        {"out", "PATH", "directory for plots and their data [out/bench]"},
        {"sweep", "FILE",
         "run the sweep spec FILE.json instead (techniques x scenes x sizes x shadow maps x "
         "filters x precisions x params x orbits; docs/user-guide.md \"Sweeps\"): one JSON "
         "line per row in the spec's order, --csv as above, no plots or claims"},
        {"merge", "FILE",
         "merge bench JSON-line files (repeatable): their rows on stdout with pareto_rank "
         "recomputed over all of them per scene, window and orbit"},
        {"budget-ms", "X",
         "after the sweep, per scene: the variants with a median frame time within X ms, "
         "ranked by RMSE, with band RMSE, temporal change and Pareto rank (references are "
         "not ranked); X > 0 [no ranking]"}}},
      {"plan", "the passes a frame of a technique needs, those left out, and why",
       join({{"technique", "T", "technique name, required"}}, renderOptions())},
      {"figures",
       "the main job: every reproduced paper figure and report.html",
       {{"out", "PATH", "output directory [out/figures]"},
        {"only", "ID", "only this figure id (shadowlab list); repeatable"},
        {"set", "KEY=VALUE",
         "with --only: re-make the figure with KEY changed in every panel, repeatable; keys: "
         "size=WxH, shadow-map=N, filter=K, precision=8|12|float, camera-distance=X, "
         "light-radius=R, light-position=X,Y,Z, or any --param key of the figure's techniques "
         "(order=8); written to OUT/ID--KEY-VALUE/ with the overrides in the caption and the "
         "file names"},
        {"no-progress", nullptr, "no progress lines on stderr"}}},
      {"lesson",
       "one self-contained HTML lesson on a technique: the paper's idea, every pass with its\n"
       "caption, GL state card and GLSL twin, legacy against modern, the known departures",
       {{"out", "DIR",
         "output directory (made or replaced as a whole; an existing DIR must be "
         "empty or hold only a previous lesson or dump), required"},
        {"scene", "S", "scene name (shadowlab list) or a scene .json file [brabec]"},
        {"size", "WxH", "window WxH [400x300]"},
        {"shadow-map", "N", "shadow map side in texels, where the technique reads one [512]"}},
       "technique",
       "technique name (shadowlab list), required"},
      {"gallery",
       "the artefact gallery: wrong/right picture pairs, their render commands and lab links",
       {{"out", "DIR", "writes DIR/gallery/ (index.html and PNGs; replaced as a whole), required"},
        {"lab", "URL",
         "address of `shadowlab serve` the lab links open [http://127.0.0.1:8080/]"}}},
      {"course",
       "the lessons in a teaching order, with exercises, a teacher's page and the gallery",
       {{"out", "DIR",
         "writes DIR/index.html, DIR/teacher.html, DIR/teacher/, DIR/gallery/ and "
         "DIR/lessons/, required"},
        {"lab", "URL", "address of `shadowlab serve` the lab links open [http://127.0.0.1:8080/]"},
        {"no-progress", nullptr, "no progress lines on stderr"}}},
      {"serve",
       "the live lab: a page and its API (/api/techniques, /api/scenes, /api/render, /api/error)",
       {{"host", "ADDRESS",
         "address to listen on; anything but loopback is warned about "
         "[127.0.0.1]"},
        {"port", "N", "TCP port; 0 picks a free one [8080]"}}},
  };
  return kCommands;
}

}  // namespace

Args parse(int argc, char** argv) {
  if (argc < 2) throw InputError("no command given (try: shadowlab --help)");
  const auto& commands = commandSpecs();
  if (std::none_of(commands.begin(), commands.end(),
                   [&](const CommandSpec& c) { return argv[1] == std::string(c.name); }))
    throw InputError("unknown command '" + std::string(argv[1]) + "' (try: shadowlab --help)");
  CLI::App app{"shadowlab", "shadowlab"};
  app.require_subcommand(1, 1);
  app.set_help_flag();  // top-level help is apps/shadowlab.cpp's usage text
  std::map<std::string, std::map<std::string, CLI::Option*>> options;
  for (const CommandSpec& c : commands) {
    CLI::App* sub = app.add_subcommand(c.name, c.summary);
    sub->set_help_flag("-h,--help", "print this help and exit");
    for (const OptionSpec& o : c.options) {
      const std::string flag = std::string("--") + o.name;
      CLI::Option* option = o.value ? sub->add_option(flag, o.help)
                                          ->type_name(o.value)
                                          ->type_size(1)
                                          ->allow_extra_args(false)
                                          ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll)
                                    : sub->add_flag(flag, o.help);
      options[c.name][o.name] = option;
    }
    if (c.positional)
      options[c.name][c.positional] =
          sub->add_option(c.positional, c.positionalHelp)->type_size(1)->required();
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    // `shadowlab COMMAND --help`: the command's options, on stdout (exit status 0).
    for (CLI::App* sub : app.get_subcommands()) throw HelpRequested{sub->help("shadowlab")};
    throw HelpRequested{app.help()};
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    throw InputError(what + " (try: shadowlab " +
                     (app.get_subcommands().empty()
                          ? std::string("--help")
                          : app.get_subcommands()[0]->get_name() + " --help") +
                     ")");
  }
  Args a;
  a.command = app.get_subcommands().at(0)->get_name();
  for (const auto& [name, option] : options[a.command]) {
    if (option->count() == 0) continue;
    if (option->get_expected_min() == 0) {
      a.flags.push_back(name);
      continue;
    }
    a.options[name] = option->results();
  }
  for (const CommandSpec& c : commands)
    if (a.command == c.name)
      for (const OptionSpec& o : c.options)
        if (o.value && std::string(o.value) == kPngValue && a.options.count(o.name))
          for (const std::string& path : a.options.at(o.name)) requirePngName(o.name, path);
  return a;
}

bool parseTool(CLI::App& app, int argc, char** argv) {
  app.set_help_flag("-h,--help", "print this help and exit");
  // A repeated single-valued option keeps its last value, as before the move to CLI11.
  for (CLI::Option* option : app.get_options())
    if (option->get_multi_option_policy() == CLI::MultiOptionPolicy::Throw)
      option->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::cout << app.help();
    return false;
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    throw InputError(what + " (try: " + app.get_name() + " --help)");
  }
  return true;
}

int parsePositiveInt(const std::string& what, const std::string& text, int maxValue) {
  const std::optional<long long> v = parseWholeNumber(text);  // strict: digits only
  if (!v) throw InputError(what + " must be a whole number, got '" + text + "'");
  if (*v <= 0 || *v > maxValue)
    throw InputError(what + " must lie in 1.." + std::to_string(maxValue) + ", got " + text);
  return int(*v);
}

double parseNumber(const std::string& what, const std::string& text) {
  const std::optional<double> v = parseDecimal(text);  // strict: no hex, inf, nan or spaces
  if (!v) throw InputError(what + " must be a decimal number, got '" + text + "'");
  return *v;
}

void parseSize(const std::string& text, int& width, int& height) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw InputError("--size must look like 800x600, got '" + text + "'");
  constexpr int kMaxWindowSide = 16384;
  width = parsePositiveInt("--size width", text.substr(0, x), kMaxWindowSide);
  height = parsePositiveInt("--size height", text.substr(x + 1), kMaxWindowSide);
}

ImagingChoice parseImaging(const std::string& text) {
  if (text == "native") return ImagingChoice::kNative;
  if (text == "emulated") return ImagingChoice::kEmulated;
  throw InputError("--imaging must be native or emulated, got '" + text + "'");
}

RenderParams renderParams(const Args& args) {
  RenderParams p;
  if (auto v = args.value("size")) parseSize(*v, p.width, p.height);
  constexpr int kLargestShadowMap = 1 << 16;  // the GL maximum is checked once a context exists
  if (auto v = args.value("shadow-map"))
    p.shadowMapTexels = parsePositiveInt("--shadow-map", *v, kLargestShadowMap);
  if (auto v = args.value("filter")) p.filter = parsePositiveInt("--filter", *v, 16);
  if (auto v = args.value("precision")) p.precision = parsePrecision(*v);
  if (auto v = args.value("backend")) p.backend = parseBackend(*v);
  if (auto v = args.value("imaging")) p.imaging = parseImaging(*v);
  if (auto it = args.options.find("param"); it != args.options.end())
    for (const std::string& kv : it->second) {
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0)
        throw InputError("--param must look like key=value, got '" + kv + "'");
      p.extra[kv.substr(0, eq)] = kv.substr(eq + 1);
    }
  return p;
}

glm::vec3 parsePosition(const std::string& what, const std::string& text) {
  glm::vec3 v;
  size_t start = 0;
  for (int i = 0; i < 3; ++i) {
    const size_t comma = text.find(',', start);
    if ((i < 2) != (comma != std::string::npos))
      throw InputError(what + " must look like X,Y,Z, got '" + text + "'");
    const std::string part = text.substr(start, i < 2 ? comma - start : std::string::npos);
    const double x = parseNumber(what, part);
    if (!(std::fabs(x) <= kMaxSceneCoordinate))
      throw InputError(what + " coordinates must lie within +-1e12, got " + part);
    v[i] = float(x);
    start = comma + 1;
  }
  return v;
}

SceneAdjustments sceneAdjustments(const Args& args) {
  SceneAdjustments a;
  constexpr double kLargestCameraFactor = 1e6;  // beyond it the far plane leaves float range
  if (auto v = args.value("camera-distance")) {
    const double d = parseNumber("--camera-distance", *v);
    if (!(d > 0.0 && d <= kLargestCameraFactor))
      throw InputError("--camera-distance must lie in (0, 1e6], got " + *v);
    a.cameraDistance = float(d);
  }
  if (auto v = args.value("light-radius")) {
    const double r = parseNumber("--light-radius", *v);
    if (!(r >= 0.0 && r <= kMaxSceneCoordinate))
      throw InputError("--light-radius must lie in [0, 1e12] (world units), got " + *v);
    a.lightRadius = float(r);
  }
  if (auto v = args.value("light-position"))
    a.lightPosition = parsePosition("--light-position", *v);
  return a;
}

namespace {
// "1.5,2,-3" -> three strict decimals; InputError naming the option otherwise.
std::array<double, 3> parseTriple(const std::string& what, const std::string& text,
                                  const char* form) {
  std::array<double, 3> v{};
  size_t start = 0;
  for (size_t i = 0; i < v.size(); ++i) {
    const size_t comma = text.find(',', start);
    const bool last = i + 1 == v.size();
    if (last != (comma == std::string::npos))
      throw InputError(what + " must look like " + form + ", got '" + text + "'");
    const std::string part = text.substr(start, last ? std::string::npos : comma - start);
    v[i] = parseNumber(what, part);
    start = comma + 1;
  }
  return v;
}

constexpr double kPi = 3.14159265358979323846;

// The orbit frame of a camera: `axis` its up, azimuth 0 along world +z made normal to the axis
// (+x when the axis is z), azimuth 90 along axis x front.
struct OrbitFrame {
  glm::vec3 axis, front, side;
};
OrbitFrame orbitFrame(const Camera& camera) {
  OrbitFrame f;
  f.axis = glm::normalize(camera.up);
  constexpr float kParallel = 1e-3f;  // |z off the axis| below this: the axis is z
  f.front = glm::vec3(0, 0, 1) - glm::dot(glm::vec3(0, 0, 1), f.axis) * f.axis;
  if (glm::length(f.front) < kParallel)
    f.front = glm::vec3(1, 0, 0) - glm::dot(glm::vec3(1, 0, 0), f.axis) * f.axis;
  f.front = glm::normalize(f.front);
  f.side = glm::cross(f.axis, f.front);
  return f;
}
}  // namespace

ViewPose viewPose(const Scene& scene) {
  const auto [axis, front, side] = orbitFrame(scene.camera);
  const glm::vec3 offset = scene.camera.position - scene.camera.target;
  const double distance = glm::length(offset);
  const glm::vec3 d = offset / float(distance);
  constexpr double kDegreesPerRadian = 180.0 / kPi;
  ViewPose pose;
  pose.azimuthDegrees = std::atan2(glm::dot(d, side), glm::dot(d, front)) * kDegreesPerRadian;
  pose.elevationDegrees =
      std::asin(std::clamp(double(glm::dot(d, axis)), -1.0, 1.0)) * kDegreesPerRadian;
  pose.distance = distance;
  pose.light = scene.light.position;
  return pose;
}

void applyView(const Args& args, Scene& scene) {
  if (auto v = args.value("orbit")) {
    const auto o = parseTriple("--orbit", *v, "AZ,EL,DIST");
    constexpr double kMaxAzimuthDegrees = 360.0;
    constexpr double kMaxElevationDegrees = 89.0;  // the camera's up stays off its view direction
    constexpr double kMinOrbitDistance = 1e-3;     // world units; the near plane is 0.1 or less
    if (std::abs(o[0]) > kMaxAzimuthDegrees)
      throw InputError("--orbit azimuth must lie in [-360, 360] degrees, got '" + *v + "'");
    if (std::abs(o[1]) > kMaxElevationDegrees)
      throw InputError("--orbit elevation must lie in [-89, 89] degrees, got '" + *v + "'");
    if (!(o[2] >= kMinOrbitDistance && o[2] <= kMaxSceneCoordinate))
      throw InputError("--orbit distance must lie in [0.001, 1e12], got '" + *v + "'");
    const auto [axis, front, side] = orbitFrame(scene.camera);
    constexpr double kRadiansPerDegree = kPi / 180.0;
    const double az = o[0] * kRadiansPerDegree, el = o[1] * kRadiansPerDegree;
    const glm::vec3 d = float(std::cos(el) * std::cos(az)) * front +
                        float(std::cos(el) * std::sin(az)) * side + float(std::sin(el)) * axis;
    scene.camera.position = scene.camera.target + float(o[2]) * d;
  }
  validateScene(scene);
}

void viewScene(const Args& args, Scene& scene) {
  adjustScene(scene, sceneAdjustments(args));
  applyView(args, scene);
}

std::vector<CommonOption> givenCommonOptions(const Args& args) {
  std::vector<CommonOption> given;
  for (CommonOption o : allCommonOptions())
    if (args.has(std::string(optionFlag(o)).substr(2))) given.push_back(o);  // without "--"
  return given;
}

}  // namespace sl::cli
