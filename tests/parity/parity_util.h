// The parity harness (issue 10): every case runs once through the emulation on Debian's
// OSMesa (imaging/ installed) and once natively on the reference Mesa 7.8.2
// (../shared/reference-gl), and the outcomes are compared: 8-bit data bit for bit, float data
// within 1e-6, and the GL errors raised.
//
// Only one reference context can be bound at a time (core/gl/context.h), so each run creates
// its own context and destroys it before the next one is made.
#pragma once

#include <sys/stat.h>

#include <cstdlib>
#include <functional>
#include <memory>
#include <string>

#include "imaging/imaging_test_util.h"
#include "interpose/preloaded_context.h"

namespace sl::imaging::testing {

constexpr int kParityW = 16, kParityH = 12;  // small: every case is cheap
// Float comparisons: both sides compute in single precision from the same inputs; 1e-6 is a
// few ulps at 1.0, the bound issue 10 sets for float paths.
constexpr float kFloatTolerance = 1e-6f;

inline bool referenceAvailable() {
  const std::string path = referenceGlPath();
  struct stat st {};
  return !path.empty() && stat(path.c_str(), &st) == 0;
}

#define SL_REQUIRE_REFERENCE()                                                           \
  if (!::sl::imaging::testing::referenceAvailable())                                     \
  GTEST_SKIP() << "parity skipped: the reference GL (Mesa 7.8.2) is not available; set " \
                  "SHADOWLAB_REFERENCE_GL or place it at ../shared/reference-gl"

struct Outcome {
  std::vector<uint8_t> bytes;  // 8-bit results, compared bit for bit
  std::vector<float> floats;   // float results, compared within kFloatTolerance
  std::vector<GLenum> errors;  // errors raised during the case, in order
  // Per byte: 1 where the exact value written lies in [kMesaSaturationStart, 254.5/255),
  // which the reference writes as 255 (departures_test.cpp, ReferenceSaturatesAbove0996).
  // Filled by the scenario from the emulation's float result; only the emulated one is used.
  std::vector<uint8_t> saturationBand;
};

// Mesa 7.8 converts floats to unsigned bytes with a shortcut that maps every value from
// 0x3f7f0000 (0.99609375) up to 255, where rounding to nearest gives 254 below 254.5/255.
constexpr float kMesaSaturationStart = 0.99609375f;
inline bool inSaturationBand(float v) { return v >= kMesaSaturationStart && v < 254.5f / 255.0f; }

using Scenario = std::function<void(Outcome&)>;

// SHADOWLAB_PARITY_PATH=preloaded (ctest parity.preloaded_path, with LD_PRELOAD=
// "libshadowlab-imaging.so libOSMesa.so.8"): the Debian side runs on a context made through
// the process's global symbols, so every call of the scenario goes through the drop-in
// library's exports and its emulation, as an unchanged program's calls do
// (interpose/preloaded_context.h); the reference side is unchanged.
inline bool preloadedPath() {
  const char* v = std::getenv("SHADOWLAB_PARITY_PATH");
  return v != nullptr && std::string(v) == "preloaded";
}

// Runs `scenario` on a fresh context of `backend`; the emulation is installed on Debian's
// OSMesa (the reference keeps its native imaging). `accumulation` false makes the Debian
// context without an accumulation buffer, so the emulated one is used.
inline Outcome runOn(Backend backend, const Scenario& scenario, bool accumulation = true,
                     int w = kParityW, int h = kParityH) {
  ContextSpec spec;
  spec.backend = backend;
  spec.width = w;
  spec.height = h;
  spec.accumulation = backend == Backend::kReference ? true : accumulation;
  std::unique_ptr<interpose::PreloadedOsmesaContext> preloaded;
  std::unique_ptr<GlContext> ctx;
  const bool throughLibrary = backend == Backend::kOsmesa && preloadedPath();
  if (throughLibrary)
    preloaded = std::make_unique<interpose::PreloadedOsmesaContext>(w, h, spec.accumulation);
  else
    ctx = GlContext::create(spec);
  // Through the library, the context already names GL_ARB_imaging (the library's), so this
  // process's own imaging/ stays out and the library's emulation answers.
  const Mode mode = install(throughLibrary ? preloaded->context() : *ctx);
  EXPECT_EQ(mode, backend == Backend::kOsmesa && !throughLibrary ? Mode::kEmulated : Mode::kNative);
  Outcome o;
  scenario(o);
  const auto tail = drainErrors();
  o.errors.insert(o.errors.end(), tail.begin(), tail.end());
  return o;
}

inline void expectSame(const Outcome& emulated, const Outcome& reference) {
  EXPECT_EQ(emulated.errors, reference.errors) << "GL errors differ";
  ASSERT_EQ(emulated.bytes.size(), reference.bytes.size());
  int reported = 0;
  for (size_t i = 0; i < emulated.bytes.size() && reported < 8; ++i) {
    const bool explained = emulated.bytes[i] == 254 && reference.bytes[i] == 255 &&
                           i < emulated.saturationBand.size() && emulated.saturationBand[i];
    if (emulated.bytes[i] != reference.bytes[i] && !explained) {
      ADD_FAILURE() << "byte " << i << " (pixel " << i / 4 << ", component " << i % 4
                    << "): emulated " << int(emulated.bytes[i]) << ", reference "
                    << int(reference.bytes[i]);
      ++reported;
    }
  }
  ASSERT_EQ(emulated.floats.size(), reference.floats.size());
  for (size_t i = 0; i < emulated.floats.size() && reported < 8; ++i) {
    if (!(std::fabs(emulated.floats[i] - reference.floats[i]) <= kFloatTolerance)) {
      ADD_FAILURE() << "float " << i << ": emulated " << emulated.floats[i] << ", reference "
                    << reference.floats[i];
      ++reported;
    }
  }
}

// Runs the scenario on both back ends and compares.
inline void checkParity(const Scenario& scenario, bool emulatedAccumulation = false) {
  const Outcome reference = runOn(Backend::kReference, scenario);
  const Outcome emulated = runOn(Backend::kOsmesa, scenario, !emulatedAccumulation);
  expectSame(emulated, reference);
}

// Everything the imaging subset can enable, switched off; identity matrix and scale/bias.
inline void resetImaging() {
  for (GLenum cap :
       {GL_COLOR_TABLE, GL_POST_CONVOLUTION_COLOR_TABLE, GL_POST_COLOR_MATRIX_COLOR_TABLE,
        GL_CONVOLUTION_1D, GL_CONVOLUTION_2D, GL_SEPARABLE_2D, GL_HISTOGRAM, GL_MINMAX})
    glDisable(cap);
  glMatrixMode(GL_COLOR);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  for (GLenum p : {GL_RED_SCALE, GL_GREEN_SCALE, GL_BLUE_SCALE, GL_ALPHA_SCALE,
                   GL_POST_CONVOLUTION_RED_SCALE, GL_POST_CONVOLUTION_GREEN_SCALE,
                   GL_POST_CONVOLUTION_BLUE_SCALE, GL_POST_CONVOLUTION_ALPHA_SCALE,
                   GL_POST_COLOR_MATRIX_RED_SCALE, GL_POST_COLOR_MATRIX_GREEN_SCALE,
                   GL_POST_COLOR_MATRIX_BLUE_SCALE, GL_POST_COLOR_MATRIX_ALPHA_SCALE})
    glPixelTransferf(p, 1.0f);
  for (GLenum p : {GL_RED_BIAS, GL_GREEN_BIAS, GL_BLUE_BIAS, GL_ALPHA_BIAS,
                   GL_POST_CONVOLUTION_RED_BIAS, GL_POST_CONVOLUTION_GREEN_BIAS,
                   GL_POST_CONVOLUTION_BLUE_BIAS, GL_POST_CONVOLUTION_ALPHA_BIAS,
                   GL_POST_COLOR_MATRIX_RED_BIAS, GL_POST_COLOR_MATRIX_GREEN_BIAS,
                   GL_POST_COLOR_MATRIX_BLUE_BIAS, GL_POST_COLOR_MATRIX_ALPHA_BIAS})
    glPixelTransferf(p, 0.0f);
}

// A grey pattern (R = G = B) with an independent alpha: where the reference indexes or
// counts luminance with R for all three components (its README, departures 2 and 6), grey
// input makes the specification's answer and its answer the same.
inline std::vector<uint8_t> greyPattern(int w, int h, unsigned seed) {
  auto px = patternImage(w, h, seed);
  for (size_t p = 0; p < px.size(); p += 4) px[p + 1] = px[p + 2] = px[p];
  return px;
}

inline void appendBytes(Outcome& o, const std::vector<uint8_t>& v) {
  o.bytes.insert(o.bytes.end(), v.begin(), v.end());
}
inline void appendFloats(Outcome& o, const std::vector<float>& v) {
  o.floats.insert(o.floats.end(), v.begin(), v.end());
}

// Reads the window with every stage off (what the framebuffer holds).
inline std::vector<uint8_t> readWindow() {
  resetImaging();
  return readRgba8(0, 0, kParityW, kParityH);
}

}  // namespace sl::imaging::testing
