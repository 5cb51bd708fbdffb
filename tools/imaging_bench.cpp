// imaging_bench — speed of the imaging emulation.
//
// Every operation on 512x512, 800x600 and 1024x1024 RGBA8, timed (best of 5 after one warm-up;
// the stage and the memcpy best of 20) as a ratio to a memcpy of the same w*h*4 bytes
// measured in the same run:
//   * emulated: imaging/ installed on Debian's OSMesa (llvmpipe), the whole GL call;
//   * reference: the same call natively on Mesa 7.8.2 (../shared/reference-gl), when present;
//   * stage: the emulation's transform alone (the 8-bit byte path where it applies, else
//     runPipeline on a float RGBA image), the part imaging/ controls; the GL call adds the
//     driver's read-back and the write-back.
//   * stage without the matrix vectors: where the colour matrix is the only stage, the same
//     transform without imaging/color_matrix_groups.cpp (the byte path's scalar loops, or for
//     client groups the general path's float image), in the same run: what the vectors save.
//     The dense-matrix glDrawPixels rows' stage is the transform from the client groups
//     (GL_RGBA / GL_RGB of bytes or floats) to the bytes the call writes;
//   * emulated, glDrawPixels write-back: the same call with imaging/'s write-back forced to
//     the driver's glDrawPixels (what every emulated call used before write_back.cpp).
//   * preloaded: the same GL call made the way an unchanged program makes it, through
//     libshadowlab-imaging.so by LD_PRELOAD (interpose/preloaded_context.h): this tool runs
//     itself once per size with the library preloaded (--preloaded-run WxH) and reads its
//     ratios; the last column divides its time by the emulated call's.
// The "write-back:" rows time the candidate ways of putting a w x h RGBA8 image into the
// window (imaging/write_back.cpp explains the choice).
// Prints one markdown table. Usage: build/bin/imaging_bench [--quick] [--cpu] [--only TEXT]
#include <dlfcn.h>
#include <time.h>

#include <CLI/CLI.hpp>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "core/base/errors.h"
#include "core/gl/context.h"
#include "imaging/imaging.h"
#include "imaging/internal.h"
#include "interpose/preloaded_context.h"

// After core/gl/gl.h, which includes GL/gl.h with the extension prototypes it needs.
#include <GL/osmesa.h>

