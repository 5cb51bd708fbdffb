// core/technique/technique.h — the one interface every shadow technique implements (legacy_gl/,
// modern/, reference/): render a scene with parameters into a Frame.
//
// A technique is plain data: a name, its citation, what context it needs and a render
// function. legacy_gl/ and modern/ each export a list; apps/ and tests put them together.
#pragma once

#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <type_traits>
#include <vector>

#include "core/base/image.h"
#include "core/gl/context.h"
#include "core/gl/gl_trace.h"
#include "core/scene/scene.h"
#include "core/technique/pass_table.h"

namespace sl {

// Arithmetic precision of the colour channels that carry encoded depth (Brabec–Seidel §6):
// 8 bits (their Octane/O2 buffers), 12 bits (Octane VPro: a 16-bit buffer quantised to 12)
// and float (no 2001 limits).
enum class Precision { k8, k12, kFloat };
const char* precisionName(Precision p);
Precision parsePrecision(const std::string& s);  // "8", "12", "float"; throws InputError

// The --param values a render read (RenderParams::readLog): key -> value as --param spells it.
// Guarded, as a technique may read parameters from worker threads.
struct ParamReadLog {
  std::mutex mutex;
  std::map<std::string, std::string> values;
};

// One --param key a technique understands, declared once where the technique is defined (its
// kind, default, range or choices, and what it means). The technique reads the value through
// RenderParams with the same declaration; `list`, checkParams, the bench's sweeps and the live
// lab read the declarations (docs/design.md: declared once, never listed by hand again).
struct ParamSpec {
  enum class Kind { kNumber, kInteger, kChoice, kFlag };
  std::string key;
  Kind kind = Kind::kNumber;
  double fallback = 0.0;  // kNumber, kInteger: the default
  double lo = 0.0;        // kNumber, kInteger: the accepted range [lo, hi]
  double hi = 0.0;
  bool acceptsAuto = false;          // kNumber: "auto" (the default) lets the technique derive it
  std::string choiceFallback;        // kChoice: the default
  std::vector<std::string> choices;  // kChoice: the accepted values
  bool flagFallback = false;         // kFlag: the default
  std::string meaning;               // one line, with the paper's section where there is one
  std::string defaultText() const;   // the default as --param spells it ("16", "linear", "auto")
  // True when `value` (as --param spells it) is the default: "1" and "1.0" are the same number.
  bool isDefault(const std::string& value) const;
};
ParamSpec numberParam(std::string key, double fallback, double lo, double hi, std::string meaning);
ParamSpec autoNumberParam(std::string key, double lo, double hi, std::string meaning);
ParamSpec integerParam(std::string key, int fallback, int lo, int hi, std::string meaning);
ParamSpec choiceParam(std::string key, std::string fallback, std::vector<std::string> choices,
                      std::string meaning);
ParamSpec flagParam(std::string key, bool fallback, std::string meaning);
const char* paramKindName(ParamSpec::Kind kind);  // "number", "integer", "choice", "flag"
// "order=16 (integer in [1, 64]): M, the number of Fourier terms ..." (the default, the accepted
// values, the meaning), as `shadowlab list` prints it.
std::string describeParam(const ParamSpec& p);

// Declarations several techniques share (each technique still lists them in its own params).
ParamSpec compareParam();  // compare=linear|nearest: GL_LINEAR (2x2 PCF) or GL_NEAREST lookups
ParamSpec
planParam();  // plan=on|off: the pass planner may leave out passes (core/technique/plan.h)
ParamSpec offsetFactorParam(double fallback);  // glPolygonOffset factor of the light pass
ParamSpec offsetUnitsParam(double fallback, double largest);  // its units, in [-largest, largest]

// --imaging: which implementation of the OpenGL 1.2 imaging subset (ARB_imaging) a legacy
// technique's context uses. kBackendDefault: the back end's own where it has one (reference),
// else the software emulation of imaging/ (osmesa).
enum class ImagingChoice { kBackendDefault, kNative, kEmulated };

struct RenderParams {
  int width = 800;  // window, pixels (Brabec–Seidel §5)
  int height = 600;
  int shadowMapTexels = 512;  // side of the square shadow map (Brabec–Seidel §5)
  int filter = 2;             // PCF footprint side: 1 = unfiltered, 2, 3, 4
  Precision precision = Precision::k8;
  Backend backend = Backend::kOsmesa;
  ImagingChoice imaging = ImagingChoice::kBackendDefault;  // --imaging (legacy techniques)
  bool capturePasses = false;                // fill Frame::intermediates (--dump-passes)
  std::map<std::string, std::string> extra;  // --param key=value, technique specific
  // When set, number/integer/text/flag note every key they are asked for with the value they
  // return, the technique's default included where the key was not given: the effective
  // --params of a render (apps/shadowlab.cpp prints them). Copies share the log.
  std::shared_ptr<ParamReadLog> readLog;

