// The write-back of imaging/write_back.cpp: where the state is trivial, the texture upload and
// blit must leave exactly the framebuffer the driver's glDrawPixels leaves (bit for bit, no
// tolerance: both write the same bytes); where any fragment operation of glspec121 4.1 (or a
// colour mask, zoom, texturing, ...) could act, the emulation must fall back to glDrawPixels
// and still give its framebuffer. Every case runs twice on the same start image: the fastest
// path, then glDrawPixels forced (WriteBackPath::kDrawPixels), and compares whole windows.
#include <dlfcn.h>
#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "imaging/internal.h"
#include "imaging_test_util.h"

// After core/gl/gl.h, which includes GL/gl.h with the extension prototypes it needs.
#include <GL/osmesa.h>

namespace sl::imaging::detail {
namespace {
using namespace sl::imaging::testing;

// Odd sizes: rows of no round length, and a copy that sticks out of the window on two sides.
constexpr int kWindowWidth = 67, kWindowHeight = 45;
constexpr int kCopyWidth = 40, kCopyHeight = 30;

// A gamma table (every entry distinct): the copy changes every pixel, so an emulated call
// that wrote nothing, or wrote the source unchanged, would show.
void enableGammaTable() {
  std::vector<float> table(256 * 4);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 4; ++c) table[size_t(i * 4 + c)] = std::sqrt(float(i) / 255.0f);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 256, GL_RGBA, GL_FLOAT, table.data());
  glEnable(GL_COLOR_TABLE);
}

void enableBlur() {
  const std::vector<float> k = binomialBlur3x3Rgba();
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, k.data());
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  glEnable(GL_CONVOLUTION_2D);
}

struct Outcome {
  std::vector<uint8_t> pixels;
  bool blit = false;
};

// Starts from the same window, runs `state` then `operation` with the write-back `path`, and
// returns the window and the path the last write took.
// `accumulation`: ask for the visual's accumulation buffer (false: the emulated one, whose
// GL_RETURN is imaging/'s write).
Outcome run(WriteBackPath path, const std::function<void()>& state,
            const std::function<void()>& operation, bool accumulation = true) {
  auto ctx = emulatedContext(kWindowWidth, kWindowHeight, ColorFormat::kRgba8, accumulation);
  putImage(kWindowWidth, kWindowHeight, patternImage(kWindowWidth, kWindowHeight, 7));
  currentState()->writeBack.forced = path;
  state();
  operation();
  Outcome out;
  out.blit = currentState()->writeBack.lastWasBlit;
  glDisable(GL_SCISSOR_TEST);
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  out.pixels = readRgba8(0, 0, kWindowWidth, kWindowHeight);
  EXPECT_TRUE(drainErrors().empty());
  return out;
}

// A copy from the lower left to a raster position that clips it on the right and the top.
void copyClipped() {
  glWindowPos2i(kWindowWidth - kCopyWidth / 2, kWindowHeight - kCopyHeight / 2);
  glCopyPixels(0, 0, kCopyWidth, kCopyHeight, GL_COLOR);
}
void copyToOrigin() {
  glWindowPos2i(3, 2);
  glCopyPixels(5, 4, kCopyWidth, kCopyHeight, GL_COLOR);
}
// glDrawPixels of client memory at a position left of and below the window (clipped there).
void drawClipped() {
  const std::vector<uint8_t> image = patternImage(kCopyWidth, kCopyHeight, 11);
  glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
  glRasterPos2i(0, 0);  // valid, then moved outside the window by glWindowPos
  glWindowPos2i(-7, -5);
  glDrawPixels(kCopyWidth, kCopyHeight, GL_RGBA, GL_UNSIGNED_BYTE, image.data());
}

size_t differingBytes(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  size_t n = 0;
  for (size_t i = 0; i < a.size() && i < b.size(); ++i) n += a[i] != b[i];
  return n + (a.size() > b.size() ? a.size() - b.size() : b.size() - a.size());
}

void expectBlitEqualsDrawPixels(const std::function<void()>& state,
                                const std::function<void()>& operation) {
  const Outcome fast = run(WriteBackPath::kFastest, state, operation);
  const Outcome reference = run(WriteBackPath::kDrawPixels, state, operation);
  EXPECT_TRUE(fast.blit) << "a trivial state must take the blit";
  EXPECT_FALSE(reference.blit);
  EXPECT_EQ(differingBytes(fast.pixels, reference.pixels), 0u);
  // The operation changed the window (a write that did nothing would also "match").
  const Outcome untouched = run(
      WriteBackPath::kFastest, [] {}, [] {});
  EXPECT_GT(differingBytes(fast.pixels, untouched.pixels), size_t(kCopyWidth));
}