namespace sl::imaging::bench {
namespace {
using namespace sl::gl;
using Clock = std::chrono::steady_clock;

constexpr int kRepetitions = 5;
// --cpu: time with the process CPU clock (all threads) instead of the wall clock, for a
// machine shared with other jobs, where wall time measures the queue more than the work.
bool gCpuClock = false;
// --only TEXT: only the operations whose name contains TEXT (for profiling one of them).
std::string gOnly;

double nowMs() {
  if (gCpuClock) {
    timespec ts{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts);
    return double(ts.tv_sec) * 1e3 + double(ts.tv_nsec) * 1e-6;
  }
  return std::chrono::duration<double, std::milli>(Clock::now().time_since_epoch()).count();
}

double bestMs(const std::function<void()>& run, int reps) {
  run();  // warm-up
  double best = 1e30;
  for (int i = 0; i < reps; ++i) {
    const double t0 = nowMs();
    run();
    best = std::min(best, nowMs() - t0);
  }
  return best;
}

// Samples of the memcpy base and of each stage: the best of as many as the other, so that
// neither ratio term gets more chances to miss the other jobs of a shared machine.
constexpr int kSamplesPerRepetition = 4;

double memcpyMs(size_t bytes, int reps) {
  std::vector<unsigned char> a(bytes, 1), b(bytes, 2);
  volatile unsigned char sink = 0;
  const double ms = bestMs(
      [&] {
        std::memcpy(b.data(), a.data(), bytes);
        sink = sink + b[bytes / 2];
      },
      reps * kSamplesPerRepetition);
  return ms;
}

// ---- the operations, identical GL calls on either back end ----
void brabecSeidelTable() {
  std::vector<uint8_t> table(256 * 4);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 4; ++c) table[i * 4 + c] = i == 0 ? 0 : (c == 3 ? 63 : 64);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 256, GL_RGBA, GL_UNSIGNED_BYTE, table.data());
  glEnable(GL_COLOR_TABLE);
}
// A table with a different entry for every byte (a gamma curve): no step structure, so the
// per-byte table lookup, not the vector step map.
void gammaTable() {
  std::vector<float> table(256 * 4);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 4; ++c) table[size_t(i * 4 + c)] = std::pow(float(i) / 255.0f, 1.0f / 2.2f);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 256, GL_RGBA, GL_FLOAT, table.data());
  glEnable(GL_COLOR_TABLE);
}
void sumIntoAlpha() {
  const float m[16] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1};
  glMatrixMode(GL_COLOR);
  glLoadMatrixf(m);
  glMatrixMode(GL_MODELVIEW);
}
// A dense colour matrix with no table before it (every byte value distinct): the float sum
// per group, the general case of the byte path.
void luminanceMatrix() {
  const float m[16] = {0.299f, 0.299f, 0.299f, 0, 0.587f, 0.587f, 0.587f, 0,
                       0.114f, 0.114f, 0.114f, 0, 0,      0,      0,      1};
  glMatrixMode(GL_COLOR);
  glLoadMatrixf(m);
  glMatrixMode(GL_MODELVIEW);
}
// A dense 4x4 colour matrix with negative entries and entries above 1 (a saturation boost
// with a hue shift and alpha mixed in; the post-color-matrix bias 0.02): the general case of
// glColorMatrix, results below 0 and above 1 clamped by the final conversion.
void denseMatrix() {
  const float m[16] = {1.35f,  -0.12f, -0.21f, 0.05f, -0.28f, 1.42f,  -0.17f, 0.1f,
                       -0.07f, -0.3f,  1.38f,  0.2f,  0.04f,  -0.02f, 0.03f,  0.75f};
  glMatrixMode(GL_COLOR);
  glLoadMatrixf(m);
  glMatrixMode(GL_MODELVIEW);
  for (GLenum bias : {GL_POST_COLOR_MATRIX_RED_BIAS, GL_POST_COLOR_MATRIX_GREEN_BIAS,
                      GL_POST_COLOR_MATRIX_BLUE_BIAS, GL_POST_COLOR_MATRIX_ALPHA_BIAS})
    glPixelTransferf(bias, 0.02f);
}
// Client groups of the dense-matrix glDrawPixels rows: the bench image's bytes in `format`
// (GL_RGBA or GL_RGB) and `type` (GL_UNSIGNED_BYTE or GL_FLOAT, as bytes / 255).
const std::vector<uint8_t>& clientGroups(GLenum format, GLenum type, int w, int h) {
  static std::vector<uint8_t> data;
  static GLenum madeFormat = 0, madeType = 0;
  static size_t madeGroups = 0;
  const size_t groups = size_t(w) * h;
  if (madeFormat == format && madeType == type && madeGroups == groups) return data;
  const int n = format == GL_RGBA ? 4 : 3;
  const size_t size = type == GL_FLOAT ? sizeof(float) : 1;
  data.assign(groups * size_t(n) * size, 0);
  for (size_t i = 0; i < groups * size_t(n); ++i) {
    const uint8_t v = uint8_t((i * 2654435761u) >> 24);
    if (type == GL_FLOAT) {
      const float f = float(v) / 255.0f;
      std::memcpy(data.data() + i * sizeof f, &f, sizeof f);
    } else {
      data[i] = v;
    }
  }
  madeFormat = format, madeType = type, madeGroups = groups;
  return data;
}
std::function<void(int, int)> drawGroups(GLenum format, GLenum type) {
  return [format, type](int w, int h) {
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glWindowPos2i(0, 0);
    glDrawPixels(w, h, format, type, clientGroups(format, type, w, h).data());
    glFinish();
  };
}
void blur3x3() {
  const std::vector<float> k = detail::binomialBlur3x3Rgba();
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, k.data());
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  glEnable(GL_CONVOLUTION_2D);
}
void packingKernel() {  // Brabec–Seidel Eq. (1)
  float k[9 * 4] = {};
  k[(0 * 3 + 0) * 4 + 0] = 1;
  k[(0 * 3 + 1) * 4 + 1] = 1;
  k[(1 * 3 + 0) * 4 + 2] = 1;
  k[(1 * 3 + 1) * 4 + 3] = 1;
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, k);
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  glEnable(GL_CONVOLUTION_2D);
}
void resetAll() {
  for (GLenum cap : {GL_COLOR_TABLE, GL_CONVOLUTION_2D}) glDisable(cap);
  glMatrixMode(GL_COLOR);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  for (GLenum bias : {GL_POST_COLOR_MATRIX_RED_BIAS, GL_POST_COLOR_MATRIX_GREEN_BIAS,
                      GL_POST_COLOR_MATRIX_BLUE_BIAS, GL_POST_COLOR_MATRIX_ALPHA_BIAS})
    glPixelTransferf(bias, 0.0f);
}