  // Typed access to `extra` with range checks; unknown keys are reported by checkParams.
  double number(const std::string& key, double fallback, double lo, double hi) const;
  int integer(const std::string& key, int fallback, int lo, int hi) const;
  std::string text(const std::string& key, const std::string& fallback,
                   const std::vector<std::string>& allowed) const;
  bool flag(const std::string& key, bool fallback) const;
  // The same through a technique's declaration (ParamSpec): its default, range and choices.
  double number(const ParamSpec& spec) const;
  int integer(const ParamSpec& spec) const;
  std::string text(const ParamSpec& spec) const;
  bool flag(const ParamSpec& spec) const;
  // An acceptsAuto number: empty when absent or "auto" (the technique derives the value).
  std::optional<double> numberOrAuto(const ParamSpec& spec) const;
};

// The --params of a render: every key given, and every key the technique read through
// number/integer/text/flag with the value it used (its default where none was given). Without
// a readLog, the keys given.
std::map<std::string, std::string> effectiveParams(const RenderParams& p);

struct PassTime {
  PassTime() = default;
  // A pass timed by hand (CPU work such as ray tracing): the file and function that time it are
  // its source, as PassTimer records them.
  PassTime(std::string n, double ms, const char* file = __builtin_FILE(),
           const char* function = __builtin_FUNCTION());
  std::string name;
  double milliseconds = 0.0;
  // From the technique's pass table (core/technique/pass_table.h), for passes run through
  // core/technique/passes.h: the pass's id ("5c"), its floor class, its role and which of its
  // repeated parts this run is.
  std::string id;
  PassFloor floor = PassFloor::kNone;
  PassRole role = PassRole::kOther;
  int part = 0;
  // Declared by the pass itself (PassTimer): the paper's section/equation/figure it follows,
  // and where its function lives (file relative to the source tree, function name).
  std::string section;
  std::string sourceFile;
  std::string sourceFunction;
  // The shader passes it runs: IDs of `// @pass ID` markers in the GLSL (core/gl/shaders.h
  // shaderPassMarkers), which name the legacy passes they replace.
  std::vector<std::string> glsl;
  // The words of the GL state lines that matter for the pass (PassSpec::keyState).
  std::vector<std::string> keyState;
  // While a GlTrace runs (--dump-passes): the GL state it set (core/gl/gl_trace.h).
  TracedPass gl;
};

struct PassImage {
  PassImage() = default;
  PassImage(std::string n, std::string c, Image i)
      : name(std::move(n)), caption(std::move(c)), image(std::move(i)) {}
  std::string name;  // file-name friendly: "1-light-pass-ramp-depth"
  std::string caption;
  std::string passId;  // the pass of the technique's table it belongs to ("5c")
  Image image;
  // A packed map (several depth samples per texel, Brabec–Seidel §4 Fig. 5): the channel that
  // holds the texel's own (centre) sample and what each channel holds ("lower left", ...). The
  // dump (teach/pass_dump.h) then shows every channel on one depth scale and each channel minus
  // the centre one, so the one-texel shift between them is visible.
  int centreChannel = -1;
  std::vector<std::string> channelMeaning;
};

struct Frame {
  Image color;       // shaded RGB image, rows bottom-up
  Image visibility;  // one channel, 1 = fully lit, 0 = umbra, before any shading
  std::vector<PassTime> passes;
  std::vector<PassImage> intermediates;
  std::map<std::string, double> counters;  // technique statistics (overdraw, silhouette share)
  double totalMilliseconds() const;
};

struct ContextNeeds {
  Profile profile = Profile::kCompatibility;
  bool accumulation = false;
  bool colorFromPrecision = false;  // colour buffer format follows RenderParams::precision
};

// The options of render, compare and plan that only some techniques read; --size and
// --backend apply to every technique. An option given to a technique that does not read it is
// an input error (registry/registry.h rejectIgnoredOptions). --imaging is read by every technique
// of the compatibility profile (those that get the imaging subset installed).
enum class CommonOption { kShadowMap, kFilter, kPrecision, kImaging };
const std::vector<CommonOption>& allCommonOptions();
const char* optionFlag(CommonOption o);  // "--shadow-map"

// Which common options a technique's render reads, declared where the technique is registered.
struct CommonOptions {
  bool shadowMap = false;  // RenderParams::shadowMapTexels
  bool filter = false;     // RenderParams::filter
  // The --filter sides it accepts when it reads --filter (fast PCF: 2 and 4, the footprints of
  // Brabec & Seidel §4); empty = every side checkParams allows. checkParams refuses the others.
  std::vector<int> filterSides{};
  bool precision = false;  // RenderParams::precision
};

// What the pass planner (core/technique/plan.h) needs to know of a technique, declared by the
// technique where it is defined, so that the planner asks instead of matching names.
struct PlanTraits {
  // The work of the light-side passes.
  enum class ShadowWork { kShadowMap, kShadowVolumes, kSmoothies, kRays };
  ShadowWork shadowWork = ShadowWork::kShadowMap;
  // How a filter footprint's samples are grouped: one comparison per pixel; Brabec–Seidel §3
  // (four samples per pass, one per RGBA channel, groups summed in the accumulation buffer);
  // §4 fast PCF (2x2 packed by one convolution, larger footprints summed as 2x2 phases).
  enum class SampleGrouping { kOnePerPixel, kFourPerPass, kPackedPhases };
  SampleGrouping samples = SampleGrouping::kOnePerPixel;
  // The imaging subset stages the legacy passes use (Brabec–Seidel §3 Fig. 4, §4 Eq. (1)).
  bool colourTableCompare = false;
  bool colourMatrixSum = false;
  bool packingConvolution = false;
  // Prefiltered maps (Annen et al. 2007 CSM; VSM): a separable blur and a mip chain.
  enum class Prefilter { kNone, kConvolution, kVariance };
  Prefilter prefilter = Prefilter::kNone;  // its blur/storage/filtering defaults: its ParamSpecs
};

// A technique's render function. Calling it renders, then throws as GlError a GL failure that a
// pass noted at its end (PassTimer; core/base/errors.h noteGlError); should the render throw
// something else after that failure, the failure, met first, is what is thrown.
class RenderFunction {
 public:
  using Function = std::function<Frame(GlContext&, const Scene&, const RenderParams&)>;
  RenderFunction() = default;
  template <class F, class = std::enable_if_t<std::is_constructible_v<Function, F>>>
  RenderFunction(F f) : function_(std::move(f)) {}
  Frame operator()(GlContext& context, const Scene& scene, const RenderParams& params) const;
  explicit operator bool() const { return bool(function_); }