TEST(WriteBack, PlainCopyPixelsBlitsAndMatchesTheDriversCopyPixels) {
  // No imaging state: the forced run is the driver's own glCopyPixels (the emulation forwards
  // it); the fast run reads and blits (4.3.3). Source and destination overlap, and the second
  // copy is clipped by the window.
  expectBlitEqualsDrawPixels([] {}, copyToOrigin);
  expectBlitEqualsDrawPixels([] {}, copyClipped);
}

TEST(WriteBack, CopyPixelsWithColorTableBlitsAndMatchesDrawPixels) {
  expectBlitEqualsDrawPixels(enableGammaTable, copyToOrigin);
  expectBlitEqualsDrawPixels(enableGammaTable, copyClipped);
}

TEST(WriteBack, CopyPixelsWithConvolutionBlitsAndMatchesDrawPixels) {
  expectBlitEqualsDrawPixels(enableBlur, copyToOrigin);
  expectBlitEqualsDrawPixels(enableBlur, copyClipped);
}

TEST(WriteBack, DrawPixelsClippedLeftAndBelowBlitsAndMatchesDrawPixels) {
  expectBlitEqualsDrawPixels(enableGammaTable, drawClipped);
}

TEST(WriteBack, DitheringEnabledStillBlits) {
  // GL_DITHER is enabled initially (4.1.7); both paths must give the exact 8-bit values.
  expectBlitEqualsDrawPixels(
      [] {
        glEnable(GL_DITHER);
        enableGammaTable();
      },
      copyToOrigin);
}

// States where a fragment operation acts: the emulation must fall back to glDrawPixels (the
// blit would ignore the operation) and leave the window glDrawPixels leaves; the operation
// must also have changed the result against the trivial state, or the case would prove nothing.
void expectFallback(const std::string& name, const std::function<void()>& extra) {
  SCOPED_TRACE(name);
  const auto state = [&] {
    enableGammaTable();
    extra();
  };
  const Outcome fast = run(WriteBackPath::kFastest, state, copyToOrigin);
  const Outcome reference = run(WriteBackPath::kDrawPixels, state, copyToOrigin);
  EXPECT_FALSE(fast.blit) << "the state is not trivial: glDrawPixels must run";
  EXPECT_EQ(differingBytes(fast.pixels, reference.pixels), 0u);
  const Outcome trivial = run(WriteBackPath::kFastest, enableGammaTable, copyToOrigin);
  EXPECT_GT(differingBytes(fast.pixels, trivial.pixels), 0u);
}

TEST(WriteBack, NonTrivialFragmentStateFallsBackToDrawPixels) {
  expectFallback("blending (4.1.6)", [] {
    glBlendFunc(GL_ONE, GL_ONE);
    glEnable(GL_BLEND);
  });
  expectFallback("colour mask (4.2.2)", [] { glColorMask(GL_TRUE, GL_FALSE, GL_TRUE, GL_FALSE); });
  expectFallback("scissor test (4.1.2)", [] {
    glScissor(10, 8, 12, 9);
    glEnable(GL_SCISSOR_TEST);
  });
  expectFallback("alpha test (4.1.3)", [] {
    glAlphaFunc(GL_GREATER, 0.5f);
    glEnable(GL_ALPHA_TEST);
  });
  expectFallback("pixel zoom (3.6.4)", [] { glPixelZoom(2.0f, 1.0f); });
  expectFallback("texturing on unit 1 (3.8)", [] {
    GLuint tex = 0;
    glGenTextures(1, &tex);
    glActiveTexture(GL_TEXTURE1);
    glBindTexture(GL_TEXTURE_2D, tex);
    const uint8_t green[4] = {0, 255, 0, 255};
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 1, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, green);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexEnvi(GL_TEXTURE_ENV, GL_TEXTURE_ENV_MODE, GL_MODULATE);
    glEnable(GL_TEXTURE_2D);
    glActiveTexture(GL_TEXTURE0);
  });
}