struct Operation {
  const char* name;
  std::function<void()> setup;
  std::function<void(int, int)> run;
  bool noStage = false;     // no imaging/ transform of its own (accumulation buffer, floor rows)
  bool osmesaOnly = false;  // a write-back candidate of Debian's OSMesa: no reference call
  bool writesBack = true;   // ends in imaging/'s write-back (the glDrawPixels column applies)
  // glDrawPixels of client groups in this format and type (0: the framebuffer's RGBA8 bytes):
  // the stage is the emulation's transform from those groups to the bytes it writes.
  GLenum clientFormat = 0, clientType = 0;
};

// ---- write-back candidates: one w x h RGBA8 image into the window at (0, 0) ----
const std::vector<uint8_t>& writeImage(int w, int h) {
  static std::vector<uint8_t> img;
  if (img.size() != size_t(w) * h * 4) {
    img.resize(size_t(w) * h * 4);
    for (size_t i = 0; i < img.size(); ++i) img[i] = uint8_t((i * 40503u) >> 8);
  }
  return img;
}
void writeDrawPixels(int w, int h) {
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glWindowPos2i(0, 0);
  glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, writeImage(w, h).data());
  glFinish();
}
// imaging/'s own write-back (write_back.cpp): flipped upload and mirrored blit.
void writeImaging(int w, int h) {
  glWindowPos2i(0, 0);
  detail::drawBytes(*detail::currentState(), w, h, writeImage(w, h).data());
  glFinish();
}
// The texture and framebuffer the two candidates below upload into (made once per size).
struct UploadTarget {
  GLuint texture = 0, framebuffer = 0;
  int w = 0, h = 0;
};
UploadTarget gUploadTarget;  // reset by measure(): its names die with each context
UploadTarget& uploadTarget(int w, int h) {
  UploadTarget& t = gUploadTarget;
  if (t.w != w || t.h != h) {
    glCreateTextures(GL_TEXTURE_2D, 1, &t.texture);
    glTextureStorage2D(t.texture, 1, GL_RGBA8, w, h);
    glCreateFramebuffers(1, &t.framebuffer);
    glNamedFramebufferTexture(t.framebuffer, GL_COLOR_ATTACHMENT0, t.texture, 0);
    t.w = w;
    t.h = h;
  }
  return t;
}
// Upload as is and blit without a mirror (Mesa's window is stored top row first, so the
// blit flips rows and llvmpipe draws it).
void writeBlitUnmirrored(int w, int h) {
  const UploadTarget& t = uploadTarget(w, h);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.texture, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, writeImage(w, h).data());
  glBlitNamedFramebuffer(t.framebuffer, 0, 0, 0, w, h, 0, 0, w, h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  glFinish();
}
// Upload and one screen-aligned textured quad (identity matrices, GL_REPLACE).
void writeQuad(int w, int h) {
  const UploadTarget& t = uploadTarget(w, h);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glTextureSubImage2D(t.texture, 0, 0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, writeImage(w, h).data());
  glBindTexture(GL_TEXTURE_2D, t.texture);
  glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_REPLACE);
  glEnable(GL_TEXTURE_2D);
  glBegin(GL_QUADS);
  glTexCoord2f(0, 0);
  glVertex2f(-1, -1);
  glTexCoord2f(1, 0);
  glVertex2f(1, -1);
  glTexCoord2f(1, 1);
  glVertex2f(1, 1);
  glTexCoord2f(0, 1);
  glVertex2f(-1, 1);
  glEnd();
  glDisable(GL_TEXTURE_2D);
  glFinish();
}
// A memcpy into the buffer given to OSMesaMakeCurrent: fast but NOT a write-back on Mesa 22's
// gallium OSMesa, which never reads that buffer (tests/imaging/write_back_test.cpp).
void writeOsmesaBuffer(int w, int h) {
  static void* library = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_NOLOAD);
  if (library == nullptr) return;
  static const auto getCurrent = reinterpret_cast<decltype(&::OSMesaGetCurrentContext)>(
      dlsym(library, "OSMesaGetCurrentContext"));
  static const auto getBuffer =
      reinterpret_cast<decltype(&::OSMesaGetColorBuffer)>(dlsym(library, "OSMesaGetColorBuffer"));
  GLint bw = 0, bh = 0, format = 0;
  void* buffer = nullptr;
  if (getBuffer == nullptr || !getBuffer(getCurrent(), &bw, &bh, &format, &buffer)) return;
  if (bw != w || bh != h) return;
  std::memcpy(buffer, writeImage(w, h).data(), size_t(w) * h * 4);
}