 private:
  Function function_;
};

// A pass table that other --params select in place of a technique's default one (modern.gems16's
// kernel=bicubic, modern.csm without its mip chain): the --params that select it, and its table.
struct PassVariant {
  std::map<std::string, std::string> params;  // --param key=value, as RenderParams::extra
  PassTable passes;
};

// Which module declares a technique: the OpenGL 1.x fixed-function pipelines (legacy_gl/), the
// GLSL techniques (modern/) or the ray-traced truth (reference/). Set by the registry from the
// module's list (registry/registry.cpp), never read from the name.
enum class TechniqueFamily { kLegacy, kModern, kReference };

struct Technique {
  std::string name;                                   // "legacy.pcf"
  TechniqueFamily family = TechniqueFamily::kModern;  // set by the registry
  std::string paper;                                  // "Brabec & Seidel 2001, §3"
  std::string summary;                                // one line
  std::string status;                                 // "complete", or what is missing
  ContextNeeds needs;
  std::vector<ParamSpec> params;          // the --param keys it understands, declared once
  CommonOptions reads;                    // the common options its render reads
  PlanTraits plan;                        // what the pass planner asks of it
  PassTable passes;                       // its passes, declared once (core/technique/pass_table.h)
  std::vector<PassVariant> passVariants;  // the tables other --params select instead
  // What its visibility approximates: the point light's hard shadow (shadow maps, volumes,
  // reference.hard) or the spherical light's soft one (smoothies, reference.soft). The bench
  // and the figures score it against the matching ray-traced truth.
  enum class Light { kPoint, kArea };
  Light light = Light::kPoint;
  // What its visibility is across a point light's shadow edge with its default parameters: the
  // binary result of a depth or stencil test per pixel (hard), or a fraction filtered over a
  // footprint (filtered: PCF kernels, the driver's 2x2 compare, prefiltered maps). The figures
  // group techniques by it (figures/figure_list.cpp error-vs-time); light = kArea is "soft".
  enum class Edge { kHard, kFiltered };
  Edge edge = Edge::kHard;
  RenderFunction render;
};

bool readsOption(const Technique& t, CommonOption o);
// "soft" (light = kArea), "filtered" or "hard" (Technique::edge).
const char* shadowGroup(const Technique& t);
// Its default pass table, then each variant's (Technique::passVariants).
std::vector<const PassTable*> allPassTables(const Technique& t);
std::vector<std::string> paramKeys(const Technique& t);  // its --param keys, in declared order
// Its declaration of `key`, or nullptr when it has no such --param.
const ParamSpec* findParam(const Technique& t, const std::string& key);

// The context a technique needs for the given parameters.
ContextSpec contextFor(const Technique& t, const RenderParams& p);

// Checks the generic parameters and that every --param key is one the technique knows;
// throws InputError naming the problem. `maxTextureSize` bounds the shadow map.
void checkParams(const Technique& t, const RenderParams& p, int maxTextureSize);

// Times one pass: glFinish() before and after, so the time is the pass's own GPU+CPU work.
// Also checks GL errors at the end of the pass: the destructor does not throw, it notes the
// error (core/base/errors.h noteGlError), and the next pass, checkGl or the end of the render
// throws it as GlError naming the pass.
//
// The pass declares itself here: `section` is the paper's section, equation or figure it
// follows ("Brabec & Seidel §4, Eq. (1), Fig. 5"); the file and function of the call are filled
// in by the compiler (the function that opens the timer is the pass's function). While a
// GlTrace runs, the GL calls made inside the timer become the pass's state lines.
class PassTimer {
 public:
  PassTimer(Frame& frame, std::string name, std::string section = "",
            const char* file = __builtin_FILE(), const char* function = __builtin_FUNCTION());
  ~PassTimer();
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

 private:
  Frame& frame_;
  PassTime pass_;
  double start_;
};

// A source file path as the compiler spelled it, relative to the source tree
// ("/work/x/legacy_gl/fast_pcf.cpp" -> "legacy_gl/fast_pcf.cpp").
std::string sourceRelativePath(const std::string& file);

double nowMilliseconds();

// Reads the current read buffer as float RGBA (rows bottom-up).
Image readColorBuffer(int x, int y, int width, int height);

}  // namespace sl