TEST(WriteBack, FractionalRasterPositionFallsBack) {
  // 3.6.4: fragment centres decide; a blit would have to round the position itself.
  const auto state = enableGammaTable;
  const auto op = [] {
    // Identity matrices: object (0, 0) is the window centre, (33.5, 22.5) here.
    glRasterPos2i(0, 0);
    glCopyPixels(5, 4, kCopyWidth, kCopyHeight, GL_COLOR);
  };
  const Outcome fast = run(WriteBackPath::kFastest, state, op);
  const Outcome reference = run(WriteBackPath::kDrawPixels, state, op);
  EXPECT_FALSE(fast.blit);
  EXPECT_EQ(differingBytes(fast.pixels, reference.pixels), 0u);
}

TEST(WriteBack, AccumReturnBlitsUnlessTheColourMaskActs) {
  const auto accumulate = [] {
    glClear(GL_ACCUM_BUFFER_BIT);
    glAccum(GL_LOAD, 0.75f);
    glAccum(GL_RETURN, 1.25f);
  };
  constexpr bool kEmulatedAccum = false;
  const Outcome fast = run(
      WriteBackPath::kFastest, [] {}, accumulate, kEmulatedAccum);
  const Outcome reference = run(
      WriteBackPath::kDrawPixels, [] {}, accumulate, kEmulatedAccum);
  EXPECT_TRUE(fast.blit);
  EXPECT_EQ(differingBytes(fast.pixels, reference.pixels), 0u);
  const auto masked = [] { glColorMask(GL_FALSE, GL_TRUE, GL_TRUE, GL_TRUE); };
  const Outcome maskedFast = run(WriteBackPath::kFastest, masked, accumulate, kEmulatedAccum);
  const Outcome maskedReference =
      run(WriteBackPath::kDrawPixels, masked, accumulate, kEmulatedAccum);
  EXPECT_FALSE(maskedFast.blit);
  EXPECT_EQ(differingBytes(maskedFast.pixels, maskedReference.pixels), 0u);
  EXPECT_GT(differingBytes(maskedFast.pixels, fast.pixels), 0u);
  // Scissored RETURN writes the box only (4.2.4); the blit applies the same box.
  const auto scissored = [] {
    glScissor(9, 7, 20, 11);
    glEnable(GL_SCISSOR_TEST);
  };
  const Outcome boxFast = run(WriteBackPath::kFastest, scissored, accumulate, kEmulatedAccum);
  const Outcome boxReference =
      run(WriteBackPath::kDrawPixels, scissored, accumulate, kEmulatedAccum);
  EXPECT_TRUE(boxFast.blit);
  EXPECT_EQ(differingBytes(boxFast.pixels, boxReference.pixels), 0u);
}

// Why the emulation does not write into the buffer it gave OSMesaMakeCurrent: on Mesa 22's
// gallium OSMesa the GL renders into its own resource and copies it into that buffer at
// glFinish, so a direct write is never seen by glReadPixels and is overwritten by the next
// finish. (A Mesa that rendered into the buffer itself would fail this test; the direct write
// could then be reconsidered.)
TEST(WriteBack, DirectWritesIntoTheOsmesaBufferAreInvisibleToTheGl) {
  auto ctx = emulatedContext(kWindowWidth, kWindowHeight);
  void* library = dlopen("libOSMesa.so.8", RTLD_NOW | RTLD_NOLOAD);
  ASSERT_NE(library, nullptr);
  const auto getCurrent = reinterpret_cast<decltype(&::OSMesaGetCurrentContext)>(
      dlsym(library, "OSMesaGetCurrentContext"));
  const auto getBuffer =
      reinterpret_cast<decltype(&::OSMesaGetColorBuffer)>(dlsym(library, "OSMesaGetColorBuffer"));
  ASSERT_TRUE(getCurrent != nullptr && getBuffer != nullptr);
  glClearColor(1, 0, 0, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  glFinish();
  GLint w = 0, h = 0, format = 0;
  void* buffer = nullptr;
  ASSERT_EQ(getBuffer(getCurrent(), &w, &h, &format, &buffer), GL_TRUE);
  ASSERT_EQ(w, kWindowWidth);
  auto* bytes = static_cast<uint8_t*>(buffer);
  EXPECT_EQ(bytes[0], 255);  // the finish copied the clear into the buffer
  std::fill(bytes, bytes + size_t(w) * h * 4, uint8_t(0x40));
  const std::vector<uint8_t> seen = readRgba8(0, 0, 1, 1);
  EXPECT_EQ(seen[0], 255) << "the GL read the direct write";
  EXPECT_EQ(seen[1], 0);
  glFinish();
  EXPECT_EQ(bytes[1], 0) << "glFinish did not overwrite the direct write";
  dlclose(library);
}

}  // namespace
}  // namespace sl::imaging::detail
