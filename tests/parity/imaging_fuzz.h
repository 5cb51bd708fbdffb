// Differential fuzzing of the imaging subset: a seeded generator of random but valid GL call
// sequences (color tables of every internal format with scale/bias, color matrices, 1D/2D/
// separable convolutions under every border mode, histogram/minmax with and without sink,
// pixel-transfer scale/bias, the accumulation buffer, and DrawPixels/CopyPixels/ReadPixels/
// TexImage2D/CopyTexImage2D through the pipeline), an executor that makes a sequence's calls on
// the current context, and a comparison of the emulation's outcome with the reference's
// (Mesa 7.8.2) under the documented tie rules and departures (parity_util.h,
// departures_test.cpp, ../shared/reference-gl/README.md).
//
// The generator stays clear of the reference's documented departures where a departure would
// hide everything behind it (see Generator constraints in imaging_fuzz.cpp); the departures it
// can still reach are recognised per value by compare() and counted by name, never silently.
// No gtest here: the developer tool tools/imaging_fuzz.cpp links this file too.
#pragma once

#include <cstdint>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/gl/context.h"

namespace sl::imaging::fuzz {

// One GL call (or a short fixed idiom, such as "read the window") with its arguments.
enum class Kind {
  kPixelTransfer,            // e[0] pname, f[0] value
  kColorTable,               // e: target, internalformat, type; i[0] width; f data (RGBA)
  kColorTableParameter,      // e: target, pname (SCALE/BIAS); f[0..3]
  kCopyColorTable,           // e: target, internalformat; i: x, y, width
  kEnable,                   // e[0] cap
  kDisable,                  // e[0] cap
  kLoadColorMatrix,          // f[0..15] column-major
  kConvolutionFilter1D,      // e[0] internalformat; i[0] width; f data (RGBA floats)
  kConvolutionFilter2D,      // e[0] internalformat; i: width, height; f data
  kSeparableFilter2D,        // e[0] internalformat; i: width, height; f row (4w) then column (4h)
  kCopyConvolutionFilter2D,  // e[0] internalformat; i: x, y, width, height
  kConvolutionBorder,        // e: target, mode; f[0..3] border color
  kConvolutionScaleBias,     // e: target, pname (FILTER_SCALE/BIAS); f[0..3]
  kHistogram,                // e: internalformat; i: width, sink
  kMinmax,                   // e: internalformat; i: sink
  kScissor,                  // i: x, y, w, h
  kAccum,                    // e[0] op; f[0] value
  kReadPixels,               // e[0] type (UNSIGNED_BYTE/FLOAT); i: x, y, w, h  -> recorded
  kCopyPixels,               // i: x, y, w, h, dx, dy
  kDrawPixels,               // i: w, h, dx, dy; b data (RGBA8)
  kTexImage2D,               // i: w, h; b data -> texels recorded (GetTexImage)
  kCopyTexImage2D,           // i: x, y, w, h -> texels recorded
  kGetHistogram,             // e[0] format; i[0] reset -> recorded (GL_FLOAT counts)
  kGetMinmax,                // e[0] format; i[0] reset -> recorded (GL_FLOAT)
  kGetColorTable,            // e: target, format -> recorded (GL_FLOAT)
};

struct Call {
  Kind kind;
  std::vector<uint32_t> e;  // enums
  std::vector<int> i;       // integers
  std::vector<float> f;     // floats
  std::vector<uint8_t> b;   // bytes
  int group = 0;            // the feature it belongs to (its definition, enable and queries)
};

// Every sequence runs in a kWindow x kWindow window (RGBA8, cleared to 0).
constexpr int kWindow = 16;

struct Sequence {
  uint64_t seed = 0;
  int w = 8, h = 8;            // the image, at the window's origin (4..kWindow each)
  std::vector<uint8_t> image;  // RGBA8, w*h*4
  std::vector<Call> calls;
};

// Where a recorded value came from: decides which documented departure can explain it.
enum class Origin : uint8_t {
  kWindow,      // the window read at the end with every stage off (identity path)
  kReadPixels,  // glReadPixels through the pipeline
  kTexture,     // glGetTexImage after TexImage2D/CopyTexImage2D
  kHistogram,   // glGetHistogram counts
  kMinmax,      // glGetMinmax values
  kColorTable,  // glGetColorTable
};

struct Record {
  std::vector<uint8_t> bytes;
  std::vector<Origin> byteOrigin;
  std::vector<float> floats;
  std::vector<Origin> floatOrigin;
  std::vector<uint8_t> floatConvolved;  // 1 where a convolution was enabled for the read
  // Per call, the GL errors it raised (in order); calls that raised none are absent.
  std::map<int, std::vector<uint32_t>> errors;
  // Exact mode only (the emulation on a float colour buffer): the value each byte of `bytes`
  // had before its conversion to 8 bits, so the comparison can tell a rounding tie.
  std::vector<float> exact;
  // Per byte, where it came from as far as the tie rules care: glReadPixels(UNSIGNED_BYTE),
  // which the reference truncates (departures_test.cpp AdditionalA), a glAccum(GL_RETURN)
  // result (accumulation ties), a texel, or none of these.
  std::vector<uint8_t> truncatable;
};

// Generates the sequence of `seed` (deterministic: the same seed gives the same sequence on
// every platform: std::mt19937_64 and integer arithmetic only).
Sequence generate(uint64_t seed);

// Makes the sequence's calls on the current context (a kWindow x kWindow window), after
// putting back the state an earlier sequence may have left.
// exact: the context has a float colour buffer; bytes are read back as floats into
// Record::exact instead (and textures are GL_RGBA32F).
Record execute(const Sequence& s, bool exact);

// The outcome of one sequence on the three contexts it needs: the emulation on Debian's OSMesa
// (8-bit, the one compared), the emulation on a float colour buffer (its exact values), and
// the reference. The contexts are made on the first call and kept for the process; whatever
// context was current before is not current afterwards. Throws GlError when a context cannot
// be made.
struct Runs {
  Record emulated, exact, reference;
};
Runs runAll(const Sequence& s);

// The comparison. Each value that differs is either explained (by name: a documented tie rule
// or departure) or not.
struct Verdict {
  std::map<std::string, int> explained;  // name -> count
  std::vector<std::string> unexplained;  // one line per difference (first few)
  int unexplainedCount = 0;
  std::set<std::string> classes;  // kinds of the unexplained differences, e.g. "float (origin 4)"
  bool agree() const { return unexplainedCount == 0; }
};
Verdict compare(const Sequence& s, const Runs& runs);

// Readable C: the calls as a paste-able block (the image as an array, then each call).
std::string toC(const Sequence& s);

// Drops whole features (a table with its parameters, enable and queries), then single calls
// that define nothing, while the sequence still has an unexplained difference of the first
// class it had; returns
// the shortest sequence found (each try runs the three contexts again).
Sequence minimise(const Sequence& s);

}  // namespace sl::imaging::fuzz
