// Pixel buffer objects bound by the caller (ARB_pixel_buffer_object): with a buffer bound to
// GL_PIXEL_PACK_BUFFER or GL_PIXEL_UNPACK_BUFFER, a pixel command's pointer is an offset into
// it. The emulation's own reads and writes of the framebuffer (glCopyPixels through a colour
// table or a convolution, GL_ACCUM and GL_RETURN of the emulated accumulation buffer, on the
// blit write-back and on the glDrawPixels fallback) point at its own memory, so they must run
// with no buffer bound (imaging/internal.h ClientTransfers) and leave the caller's bindings as
// they were. The window after the same calls must not depend on the bindings.
#include <gtest/gtest.h>

#include <cmath>

#include "imaging/internal.h"
#include "imaging_test_util.h"

namespace sl::imaging::detail {
namespace {
using namespace sl::imaging::testing;

constexpr int kWidth = 67, kHeight = 45;
constexpr int kCopyWidth = 40, kCopyHeight = 30;
constexpr GLsizeiptr kBufferBytes = 64;  // far too small for any image: a read would fail

struct Outcome {
  std::vector<uint8_t> window;
  std::vector<GLenum> errors;
  GLint pack = -1, unpack = -1;  // the bindings after the calls
  GLuint packName = 0, unpackName = 0;
};

Outcome runCalls(bool bindBuffers) {
  constexpr bool kEmulatedAccum = false;
  auto ctx = emulatedContext(kWidth, kHeight, ColorFormat::kRgba8, kEmulatedAccum);
  EXPECT_TRUE(ctx->caps().hasExtension("GL_ARB_pixel_buffer_object"));
  putImage(kWidth, kHeight, patternImage(kWidth, kHeight, 5));
  // Tables and filters from client memory first (with an unpack buffer bound their pointers
  // would be offsets too).
  std::vector<float> table(256 * 4);
  for (int i = 0; i < 256; ++i)
    for (int c = 0; c < 4; ++c) table[size_t(i * 4 + c)] = std::sqrt(float(i) / 255.0f);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 256, GL_RGBA, GL_FLOAT, table.data());
  const std::vector<float> blur = binomialBlur3x3Rgba();
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, blur.data());
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPLICATE_BORDER);
  Outcome out;
  GLuint buffers[2] = {0, 0};
  glGenBuffers(2, buffers);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, buffers[0]);
  glBufferData(GL_PIXEL_PACK_BUFFER, kBufferBytes, nullptr, GL_STREAM_READ);
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, buffers[1]);
  glBufferData(GL_PIXEL_UNPACK_BUFFER, kBufferBytes, nullptr, GL_STREAM_DRAW);
  if (!bindBuffers) {
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  }
  out.packName = bindBuffers ? buffers[0] : 0;
  out.unpackName = bindBuffers ? buffers[1] : 0;
  glEnable(GL_COLOR_TABLE);  // the byte path: a read and a blit
  glWindowPos2i(20, 12);
  glCopyPixels(0, 0, kCopyWidth, kCopyHeight, GL_COLOR);
  glDisable(GL_COLOR_TABLE);
  glEnable(GL_CONVOLUTION_2D);  // the 8-bit convolution: a read and a blit
  glWindowPos2i(3, 2);
  glCopyPixels(10, 5, kCopyWidth, kCopyHeight, GL_COLOR);
  glColorMask(GL_TRUE, GL_TRUE, GL_FALSE, GL_TRUE);  // the glDrawPixels write-back
  glWindowPos2i(25, 9);
  glCopyPixels(0, 0, kCopyWidth, kCopyHeight, GL_COLOR);
  glDisable(GL_CONVOLUTION_2D);
  glClear(GL_ACCUM_BUFFER_BIT);
  glAccum(GL_LOAD, 0.75f);    // a read
  glAccum(GL_RETURN, 1.25f);  // glDrawPixels under the colour mask
  glColorMask(GL_TRUE, GL_TRUE, GL_TRUE, GL_TRUE);
  glAccum(GL_ACCUM, -0.25f);
  glAccum(GL_RETURN, 1.0f);  // the blit
  out.errors = drainErrors();
  glGetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &out.pack);
  glGetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &out.unpack);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);  // our own read of the window below
  glBindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  out.window = readRgba8(0, 0, kWidth, kHeight);
  glDeleteBuffers(2, buffers);
  return out;
}

TEST(PixelBuffers, EmulatedTransfersIgnoreTheCallersBoundBuffers) {
  const Outcome unbound = runCalls(false);
  const Outcome bound = runCalls(true);
  EXPECT_TRUE(unbound.errors.empty());
  EXPECT_TRUE(bound.errors.empty())
      << "first error 0x" << std::hex << (bound.errors.empty() ? 0u : bound.errors[0]);
  EXPECT_EQ(GLuint(bound.pack), bound.packName);  // rebound after each call
  EXPECT_EQ(GLuint(bound.unpack), bound.unpackName);
  EXPECT_NE(bound.packName, 0u);
  EXPECT_EQ(bound.window, unbound.window);
  EXPECT_NE(unbound.window, patternImage(kWidth, kHeight, 5));  // the calls drew something
}

}  // namespace
}  // namespace sl::imaging::detail
