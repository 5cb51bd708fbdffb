// core/technique.h — the one interface every shadow technique implements (legacy_gl/,
// modern/, reference/): render a scene with parameters into a Frame.
//
// A technique is plain data: a name, its citation, what context it needs and a render
// function. legacy_gl/ and modern/ each export a list; apps/ and tests put them together.
#pragma once

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/image.h"
#include "core/scene.h"

namespace sl {

// Arithmetic precision of the colour channels that carry encoded depth (Brabec–Seidel §6):
// 8 bits (their Octane/O2 buffers), 12 bits (Octane VPro: a 16-bit buffer quantised to 12)
// and float (no 2001 limits).
enum class Precision { k8, k12, kFloat };
const char* precisionName(Precision p);
Precision parsePrecision(const std::string& s);  // "8", "12", "float"; throws InputError

struct RenderParams {
  int width = 800;             // window, pixels (Brabec–Seidel §5)
  int height = 600;
  int shadowMapTexels = 512;   // side of the square shadow map (Brabec–Seidel §5)
  int filter = 2;              // PCF footprint side: 1 = unfiltered, 2, 3, 4
  Precision precision = Precision::k8;
  Backend backend = Backend::kOsmesa;
  bool capturePasses = false;  // fill Frame::intermediates (--dump-passes)
  std::map<std::string, std::string> extra;  // --param key=value, technique specific

  // Typed access to `extra` with range checks; unknown keys are reported by checkParams.
  double number(const std::string& key, double fallback, double lo, double hi) const;
  int integer(const std::string& key, int fallback, int lo, int hi) const;
  std::string text(const std::string& key, const std::string& fallback,
                   const std::vector<std::string>& allowed) const;
  bool flag(const std::string& key, bool fallback) const;
};

struct PassTime {
  std::string name;
  double milliseconds = 0.0;
};

struct PassImage {
  std::string name;  // file-name friendly: "1-light-pass-ramp-depth"
  std::string caption;
  Image image;
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

struct Technique {
  std::string name;      // "legacy.pcf"
  std::string paper;     // "Brabec & Seidel 2001, §3"
  std::string summary;   // one line
  std::string status;    // "complete", or what is missing
  ContextNeeds needs;
  std::vector<std::string> paramKeys;  // --param keys it understands
  std::function<Frame(GlContext&, const Scene&, const RenderParams&)> render;
};

// The context a technique needs for the given parameters.
ContextSpec contextFor(const Technique& t, const RenderParams& p);

// Checks the generic parameters and that every --param key is one the technique knows;
// throws InputError naming the problem. `maxTextureSize` bounds the shadow map.
void checkParams(const Technique& t, const RenderParams& p, int maxTextureSize);

// Times one pass: glFinish() before and after, so the time is the pass's own GPU+CPU work.
// Also checks GL errors at the end of the pass (throws GlError naming the pass).
class PassTimer {
 public:
  PassTimer(Frame& frame, std::string name);
  ~PassTimer() noexcept(false);
  PassTimer(const PassTimer&) = delete;
  PassTimer& operator=(const PassTimer&) = delete;

 private:
  Frame& frame_;
  std::string name_;
  double start_;
};

double nowMilliseconds();

// Reads the current read buffer as float RGBA (rows bottom-up).
Image readColorBuffer(int x, int y, int width, int height);

}  // namespace sl
