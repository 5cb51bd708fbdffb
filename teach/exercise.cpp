// teach/exercise.cpp — the graded exercises (teach/exercise.h): their declarations, how an
// answer is read, and the graders, each of which renders and measures.
#include "teach/exercise.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "core/technique/pass_table.h"
#include "registry/cli.h"
#include "registry/registry.h"
#include "registry/shadow_error.h"

namespace sl::teach {
namespace fs = std::filesystem;

namespace {

// Every grader renders this small frame (a grade takes about a second with its reference).
constexpr int kGradeWidth = 160;   // pixels
constexpr int kGradeHeight = 120;  // pixels
// The map of the bias and bleeding exercises (texels on a side): coarse enough for a 160x120
// frame that acne and bleeding cover many pixels, fine enough that shadows keep their shape.
constexpr int kGradeShadowMap = 256;
// The pass-count and level exercises use the map the course's 128-texel exercises use.
constexpr int kCountShadowMap = 128;
// The largest --filter side, as `shadowlab render --filter` accepts it (registry/cli.cpp).
constexpr int kMaxFilterSide = 16;

// Acne: the share of the truth's lit, scored pixels (outside the shadow-edge band, where
// filtering legitimately greys the edge) that the answer shows more than half shadowed. Ours:
// the course's scene at its tuned bias measures none; without enough bias, acne covers several
// percent of them or more; 1% leaves room for a few pixels on a silhouette.
constexpr double kAcneMaxShare = 0.01;
// Too much bias detaches shadows from their casters ("peter panning", light leaking): the
// truth's umbra pixels shown lit, registry/shadow_error.h leakShare. Ours: 1%, as for acne.
constexpr double kLeakMaxShare = 0.01;
// VSM light bleeding is visible when at least this share of the truth's umbra (outside the
// band) is shown more than kLeakThreshold lit (registry/shadow_error.h): 5%, ours — far above
// what a map's edge aliasing alone leaks there (modern.vsm on brabec leaks none).
constexpr double kBleedMinShare = 0.05;

// Shadow levels: a footprint of n samples gives visibility in steps of 1/n. A mask value
// counts as on the step k/n when it lies within this of it: 8-bit colour buffers and the
// accumulation buffer round each group's sum (1/255 each; two roundings), so 2/255.
constexpr double kLevelTolerance = 2.0 / 255.0;
// The largest step count tried: tolerance * n must stay well below half a step (n < 32).
constexpr int kMaxLevelDenominator = 25;

std::string formatShare(double share) {
  std::ostringstream s;
  s.precision(3);
  s << share * 100.0 << "%";
  return s.str();
}

// --- measuring ----------------------------------------------------------------------------

struct Setup {
  std::string scene = kDefaultScene;
  RenderParams params;
};

Setup baseSetup(int shadowMap) {
  Setup s;
  s.params.width = kGradeWidth;
  s.params.height = kGradeHeight;
  s.params.shadowMapTexels = shadowMap;
  return s;
}

// A parameter file's keys onto a render: scene, filter, or a --param of the technique.
void applyKeys(Setup& s, const std::map<std::string, std::string>& keys) {
  for (const auto& [key, value] : keys) {
    if (key == "scene")
      s.scene = value;
    else if (key == "filter")
      s.params.filter = cli::parsePositiveInt("filter", value, kMaxFilterSide);
    else
      s.params.extra[key] = value;
  }
}

Frame renderSetup(const std::string& technique, const Setup& s, const Scene& scene) {
  const Technique& t = findTechnique(technique);
  return renderTechnique(t, scene, s.params);
}

// The share of the truth's lit scored pixels, outside the band, that `mask` shows more than
// half shadowed: acne (self-shadowing), as kAcneMaxShare explains.
double acneShare(const Image& mask, const ShadowTruth& truth) {
  long long lit = 0, dark = 0;
  for (int y = 0; y < mask.height; ++y)
    for (int x = 0; x < mask.width; ++x) {
      if (truth.scored.at(x, y) <= 0.5f || truth.band.at(x, y) > 0.5f) continue;
      if (truth.visibility.at(x, y) <= 0.5f) continue;
      ++lit;
      if (mask.at(x, y) < 0.5f) ++dark;
    }
  return lit > 0 ? double(dark) / double(lit) : 0.0;
}

struct BiasMeasure {
  double acne = 0.0;
  double leak = 0.0;
};

BiasMeasure measureBias(const std::string& technique, const Setup& s) {
  const Scene scene = loadScene(s.scene);
  const Frame frame = renderSetup(technique, s, scene);
  const ShadowTruth truth = renderShadowTruth(scene, s.params, ErrorMetric::kPoint, false);
  return {acneShare(frame.visibility, truth), scoreShadow(frame.visibility, truth).leakShare};
}

// The smallest n (1..kMaxLevelDenominator) such that every value of the mask lies on a step
// k/n; 0 when none does.
int levelDenominator(const Image& mask) {
  for (int n = 1; n <= kMaxLevelDenominator; ++n) {
    bool all = true;
    for (float v : mask.data) {
      const double scaled = double(v) * n;
      if (std::abs(scaled - std::round(scaled)) > kLevelTolerance * n) {
        all = false;
        break;
      }
    }
    if (all) return n;
  }
  return 0;
}

int distinctLevels(const Image& mask, int denominator) {
  std::vector<bool> seen(size_t(denominator) + 1, false);
  for (float v : mask.data)
    seen[size_t(std::clamp(std::lround(double(v) * denominator), 0L, long(denominator)))] = true;
  return int(std::count(seen.begin(), seen.end(), true));
}

Grade biasGrade(const std::string& technique, const Setup& s, const std::string& what) {
  const BiasMeasure m = measureBias(technique, s);
  Grade g;
  g.measured = {{"acne_share", m.acne}, {"leak_share", m.leak}};
  const std::string numbers = "acne on " + formatShare(m.acne) + " of the truth's lit pixels (" +
                              formatShare(kAcneMaxShare) + " allowed), light leaking on " +
                              formatShare(m.leak) + " of its umbra (" + formatShare(kLeakMaxShare) +
                              " allowed)";
  if (m.acne > kAcneMaxShare) {
    g.reason = what + " leaves shadow acne: " + numbers + "; more bias is needed";
  } else if (m.leak > kLeakMaxShare) {
    g.reason = what + " is too much bias: shadows detach from their casters: " + numbers;
  } else {
    g.pass = true;
    g.reason = what + " removes the acne and keeps the shadows attached: " + numbers;
  }
  return g;
}

std::string keyList(const std::map<std::string, std::string>& keys) {
  std::string out;
  for (const auto& [k, v] : keys) out += (out.empty() ? "" : " ") + k + "=" + v;
  return out.empty() ? "the starting file's values" : out;
}

// --- the graders ----------------------------------------------------------------------------

// ramp-acne-bias: legacy.ramp with --param depth-bias=<answer>.
Grade gradeRampBias(const Exercise& e, const Answer& a) {
  if (!a.number) return {false, "no number given: the answer is the depth bias to try", {}};
  Setup s = baseSetup(kGradeShadowMap);
  s.params.extra["depth-bias"] = formatNumber(*a.number);
  return biasGrade(e.technique, s, "depth-bias=" + formatNumber(*a.number));
}

// hw-slope-bias: modern.hw with the file's offset-factor and offset-units; the constant units
// may not grow beyond the starting file's (the point is the slope factor).
Grade gradeSlopeBias(const Exercise& e, const Answer& a) {
  const Answer start = readAnswer(e, startFilePath(e));
  const double startUnits = cli::parseNumber("offset-units", start.all.at("offset-units"));
  const double units = cli::parseNumber("offset-units", a.all.at("offset-units"));
  if (units > startUnits)
    return {false,
            "offset-units=" + a.all.at("offset-units") +
                " raises the constant bias above the "
                "starting file's " +
                start.all.at("offset-units") +
                "; keep it and add a slope-scaled bias (offset-factor) instead",
            {}};
  Setup s = baseSetup(kGradeShadowMap);
  applyKeys(s, a.all);
  return biasGrade(e.technique, s, keyList(a.all));
}

// pcf-3x3: legacy.pcf with the file's --filter; the mask's shadow levels must be ninths.
Grade gradePcf3x3(const Exercise& e, const Answer& a) {
  constexpr int kWantedSamples = 9;  // a 3x3 footprint
  Setup s = baseSetup(kCountShadowMap);
  applyKeys(s, a.all);
  const Scene scene = loadScene(s.scene);
  const Frame frame = renderSetup(e.technique, s, scene);
  const int n = levelDenominator(frame.visibility);
  Grade g;
  g.measured = {{"level_denominator", n},
                {"levels_seen", n ? distinctLevels(frame.visibility, n) : 0}};
  if (n == kWantedSamples) {
    g.pass = true;
    g.reason = "the mask's shadow levels are multiples of 1/9 (" +
               std::to_string(distinctLevels(frame.visibility, n)) +
               " levels seen): a 3x3 footprint of nine samples";
  } else if (n == 0) {
    g.reason = "the mask's levels are not multiples of 1/n for any n up to " +
               std::to_string(kMaxLevelDenominator) + ": not a PCF footprint of at most 25 samples";
  } else {
    g.reason = "the mask's shadow levels are multiples of 1/" + std::to_string(n) + " (" +
               std::to_string(distinctLevels(frame.visibility, n)) +
               " levels seen): " + std::to_string(n) +
               " samples per pixel, not the nine of a 3x3 footprint";
  }
  return g;
}

// vsm-bleeding: modern.vsm with the file's scene and params; bleeding must be measured.
Grade gradeVsmBleeding(const Exercise& e, const Answer& a) {
  Setup s = baseSetup(kGradeShadowMap);
  applyKeys(s, a.all);
  const Scene scene = loadScene(s.scene);
  const Frame frame = renderSetup(e.technique, s, scene);
  const ShadowTruth truth = renderShadowTruth(scene, s.params, ErrorMetric::kPoint, false);
  const ShadowError err = scoreShadow(frame.visibility, truth);
  Grade g;
  g.measured = {{"leak_share", err.leakShare}, {"rmse", err.all.rmse}};
  const std::string numbers = formatShare(err.leakShare) +
                              " of the truth's umbra is shown more than " +
                              formatNumber(kLeakThreshold) + " lit (" +
                              formatShare(kBleedMinShare) + " makes bleeding visible)";
  g.pass = err.leakShare >= kBleedMinShare;
  g.reason = keyList(a.all) +
             (g.pass ? ": light bleeds into the umbra: " : ": no visible light bleeding: ") +
             numbers;
  return g;
}

// A prediction is an integer; the reason does not give the measured count away.
Grade predictionGrade(const Answer& a, int measured, const std::string& what,
                      const std::string& hint) {
  Grade g;
  g.measured = {{what, measured}};
  if (!a.number) {
    g.reason = "no number given: the answer is your prediction of " + what;
    return g;
  }
  g.pass = *a.number == double(measured);
  g.reason = g.pass
                 ? formatNumber(*a.number) + " is the " + what + " the frame measures"
                 : formatNumber(*a.number) + " is not the " + what + " the frame measures; " + hint;
  return g;
}

// pcf-colour-passes: legacy.pcf --filter 3; how many times pass 4 (colour table + colour
// matrix) runs in one frame, counted from the frame's pass records by the pass table's id.
Grade gradeColourPasses(const Exercise& e, const Answer& a) {
  constexpr const char* kCountPass = "4";
  constexpr int kFilter = 3;
  const Technique& t = findTechnique(e.technique);
  const PassSpec& spec = findPassSpec(t.passes, kCountPass);
  Setup s = baseSetup(kCountShadowMap);
  s.params.filter = kFilter;
  const Frame frame = renderSetup(e.technique, s, loadScene(s.scene));
  const int runs = int(std::count_if(frame.passes.begin(), frame.passes.end(),
                                     [&](const PassTime& p) { return p.id == spec.id; }));
  return predictionGrade(a, runs, "number of runs of pass " + spec.id,
                         "dump the frame (shadowlab render --technique legacy.pcf --filter 3 "
                         "--dump-passes DIR ...) and count pass " +
                             spec.id + "'s images");
}

// modern-pcf-levels: modern.pcf --filter 4; how many visibility levels the mask can take.
Grade gradeModernLevels(const Exercise& e, const Answer& a) {
  constexpr int kFilter = 4;
  Setup s = baseSetup(kCountShadowMap);
  s.params.filter = kFilter;
  const Frame frame = renderSetup(e.technique, s, loadScene(s.scene));
  const int n = levelDenominator(frame.visibility);
  if (n == 0) throw GlError(e.technique + ": the mask's levels are not steps of 1/n");
  return predictionGrade(a, n + 1, "number of shadow levels",
                         "render it with --mask and look at the grey steps across a shadow edge");
}

struct Declared {
  Exercise exercise;
  Grade (*grader)(const Exercise&, const Answer&);
};

const std::vector<Declared>& declared() {
  static const std::vector<Declared> kAll = {
      {{.id = "ramp-acne-bias",
        .family = "legacy",
        .technique = "legacy.ramp",
        .title = "The depth bias at which the ramp's acne disappears",
        .task = "Render `legacy.ramp` with `--param depth-bias=0`: acne covers the lit surfaces. "
                "Find a depth bias, in steps of the 8-bit ramp, at which the acne is gone and "
                "the shadows still touch their casters. Answer with that number.",
        .form = AnswerForm::kNumber,
        .keys = {},
        .measures = "renders legacy.ramp on brabec (160x120, 256 map) with depth-bias set to "
                    "the answer, and scores its mask against reference.hard (point metric): "
                    "passes when at most 1% of the truth's lit pixels show acne and at most 1% "
                    "of its umbra leaks"},
       gradeRampBias},
      {{.id = "pcf-3x3",
        .family = "legacy",
        .technique = "legacy.pcf",
        .title = "A 3x3 PCF from the 2x2 one",
        .task = "The starting file renders `legacy.pcf` with a 2x2 footprint. Change it into a "
                "3x3 PCF: nine samples per pixel, in groups of at most four per pass.",
        .form = AnswerForm::kParams,
        .keys = {"filter"},
        .measures = "renders legacy.pcf on brabec (160x120, 128 map) with the file's filter "
                    "and finds the step of the mask's shadow levels: passes when they are "
                    "multiples of 1/9"},
       gradePcf3x3},
      {{.id = "pcf-colour-passes",
        .family = "legacy",
        .technique = "legacy.pcf",
        .title = "How often the colour table and colour matrix run",
        .task = "Before dumping it: `legacy.pcf --filter 3` compares nine samples per pixel, "
                "four per pass through the colour table and colour matrix (pass 4). How many "
                "times does pass 4 run in one frame? Answer with that number.",
        .form = AnswerForm::kNumber,
        .keys = {},
        .measures = "renders legacy.pcf --filter 3 (160x120, 128 map) and counts the frame's "
                    "runs of pass 4 by its id in the pass table: passes when the answer "
                    "equals the count"},
       gradeColourPasses},
      {{.id = "hw-slope-bias",
        .family = "modern",
        .technique = "modern.hw",
        .title = "Slope-scaled bias on the GLSL twin",
        .task = "The starting file renders `modern.hw` with a constant depth offset only "
                "(`offset-factor=0`): acne stays on the surfaces that slope away from the "
                "light. Add a slope-scaled bias, without raising the constant `offset-units`.",
        .form = AnswerForm::kParams,
        .keys = {"offset-factor", "offset-units"},
        .measures = "renders modern.hw on brabec (160x120, 256 map) with the file's offset "
                    "and scores its mask against reference.hard (point metric): passes when "
                    "offset-units is not above the starting file's, at most 1% of the truth's "
                    "lit pixels show acne and at most 1% of its umbra leaks"},
       gradeSlopeBias},
      {{.id = "vsm-bleeding",
        .family = "modern",
        .technique = "modern.vsm",
        .title = "Make VSM's light bleeding appear",
        .task = "The starting file renders `modern.vsm` on a scene where it looks right. "
                "Choose a scene and VSM parameters under which light bleeds into the umbra.",
        .form = AnswerForm::kParams,
        .keys = {"scene", "bleed-reduction", "min-variance", "blur"},
        .measures = "renders modern.vsm (160x120, 256 map) with the file's scene and params "
                    "and scores its mask against reference.hard (point metric): passes when "
                    "at least 5% of the truth's umbra is shown more than 0.2 lit"},
       gradeVsmBleeding},
      {{.id = "modern-pcf-levels",
        .family = "modern",
        .technique = "modern.pcf",
        .title = "Predict the shadow levels of a 4x4 PCF",
        .task = "Before rendering it: how many different visibility values (shadow levels, "
                "fully lit and umbra included) can the mask of `modern.pcf --filter 4` take? "
                "Answer with that number.",
        .form = AnswerForm::kNumber,
        .keys = {},
        .measures = "renders modern.pcf --filter 4 on brabec (160x120, 128 map) and finds the "
                    "step 1/n of the mask's levels: passes when the answer is n + 1"},
       gradeModernLevels},
  };
  return kAll;
}

const Declared& findDeclared(const std::string& id) {
  for (const Declared& d : declared())
    if (d.exercise.id == id) return d;
  throw InputError("unknown exercise '" + id + "' (shadowlab exercise list names them)");
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r\n");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r\n") - b + 1);
}