void copyPixels(int w, int h) {
  glWindowPos2i(0, 0);
  glCopyPixels(0, 0, w, h, GL_COLOR);
  glFinish();
}

// The floor under every emulated call: the driver's own read-back and draw of the 8-bit
// image, with nothing of imaging/ in between (the pipeline is identity, so both forward).
void readBack(int w, int h) {
  static std::vector<uint8_t> pixels;
  pixels.resize(size_t(w) * h * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
}
void readBackAndDraw(int w, int h) {
  static std::vector<uint8_t> pixels;
  pixels.resize(size_t(w) * h * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glWindowPos2i(0, 0);
  glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, pixels.data());
  glFinish();
}

std::vector<Operation> allOperations();
std::vector<Operation> operations() {
  std::vector<Operation> ops;
  for (Operation& op : allOperations())
    if (gOnly.empty() || std::string(op.name).find(gOnly) != std::string::npos)
      ops.push_back(std::move(op));
  return ops;
}

std::vector<Operation> allOperations() {
  return {
      {"floor: glReadPixels RGBA8 (driver only)", [] {}, readBack, true, false, false},
      {"floor: glReadPixels + glDrawPixels RGBA8 (driver only)", [] {}, readBackAndDraw, true,
       false, false},
      {"write-back: glDrawPixels RGBA8 (driver; the old write-back)", [] {}, writeDrawPixels, true,
       false, false},
      {"write-back: imaging/ (flipped upload + mirrored glBlitNamedFramebuffer)", [] {},
       writeImaging, true, true},
      {"write-back: upload + glBlitNamedFramebuffer without the mirror", [] {}, writeBlitUnmirrored,
       true, true, false},
      {"write-back: upload + one textured quad", [] {}, writeQuad, true, true, false},
      {"write-back: memcpy into the OSMesa buffer (NOT seen by the GL)", [] {}, writeOsmesaBuffer,
       true, true, false},
      {"plain copy (glCopyPixels)", [] {}, copyPixels, false, false, false},
      {"+ RGBA color table (Brabec-Seidel 0/64)", brabecSeidelTable, copyPixels},
      {"+ RGBA color table (gamma 1/2.2, 256 distinct entries)", gammaTable, copyPixels},
      {"+ color table + sum-into-alpha color matrix (Fig. 4)",
       [] {
         brabecSeidelTable();
         sumIntoAlpha();
       },
       copyPixels},
      {"+ colour matrix alone (RGB to luminance, dense 3x3 block)", luminanceMatrix, copyPixels},
      {"+ dense 4x4 colour matrix (negative and >1 entries, post bias)", denseMatrix, copyPixels},
      {"glDrawPixels GL_RGBA GL_UNSIGNED_BYTE + dense 4x4 colour matrix", denseMatrix,
       drawGroups(GL_RGBA, GL_UNSIGNED_BYTE), false, false, true, GL_RGBA, GL_UNSIGNED_BYTE},
      {"glDrawPixels GL_RGB GL_UNSIGNED_BYTE + dense 4x4 colour matrix", denseMatrix,
       drawGroups(GL_RGB, GL_UNSIGNED_BYTE), false, false, true, GL_RGB, GL_UNSIGNED_BYTE},
      {"glDrawPixels GL_RGBA GL_FLOAT + dense 4x4 colour matrix", denseMatrix,
       drawGroups(GL_RGBA, GL_FLOAT), false, false, true, GL_RGBA, GL_FLOAT},
      {"glDrawPixels GL_RGB GL_FLOAT + dense 4x4 colour matrix", denseMatrix,
       drawGroups(GL_RGB, GL_FLOAT), false, false, true, GL_RGB, GL_FLOAT},
      {"+ 3x3 convolution", blur3x3, copyPixels},
      {"glCopyTexSubImage2D + 3x3 packing kernel (Eq. 1)", packingKernel,
       [](int w, int h) {
         glCopyTexSubImage2D(GL_TEXTURE_2D, 0, 0, 0, 0, 0, w, h);
         glFinish();
       },
       false, false, false},
      {"glAccum(GL_ACCUM, 0.25)", [] {},
       [](int, int) {
         glAccum(GL_ACCUM, 0.25f);
         glFinish();
       },
       true, false, false},
      {"glAccum(GL_RETURN, 1)", [] {},
       [](int, int) {
         glAccum(GL_RETURN, 1.0f);
         glFinish();
       },
       true},
  };
}

// Ratios of every operation on one back end; the context is made once per size.
// `preloaded`: the context is made through the drop-in library (this process was started
// with it preloaded); the rows that call imaging/ or OSMesa directly are left out.
std::vector<double> measure(Backend backend, int w, int h, int reps, double& memcpyRatioBase,
                            detail::WriteBackPath path = detail::WriteBackPath::kFastest,
                            bool preloaded = false) {
  std::vector<double> ratios;
  ContextSpec spec;
  spec.backend = backend;
  spec.width = w;
  spec.height = h;
  spec.accumulation = backend == Backend::kReference;  // Debian: the emulated buffer
  std::unique_ptr<GlContext> ctx;
  std::unique_ptr<interpose::PreloadedOsmesaContext> throughLibrary;
  if (preloaded) {
    throughLibrary = std::make_unique<interpose::PreloadedOsmesaContext>(w, h, spec.accumulation);
    imaging::install(throughLibrary->context());  // native: the library's GL_ARB_imaging
  } else {
    ctx = GlContext::create(spec);
    imaging::install(*ctx);
  }
  if (detail::currentState() != nullptr) detail::currentState()->writeBack.forced = path;
  gUploadTarget = UploadTarget{};
  std::vector<uint8_t> img(size_t(w) * h * 4);
  for (size_t i = 0; i < img.size(); ++i) img[i] = uint8_t((i * 2654435761u) >> 24);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glWindowPos2i(0, 0);
  glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, img.data());
  GLuint tex = 0;
  glGenTextures(1, &tex);
  glBindTexture(GL_TEXTURE_2D, tex);
  glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, img.data());
  glClear(GL_ACCUM_BUFFER_BIT);
  const double base = memcpyMs(size_t(w) * h * 4, reps);
  memcpyRatioBase = base;
  for (const Operation& op : operations()) {
    if ((op.osmesaOnly && (backend != Backend::kOsmesa || preloaded)) ||
        (path == detail::WriteBackPath::kDrawPixels && !op.writesBack)) {
      ratios.push_back(-1.0);
      continue;
    }
    op.setup();
    const double ms = bestMs([&] { op.run(w, h); }, reps);
    resetAll();
    ratios.push_back(ms / base);
  }
  glDeleteTextures(1, &tex);
  return ratios;
}

