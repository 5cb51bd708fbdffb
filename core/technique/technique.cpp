#include "core/technique/technique.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "core/gl/gl_fault.h"

namespace sl {
using namespace sl::gl;

const char* precisionName(Precision p) {
  switch (p) {
    case Precision::k8: return "8";
    case Precision::k12: return "12";
    case Precision::kFloat: return "float";
  }
  return "?";
}

Precision parsePrecision(const std::string& s) {
  if (s == "8") return Precision::k8;
  if (s == "12") return Precision::k12;
  if (s == "float" || s == "32") return Precision::kFloat;
  throw InputError("precision must be 8, 12 or float, got '" + s + "'");
}

namespace {
constexpr const char* kAutoValue = "auto";  // an acceptsAuto ParamSpec's default

double parseNumber(const std::string& key, const std::string& value) {
  const std::optional<double> v = parseDecimal(value);  // strict: no hex, inf, nan or spaces
  if (!v) throw InputError("--param " + key + "=" + value + ": not a finite decimal number");
  return *v;
}

// Notes a value a technique read (RenderParams::readLog): the given text, else the default.
void noteRead(const RenderParams& p, const std::string& key, const std::string& defaultText) {
  auto it = p.extra.find(key);
  std::lock_guard<std::mutex> lock(p.readLog->mutex);
  p.readLog->values[key] = it != p.extra.end() ? it->second : defaultText;
}
}  // namespace

double RenderParams::number(const std::string& key, double fallback, double lo, double hi) const {
  if (readLog) noteRead(*this, key, formatNumber(fallback));
  auto it = extra.find(key);
  if (it == extra.end()) return fallback;
  const double v = parseNumber(key, it->second);
  if (v < lo || v > hi)
    throw InputError("--param " + key + "=" + it->second + ": must lie in [" + std::to_string(lo) +
                     ", " + std::to_string(hi) + "]");
  return v;
}

int RenderParams::integer(const std::string& key, int fallback, int lo, int hi) const {
  if (readLog) noteRead(*this, key, std::to_string(fallback));
  auto it = extra.find(key);
  if (it == extra.end()) return fallback;
  const double v = parseNumber(key, it->second);
  if (v != std::floor(v) || v < lo || v > hi)
    throw InputError("--param " + key + "=" + it->second + ": must be an integer in [" +
                     std::to_string(lo) + ", " + std::to_string(hi) + "]");
  return int(v);
}

std::string RenderParams::text(const std::string& key, const std::string& fallback,
                               const std::vector<std::string>& allowed) const {
  if (readLog) noteRead(*this, key, fallback);
  auto it = extra.find(key);
  if (it == extra.end()) return fallback;
  if (std::find(allowed.begin(), allowed.end(), it->second) == allowed.end()) {
    std::string list;
    for (const auto& a : allowed) list += (list.empty() ? "" : ", ") + a;
    throw InputError("--param " + key + "=" + it->second + ": expected one of " + list);
  }
  return it->second;
}

namespace {
// The one vocabulary of a flag --param: these two words and no others (no
// true/false/1/0), as `shadowlab list`, the live lab's checkboxes and the figures spell them.
constexpr const char* kFlagOn = "on";
constexpr const char* kFlagOff = "off";

// "on" -> true, "off" -> false; any other word is an InputError naming the two.
bool parseFlagValue(const std::string& key, const std::string& value) {
  if (value == kFlagOn) return true;
  if (value == kFlagOff) return false;
  throw InputError("--param " + key + "=" + value + ": expected " + kFlagOn + " or " + kFlagOff);
}
}  // namespace

bool RenderParams::flag(const std::string& key, bool fallback) const {
  if (readLog) noteRead(*this, key, fallback ? kFlagOn : kFlagOff);
  auto it = extra.find(key);
  if (it == extra.end()) return fallback;
  return parseFlagValue(key, it->second);
}

std::string ParamSpec::defaultText() const {
  switch (kind) {
    case Kind::kNumber: return acceptsAuto ? std::string(kAutoValue) : formatNumber(fallback);
    case Kind::kInteger: return std::to_string(int(fallback));
    case Kind::kChoice: return choiceFallback;
    case Kind::kFlag: return flagFallback ? kFlagOn : kFlagOff;
  }
  return "";
}

bool ParamSpec::isDefault(const std::string& value) const {
  if (value == defaultText()) return true;
  if ((kind == Kind::kNumber && !acceptsAuto) || kind == Kind::kInteger) {
    const std::optional<double> v = parseDecimal(value);
    return v && *v == fallback;
  }
  return false;
}

ParamSpec numberParam(std::string key, double fallback, double lo, double hi, std::string meaning) {
  ParamSpec s;
  s.key = std::move(key);
  s.kind = ParamSpec::Kind::kNumber;
  s.fallback = fallback;
  s.lo = lo;
  s.hi = hi;
  s.meaning = std::move(meaning);
  return s;
}

ParamSpec autoNumberParam(std::string key, double lo, double hi, std::string meaning) {
  ParamSpec s = numberParam(std::move(key), lo, lo, hi, std::move(meaning));
  s.acceptsAuto = true;
  return s;
}

ParamSpec integerParam(std::string key, int fallback, int lo, int hi, std::string meaning) {
  ParamSpec s = numberParam(std::move(key), fallback, lo, hi, std::move(meaning));
  s.kind = ParamSpec::Kind::kInteger;
  return s;
}

ParamSpec choiceParam(std::string key, std::string fallback, std::vector<std::string> choices,
                      std::string meaning) {
  ParamSpec s;
  s.key = std::move(key);
  s.kind = ParamSpec::Kind::kChoice;
  s.choiceFallback = std::move(fallback);
  s.choices = std::move(choices);
  s.meaning = std::move(meaning);
  return s;
}

ParamSpec flagParam(std::string key, bool fallback, std::string meaning) {
  ParamSpec s;
  s.key = std::move(key);
  s.kind = ParamSpec::Kind::kFlag;
  s.flagFallback = fallback;
  s.meaning = std::move(meaning);
  return s;
}

const char* paramKindName(ParamSpec::Kind kind) {
  switch (kind) {
    case ParamSpec::Kind::kNumber: return "number";
    case ParamSpec::Kind::kInteger: return "integer";
    case ParamSpec::Kind::kChoice: return "choice";
    case ParamSpec::Kind::kFlag: return "flag";
  }
  return "?";
}

ParamSpec compareParam() {
  return choiceParam("compare", "linear", {"nearest", "linear"},
                     "depth comparison filter: linear = the driver's 2x2 PCF, nearest = one texel");
}

ParamSpec planParam() {
  return flagParam("plan", true, "let the pass planner leave out passes a scene does not need");
}

ParamSpec offsetFactorParam(double fallback) {
  constexpr double kLargestFactor = 100.0;  // slope factor; far beyond any useful bias
  return numberParam("offset-factor", fallback, -kLargestFactor, kLargestFactor,
                     "glPolygonOffset factor of the light pass (depth slope scale)");
}

ParamSpec offsetUnitsParam(double fallback, double largest) {
  return numberParam("offset-units", fallback, -largest, largest,
                     "glPolygonOffset units of the light pass (smallest depth steps)");
}

std::string describeParam(const ParamSpec& p) {
  std::string accepted;
  switch (p.kind) {
    case ParamSpec::Kind::kNumber:
    case ParamSpec::Kind::kInteger:
      accepted = std::string(paramKindName(p.kind)) + " in [" + formatNumber(p.lo) + ", " +
                 formatNumber(p.hi) + "]" + (p.acceptsAuto ? " or auto" : "");
      break;
    case ParamSpec::Kind::kChoice:
      for (const std::string& c : p.choices) accepted += (accepted.empty() ? "" : "|") + c;
      break;
    case ParamSpec::Kind::kFlag: accepted = std::string(kFlagOn) + "|" + kFlagOff; break;
  }
  return p.key + "=" + p.defaultText() + " (" + accepted + "): " + p.meaning;
}

double RenderParams::number(const ParamSpec& spec) const {
  return number(spec.key, spec.fallback, spec.lo, spec.hi);
}

int RenderParams::integer(const ParamSpec& spec) const {
  return integer(spec.key, int(spec.fallback), int(spec.lo), int(spec.hi));
}

std::string RenderParams::text(const ParamSpec& spec) const {
  return text(spec.key, spec.choiceFallback, spec.choices);
}

bool RenderParams::flag(const ParamSpec& spec) const { return flag(spec.key, spec.flagFallback); }

std::optional<double> RenderParams::numberOrAuto(const ParamSpec& spec) const {
  if (readLog) noteRead(*this, spec.key, kAutoValue);
  auto it = extra.find(spec.key);
  if (it == extra.end() || it->second == kAutoValue) return std::nullopt;
  const double v = parseNumber(spec.key, it->second);
  if (v < spec.lo || v > spec.hi)
    throw InputError("--param " + spec.key + "=" + it->second + ": must be auto or lie in [" +
                     formatNumber(spec.lo) + ", " + formatNumber(spec.hi) + "]");
  return v;
}

std::vector<std::string> paramKeys(const Technique& t) {
  std::vector<std::string> keys;
  for (const ParamSpec& p : t.params) keys.push_back(p.key);
  return keys;
}

const ParamSpec* findParam(const Technique& t, const std::string& key) {
  for (const ParamSpec& p : t.params)
    if (p.key == key) return &p;
  return nullptr;
}

std::map<std::string, std::string> effectiveParams(const RenderParams& p) {
  std::map<std::string, std::string> values = p.extra;
  if (p.readLog) {
    std::lock_guard<std::mutex> lock(p.readLog->mutex);
    for (const auto& [key, value] : p.readLog->values) values[key] = value;
  }
  return values;
}

const std::vector<CommonOption>& allCommonOptions() {
  static const std::vector<CommonOption> kAll = {CommonOption::kShadowMap, CommonOption::kFilter,
                                                 CommonOption::kPrecision, CommonOption::kImaging};
  return kAll;
}

const char* optionFlag(CommonOption o) {
  switch (o) {
    case CommonOption::kShadowMap: return "--shadow-map";
    case CommonOption::kFilter: return "--filter";
    case CommonOption::kPrecision: return "--precision";
    case CommonOption::kImaging: return "--imaging";
  }
  return "?";
}

std::vector<const PassTable*> allPassTables(const Technique& t) {
  std::vector<const PassTable*> out = {&t.passes};
  for (const PassVariant& v : t.passVariants) out.push_back(&v.passes);
  return out;
}

const char* shadowGroup(const Technique& t) {
  if (t.light == Technique::Light::kArea) return "soft";
  return t.edge == Technique::Edge::kFiltered ? "filtered" : "hard";
}

bool readsOption(const Technique& t, CommonOption o) {
  switch (o) {
    case CommonOption::kShadowMap: return t.reads.shadowMap;
    case CommonOption::kFilter: return t.reads.filter;
    case CommonOption::kPrecision: return t.reads.precision;
    case CommonOption::kImaging: return t.needs.profile == Profile::kCompatibility;
  }
  return false;
}

double Frame::totalMilliseconds() const {
  double t = 0;
  for (const PassTime& p : passes) t += p.milliseconds;
  return t;
}

ContextSpec contextFor(const Technique& t, const RenderParams& p) {
  ContextSpec spec;
  spec.backend = p.backend;
  spec.profile = t.needs.profile;
  spec.width = p.width;
  spec.height = p.height;
  spec.accumulation = t.needs.accumulation;
  spec.color = ColorFormat::kRgba8;
  if (t.needs.colorFromPrecision) {
    if (p.precision == Precision::k12) spec.color = ColorFormat::kRgba16;
    if (p.precision == Precision::kFloat) spec.color = ColorFormat::kRgba32f;
  }
  return spec;
}

void checkParams(const Technique& t, const RenderParams& p, int maxTextureSize) {
  constexpr int kMaxWindowSide = 16384;
  if (p.width <= 0 || p.height <= 0 || p.width > kMaxWindowSide || p.height > kMaxWindowSide)
    throw InputError("window size " + std::to_string(p.width) + "x" + std::to_string(p.height) +
                     " is impossible (1.." + std::to_string(kMaxWindowSide) + " per side)");
  if (p.shadowMapTexels <= 0 || (maxTextureSize > 0 && p.shadowMapTexels > maxTextureSize))
    throw InputError("shadow map size " + std::to_string(p.shadowMapTexels) + " is outside 1.." +
                     std::to_string(maxTextureSize) + " (GL_MAX_TEXTURE_SIZE of this GL)");
  if (p.filter < 1 || p.filter > 16)
    throw InputError("filter footprint " + std::to_string(p.filter) + " is outside 1..16");
  const std::vector<int>& sides = t.reads.filterSides;
  if (t.reads.filter && !sides.empty() &&
      std::find(sides.begin(), sides.end(), p.filter) == sides.end()) {
    std::string list;
    for (size_t i = 0; i < sides.size(); ++i)
      list += (i == 0 ? "" : i + 1 == sides.size() ? " or " : ", ") + std::to_string(sides[i]);
    throw InputError(t.name + ": --filter must be " + list + ", got " + std::to_string(p.filter));
  }
  for (const auto& [key, value] : p.extra) {
    const ParamSpec* spec = findParam(t, key);
    if (!spec) {
      std::string list;
      for (const auto& k : paramKeys(t)) list += (list.empty() ? "" : ", ") + k;
      throw InputError(
          "technique " + t.name + " has no parameter '" + key + "'" +
          (list.empty() ? std::string(" (it takes none)") : " (it takes " + list + ")"));
    }
    // A flag's word is checked here, before rendering, even where this frame does not read it.
    if (spec->kind == ParamSpec::Kind::kFlag) parseFlagValue(key, value);
  }
}

double nowMilliseconds() {
  using namespace std::chrono;
  return duration<double, std::milli>(steady_clock::now().time_since_epoch()).count();
}

std::string sourceRelativePath(const std::string& file) {
  const std::string root = std::string(SHADOWLAB_SOURCE_DIR) + "/";
  if (file.compare(0, root.size(), root) == 0) return file.substr(root.size());
  // A build directory inside the tree compiles "../legacy_gl/x.cpp".
  std::string relative = file;
  while (relative.rfind("../", 0) == 0) relative = relative.substr(3);
  return relative;
}

PassTime::PassTime(std::string n, double ms, const char* file, const char* function)
    : name(std::move(n)),
      milliseconds(ms),
      sourceFile(sourceRelativePath(file)),
      sourceFunction(function) {}

PassTimer::PassTimer(Frame& frame, std::string name, std::string section, const char* file,
                     const char* function)
    : frame_(frame) {
  throwNotedGlError();  // the previous pass's failure ends the render before this pass runs
  pass_.name = std::move(name);
  pass_.section = std::move(section);
  pass_.sourceFile = sourceRelativePath(file);
  pass_.sourceFunction = function;
  glFinish();
  beginTracedPass();
  glFaultPassBegin("", pass_.name);  // core/gl/gl_fault.h: pass#N faults fire here (no id)
  start_ = nowMilliseconds();
}

PassTimer::~PassTimer() {
  if (std::uncaught_exceptions() > 0) {
    endTracedPass();
    glFaultPassEnd();
    return;
  }
  const std::string name = pass_.name;
  try {
    glFinish();
  } catch (const std::exception& e) {  // no entry point or no current context: noted below
    noteGlError(name + ": " + e.what());
  }
  try {
    pass_.milliseconds = nowMilliseconds() - start_;
    pass_.gl = endTracedPass();
    frame_.passes.push_back(std::move(pass_));
    if (!glErrorNoted()) {
      const std::string errors = drainGlErrors();
      if (!errors.empty()) noteGlError(name + ": " + errors);
    }
  } catch (const std::exception& e) {
    noteGlError(name + ": " + e.what());
  }
  glFaultPassEnd();
}

Frame RenderFunction::operator()(GlContext& context, const Scene& scene,
                                 const RenderParams& params) const {
  if (!function_) throw std::bad_function_call();
  throwNotedGlError();
  Frame frame;
  try {
    frame = function_(context, scene, params);
  } catch (...) {
    throwNotedGlError();  // a pass failed first
    throw;
  }
  throwNotedGlError();
  return frame;
}

Image readColorBuffer(int x, int y, int width, int height) {
  Image image(width, height, 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(x, y, width, height, GL_RGBA, GL_FLOAT, image.data.data());
  checkGl("read colour buffer");
  return image;
}

}  // namespace sl