// key=value lines (teach/exercise.h): InputError naming the file and line.
std::map<std::string, std::string> parseParamsFile(const Exercise& e, const std::string& path,
                                                   const std::string& text) {
  std::map<std::string, std::string> keys;
  std::istringstream in(text);
  std::string line;
  int number = 0;
  while (std::getline(in, line)) {
    ++number;
    line = trim(line);
    if (line.empty() || line[0] == '#') continue;
    const std::string where = path + " line " + std::to_string(number);
    const auto eq = line.find('=');
    if (eq == std::string::npos)
      throw InputError(where + ": expected key=value, got '" + line + "'");
    const std::string key = trim(line.substr(0, eq)), value = trim(line.substr(eq + 1));
    if (std::find(e.keys.begin(), e.keys.end(), key) == e.keys.end()) {
      std::string allowed;
      for (const std::string& k : e.keys) allowed += (allowed.empty() ? "" : ", ") + k;
      throw InputError(where + ": '" + key + "' is not a key exercise " + e.id + " lets you set (" +
                       allowed + ")");
    }
    if (value.empty()) throw InputError(where + ": " + key + " has no value");
    if (!keys.emplace(key, value).second) throw InputError(where + ": " + key + " is set twice");
  }
  return keys;
}

}  // namespace

const char* answerFormName(AnswerForm form) {
  return form == AnswerForm::kNumber ? "number" : "parameter file";
}