// The transform alone (imaging/'s part of the call) on a float image, best of as many runs as
// the memcpy it is divided by (kSamplesPerRepetition). `without`: where the colour matrix is
// the only stage, the same transform without the matrix vectors of
// imaging/color_matrix_groups.cpp (RGBA8 bytes: transformBytes' scalar loops; client groups:
// the float image of the general path), else -1.
struct StageRatios {
  std::vector<double> fast, without;
};
StageRatios measureStages(int w, int h, int repetitions, double base) {
  const int reps = repetitions * kSamplesPerRepetition;  // as many samples as the memcpy
  using namespace detail;
  ContextSpec spec;
  spec.width = 16;
  spec.height = 16;
  auto ctx = GlContext::create(spec);
  imaging::install(*ctx);
  StageRatios ratios;
  Image4 source(w, h);
  std::vector<uint8_t> bytes(source.px.size());
  for (size_t i = 0; i < source.px.size(); ++i) {
    bytes[i] = uint8_t((i * 2654435761u) >> 24);
    source.px[i] = float(bytes[i]) / 255.0f;
  }
  PixelStore tight;
  tight.alignment = 1;
  for (const Operation& op : operations()) {
    if (op.noStage) {
      ratios.fast.push_back(-1.0);
      ratios.without.push_back(-1.0);
      continue;
    }
    op.setup();
    State& s = *currentState();
    if (pipelineIsIdentity(s.transfer, Dimensionality::k2D)) {  // the call forwards: no stage
      resetAll();
      ratios.fast.push_back(-1.0);
      ratios.without.push_back(-1.0);
      continue;
    }
    const bool matrixOnly = matrixOnlyPipeline(s.transfer);
    double ms = 0, copyMs = 0, withoutMs = -1, withoutCopyMs = 0;
    if (op.clientFormat != 0) {  // glDrawPixels of client groups: to the bytes it writes
      const std::vector<uint8_t>& data = clientGroups(op.clientFormat, op.clientType, w, h);
      std::vector<uint8_t> out(size_t(w) * h * 4);
      auto general = [&] {  // unpack, the stages, the final conversion
        Image4 image = unpackImage(data.data(), w, h, op.clientFormat, op.clientType, tight);
        runPipeline(s.transfer, image, Dimensionality::k2D);
        packImage(image, out.data(), GL_RGBA, GL_UNSIGNED_BYTE, tight, true);
      };
      if (matrixGroupsApply(s.transfer, op.clientFormat, op.clientType)) {
        ms = bestMs(
            [&] {
              matrixGroupsToBytes(s.transfer, data.data(), w, h, op.clientFormat, op.clientType,
                                  tight, out.data());
            },
            reps);
        withoutMs = bestMs(general, reps);
      } else {
        ms = bestMs(general, reps);
      }
    } else if (convolveBytesApplies(s.transfer)) {  // what the call runs for 8-bit buffers
      std::vector<uint8_t> out;
      int ow = 0, oh = 0;
      ms = bestMs([&] { convolveBytes(s.transfer, bytes, w, h, out, ow, oh); }, reps);
    } else if (bytePathApplies(s.transfer)) {
      std::vector<uint8_t> work;
      ms = bestMs(
          [&] {
            work = bytes;
            transformBytes(s.transfer, work, w, h);
          },
          reps);
      copyMs = bestMs([&] { work = bytes; }, reps);
      if (matrixOnly) {
        withoutMs = bestMs(
            [&] {
              work = bytes;
              transformBytes(s.transfer, work, w, h, BytePath::kScalar);
            },
            reps);
        withoutCopyMs = copyMs;
      }
    } else {
      Image4 work;
      ms = bestMs(
          [&] {
            work = source;
            runPipeline(s.transfer, work, Dimensionality::k2D);
          },
          reps);
      copyMs = bestMs([&] { work = source; }, reps);
    }
    resetAll();
    ratios.fast.push_back(std::max(0.0, ms - copyMs) / base);  // the stages, without the copy
    ratios.without.push_back(withoutMs < 0 ? -1.0
                                           : std::max(0.0, withoutMs - withoutCopyMs) / base);
  }
  return ratios;
}

// The preloaded column for one size: this tool again, with the drop-in library and Debian's
// OSMesa preloaded, measuring with --preloaded-run; its ratios (to its own memcpy) and memcpy
// time. Empty when the library was not built next to this tool or the run failed.
struct PreloadedRun {
  std::vector<double> ratios;
  double base = 0;
};
PreloadedRun runPreloaded(int w, int h, int reps) {
  namespace fs = std::filesystem;
  const fs::path self = fs::read_symlink("/proc/self/exe");
  const fs::path library = self.parent_path() / ".." / "lib" / "libshadowlab-imaging.so";
  PreloadedRun run;
  if (!fs::exists(library)) return run;
  std::string cmd = "LD_PRELOAD='" + fs::canonical(library).string() + " libOSMesa.so.8' '" +
                    self.string() + "' --preloaded-run " + std::to_string(w) + "x" +
                    std::to_string(h) + (reps < kRepetitions ? " --quick" : "") +
                    (gCpuClock ? " --cpu" : "");
  if (!gOnly.empty()) cmd += " --only '" + gOnly + "'";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (pipe == nullptr) return run;
  double value = 0;
  if (std::fscanf(pipe, "base %lf", &run.base) == 1)
    while (std::fscanf(pipe, " %lf", &value) == 1) run.ratios.push_back(value);
  if (pclose(pipe) != 0 || run.ratios.size() != operations().size()) run = PreloadedRun{};
  return run;
}

}  // namespace