const std::vector<Exercise>& exercises() {
  static const std::vector<Exercise> kList = [] {
    std::vector<Exercise> out;
    for (const Declared& d : declared()) out.push_back(d.exercise);
    return out;
  }();
  return kList;
}

const Exercise& findExercise(const std::string& id) {
  for (const Exercise& e : exercises())
    if (e.id == id) return e;
  return findDeclared(id).exercise;  // throws the InputError
}

std::string exerciseFolder(const Exercise& e) {
  return (fs::path(assetDirectory()) / "exercises" / e.id).string();
}

std::string modelAnswerPath(const Exercise& e) {
  return (fs::path(exerciseFolder(e)) /
          (e.form == AnswerForm::kNumber ? "model.txt" : "model.params"))
      .string();
}

std::string startFilePath(const Exercise& e) {
  if (e.form != AnswerForm::kParams)
    throw InputError("exercise " + e.id + " is answered with a number: it has no starting file");
  return (fs::path(exerciseFolder(e)) / "start.params").string();
}

std::string readTextFile(const std::string& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) throw InputError("no such answer file: " + path);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

Answer readAnswer(const Exercise& e, const std::string& valueOrFile) {
  Answer a;
  if (e.form == AnswerForm::kNumber) {
    if (const std::optional<double> v = parseDecimal(valueOrFile)) {
      a.source = "the value " + valueOrFile;
      a.number = *v;
      return a;
    }
    std::error_code ec;
    if (!fs::exists(valueOrFile, ec))
      throw InputError("exercise " + e.id + " is answered with a number or a file holding one; '" +
                       valueOrFile + "' is neither");
    a.source = valueOrFile;
    const std::string text = trim(readTextFile(valueOrFile));
    if (text.empty()) return a;  // an answer without a number: graded as a fail
    const std::optional<double> v = parseDecimal(text);
    if (!v) throw InputError(valueOrFile + ": expected one decimal number, got '" + text + "'");
    a.number = *v;
    return a;
  }
  a.source = valueOrFile;
  a.given = parseParamsFile(e, valueOrFile, readTextFile(valueOrFile));
  const std::string start = startFilePath(e);
  a.all = start == valueOrFile ? a.given : parseParamsFile(e, start, readTextFile(start));
  for (const auto& [k, v] : a.given) a.all[k] = v;
  return a;
}

Answer modelAnswer(const Exercise& e) { return readAnswer(e, modelAnswerPath(e)); }

Grade grade(const Exercise& e, const Answer& answer) {
  return findDeclared(e.id).grader(e, answer);
}

}  // namespace sl::teach