// Exit status for bad command-line input (the project's contract: one line on stderr, 2).
constexpr int kBadInputStatus = 2;

int run(int argc, char** argv) {
  bool quick = false;
  // CLI11 directly: imaging/ does not depend on apps/ (registry/cli.h parseTool does the same).
  CLI::App app{"speed of the imaging emulation as ratios to memcpy (markdown)", "imaging_bench"};
  app.add_flag("--quick", quick, "best of 2 instead of 5");
  app.add_flag("--cpu", gCpuClock, "time with the process CPU clock instead of the wall clock");
  app.add_option("--only", gOnly, "only the operations whose name contains TEXT")
      ->type_name("TEXT")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  // The preloaded column's measurement (runPreloaded runs it); not for people: no help line.
  std::string preloadedSize;
  app.add_option("--preloaded-run", preloadedSize)->group("");
  app.set_help_flag("-h,--help", "print this help and exit");  // listed last, as in the others
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp&) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  } catch (const CLI::ParseError& e) {
    std::string what = e.what();
    std::replace(what.begin(), what.end(), '\n', ' ');
    std::fprintf(stderr, "imaging_bench: %s (try: imaging_bench --help)\n", what.c_str());
    return kBadInputStatus;
  }
  if (operations().empty()) {
    std::string known;
    for (const Operation& op : allOperations())
      known += (known.empty() ? "" : ", ") + std::string(op.name);
    std::fprintf(stderr, "imaging_bench: --only '%s' matches no operation (known: %s)\n",
                 gOnly.c_str(), known.c_str());
    return kBadInputStatus;
  }
  const int reps = quick ? 2 : kRepetitions;
  if (!preloadedSize.empty()) {
    int w = 0, h = 0;
    if (std::sscanf(preloadedSize.c_str(), "%dx%d", &w, &h) != 2 || w <= 0 || h <= 0) {
      std::fprintf(stderr, "imaging_bench: --preloaded-run wants WxH, not '%s'\n",
                   preloadedSize.c_str());
      return kBadInputStatus;
    }
    double base = 0;
    std::vector<double> ratios;
    try {
      ratios = measure(Backend::kOsmesa, w, h, reps, base, detail::WriteBackPath::kFastest,
                       /*preloaded=*/true);
    } catch (const GlError& e) {
      constexpr int kGlFailureStatus = 3;  // the project's contract for a GL failure
      std::fprintf(stderr, "imaging_bench: --preloaded-run: %s\n", e.what());
      return kGlFailureStatus;
    }
    std::printf("base %.9g\n", base);
    for (double r : ratios) std::printf("%.9g\n", r);
    return 0;
  }
  const int sizes[][2] = {{512, 512}, {800, 600}, {1024, 1024}};
  const std::string refPath = referenceGlPath();
  const bool haveReference = !refPath.empty() && std::fopen(refPath.c_str(), "r") != nullptr;
  std::printf(
      "imaging_bench: ratios to memcpy of the same RGBA8 buffer in the same run, calls best of %d, "
      "stages and memcpy best of %d, %s time\n",
      reps, reps * kSamplesPerRepetition, gCpuClock ? "process CPU" : "wall");
  std::printf(
      "(emulated = imaging/ on Debian OSMesa llvmpipe; reference = Mesa 7.8.2 native%s; "
      "preloaded = the same call by an unchanged program through libshadowlab-imaging.so)\n\n",
      haveReference ? "" : ": NOT FOUND, column empty");
  std::printf(
      "| operation | size | stage (imaging/ transform) | stage without the matrix vectors | "
      "emulated call | emulated call, "
      "glDrawPixels write-back | reference call | emulated / reference | preloaded call | "
      "preloaded / emulated |\n"
      "| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n");
  const auto ops = operations();
  for (const auto& sz : sizes) {
    double base = 0, refBase = 0;
    double drawBase = 0;
    const auto emulated = measure(Backend::kOsmesa, sz[0], sz[1], reps, base);
    const PreloadedRun preloaded = runPreloaded(sz[0], sz[1], reps);
    const auto drawn =
        measure(Backend::kOsmesa, sz[0], sz[1], reps, drawBase, detail::WriteBackPath::kDrawPixels);
    const auto stages = measureStages(sz[0], sz[1], reps, base);
    std::vector<double> reference(ops.size(), -1.0);
    if (haveReference) reference = measure(Backend::kReference, sz[0], sz[1], reps, refBase);
    for (size_t i = 0; i < ops.size(); ++i) {
      char stage[32] = "-", without[32] = "-", ref[32] = "-", speed[32] = "-", old[32] = "-";
      if (drawn[i] >= 0 && ops[i].writesBack) std::snprintf(old, sizeof old, "%.1fx", drawn[i]);
      if (stages.fast[i] >= 0) std::snprintf(stage, sizeof stage, "%.1fx", stages.fast[i]);
      if (stages.without[i] >= 0)
        std::snprintf(without, sizeof without, "%.1fx", stages.without[i]);
      if (reference[i] >= 0 && emulated[i] >= 0) {
        std::snprintf(ref, sizeof ref, "%.0fx", reference[i]);
        // Both ratios are to a memcpy measured in the same process run: the quotient is the
        // reference's time over the emulation's (> 1: the emulation is faster).
        std::snprintf(speed, sizeof speed, "%.2f (%.1fx faster)",
                      (emulated[i] * base) / (reference[i] * refBase),
                      (reference[i] * refBase) / (emulated[i] * base));
      }
      char pre[32] = "-", preRatio[32] = "-";
      if (!preloaded.ratios.empty() && preloaded.ratios[i] >= 0) {
        std::snprintf(pre, sizeof pre, "%.1fx", preloaded.ratios[i]);
        // Each ratio is to its own process's memcpy: the quotient compares the two times.
        std::snprintf(preRatio, sizeof preRatio, "%.2f",
                      (preloaded.ratios[i] * preloaded.base) / (emulated[i] * base));
      }
      std::printf("| %s | %dx%d | %s | %s | %.1fx | %s | %s | %s | %s | %s |\n", ops[i].name, sz[0],
                  sz[1], stage, without, emulated[i], old, ref, speed, pre, preRatio);
    }
  }
  return 0;
}

}  // namespace sl::imaging::bench

int main(int argc, char** argv) { return sl::imaging::bench::run(argc, argv); }
