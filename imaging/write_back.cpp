// imaging/write_back.cpp — how the emulation's 8-bit results go back into the framebuffer.
//
// An emulated glDrawPixels / glCopyPixels ends with the driver's
// glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, bytes) at the current raster position, and
// glAccum(GL_RETURN) with the same call under switched-off fragment operations. On llvmpipe
// that draw costs tens of memcpys of the image (docs/imaging.md), more than the whole
// transform. When the state makes the result of DrawPixels a plain copy of the bytes into the
// window, the same pixels are written with a texture upload and one glBlitNamedFramebuffer,
// which the OpenGL 4.5 specification (18.3.1) lets bypass the fragment pipeline except the
// pixel ownership test, the scissor test and sRGB conversion. Every condition below names
// the section of glspec121 (or glspec14) that makes the fragment operation it excludes a
// no-op; when one does not hold, the driver's glDrawPixels runs, as before.
//
// The upload is flipped (image row r in texture row h-1-r) and blitted with srcY0 > srcY1,
// a mirror the GL defines (4.5, 18.3.1): the window system framebuffer of Mesa's state
// tracker is stored top row first, so the two mirrors cancel and llvmpipe copies memory
// (util_try_blit_via_copy_region) instead of drawing a textured quad. The result is the same
// on any implementation; only the speed depends on that. Candidates measured against
// glDrawPixels in imaging_bench ("write-back" rows, docs/imaging.md): direct writes into the
// buffer OSMesaMakeCurrent was given are NOT legal on Mesa 22's gallium OSMesa: it renders
// into its own resource and copies it into that buffer on glFinish, so the GL never reads
// what is written there (tests/imaging/write_back_test.cpp shows it).
#include <cmath>
#include <cstring>

#include "imaging/internal.h"

namespace sl::imaging::detail {
namespace {

constexpr GLint kTextureLevel = 0;

bool enabled(const State& s, GLenum cap) { return s.driver.IsEnabled(cap) != GL_FALSE; }

GLint integer(const State& s, GLenum pname) {
  GLint v = 0;
  s.driver.GetIntegerv(pname, &v);
  return v;
}

// The entry points of the blit path (OpenGL 4.5 direct state access: no binding of the
// caller's changes).
bool haveBlitEntries(const State& s) {
  const GlDispatch& d = s.driver;
  return s.context->caps().hasExtension("GL_ARB_direct_state_access") &&
         d.CreateTextures != nullptr && d.TextureStorage2D != nullptr &&
         d.TextureSubImage2D != nullptr && d.CreateFramebuffers != nullptr &&
         d.NamedFramebufferTexture != nullptr && d.BlitNamedFramebuffer != nullptr &&
         d.GetQueryiv != nullptr;
}

// Where the blit writes: the window system framebuffer of an 8-bit RGBA context, with
// nothing bound over it that the upload or the blit would read or write.
bool blitTargetIsWindow(const State& s) {
  if (framebufferType(s) != GL_UNSIGNED_BYTE) return false;  // the texture is RGBA8
  if (!haveBlitEntries(s)) return false;
  // 4.2.1: DrawPixels writes the draw buffers of the bound draw framebuffer; the blit below
  // names framebuffer 0, so the caller's must be 0.
  if (integer(s, GL_DRAW_FRAMEBUFFER_BINDING) != 0) return false;
  // sRGB conversion is the one colour operation a blit does that DrawPixels need not.
  if (enabled(s, GL_FRAMEBUFFER_SRGB)) return false;
  // 4.2.2 "Fine Control of Buffer Updates": a blit ignores the colour mask.
  GLboolean mask[4] = {GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE};
  s.driver.GetBooleanv(GL_COLOR_WRITEMASK, mask);
  return mask[0] != GL_FALSE && mask[1] != GL_FALSE && mask[2] != GL_FALSE && mask[3] != GL_FALSE;
}

// Texturing (3.8) of the fragments: the DrawPixels fragment carries the raster position's
// texture coordinates (3.6.4 "Conversion to Fragments") and every enabled unit applies.
bool texturingDisabled(const State& s) {
  const GlDispatch& d = s.driver;
  const bool rectangle = s.context->caps().hasExtension("GL_ARB_texture_rectangle");
  const GLint active = integer(s, GL_ACTIVE_TEXTURE);
  const GLint units = integer(s, GL_MAX_TEXTURE_UNITS);  // fixed-function units (1.3)
  bool off = true;
  for (GLint u = 0; u < units && off; ++u) {
    d.ActiveTexture(GLenum(GL_TEXTURE0 + u));
    off = !enabled(s, GL_TEXTURE_1D) && !enabled(s, GL_TEXTURE_2D) && !enabled(s, GL_TEXTURE_3D) &&
          !enabled(s, GL_TEXTURE_CUBE_MAP) && !(rectangle && enabled(s, GL_TEXTURE_RECTANGLE));
  }
  d.ActiveTexture(GLenum(active));
  return off;
}

// No fragment program, texturing, colour sum or fog changes a DrawPixels fragment's colour
// (3.8 - 3.10), and no per-fragment operation of 4.1 but the pixel ownership test acts.
bool fragmentsPassUnchanged(const State& s) {
  const Capabilities& caps = s.context->caps();
  // Programs replace the fixed-function fragment stages (GL 2.0 shaders, ARB/ATI programs).
  if (integer(s, GL_CURRENT_PROGRAM) != 0) return false;
  if (caps.hasExtension("GL_ARB_fragment_program") && enabled(s, GL_FRAGMENT_PROGRAM_ARB))
    return false;
  if (caps.hasExtension("GL_ATI_fragment_shader") && enabled(s, GL_FRAGMENT_SHADER_ATI))
    return false;
  // glspec14 3.9 "Color Sum": applied when enabled, and always when lighting is enabled.
  if (enabled(s, GL_COLOR_SUM) || enabled(s, GL_LIGHTING)) return false;
  if (enabled(s, GL_FOG)) return false;  // 3.10 Fog
  // 4.1.2 scissor (a blit would apply it too, but the clip below assumes the window),
  // 4.1.3 alpha test, 4.1.4 stencil test (also its writes), 4.1.5 depth test (the depth
  // buffer is written only when it is enabled), 4.1.6 blending, 4.1.8 logical operation.
  for (GLenum cap : {GL_SCISSOR_TEST, GL_ALPHA_TEST, GL_STENCIL_TEST, GL_DEPTH_TEST, GL_BLEND,
                     GL_COLOR_LOGIC_OP})
    if (enabled(s, cap)) return false;
  if (caps.depthBoundsTest() && enabled(s, GL_DEPTH_BOUNDS_TEST_EXT)) return false;
  // glspec14 4.1.3 "Multisample Fragment Operations": only with sample buffers.
  if (integer(s, GL_SAMPLE_BUFFERS) != 0) return false;
  // 4.1.7 Dithering needs no condition: it chooses c1 in {max(0, ceil(c) - 1), ceil(c)}, and
  // for the exact 8-bit values written here (c = k) the undithered k is one of the two, so
  // the blit's k is a result the specification allows DrawPixels; llvmpipe's DrawPixels gives
  // k too (write_back_test.cpp compares with dithering enabled, its initial state).
  if (!texturingDisabled(s)) return false;
  // Fragments counted by an occlusion query (glspec14 4.1.6 "Occlusion Queries"); a blit
  // generates none.
  GLint query = 0;
  s.driver.GetQueryiv(GL_SAMPLES_PASSED, GL_CURRENT_QUERY, &query);
  if (query != 0) return false;
  if (caps.hasExtension("GL_ARB_occlusion_query2")) {
    s.driver.GetQueryiv(GL_ANY_SAMPLES_PASSED, GL_CURRENT_QUERY, &query);
    if (query != 0) return false;
  }
  // Rasterizer discard (GL 3.0) drops DrawPixels fragments, not blits.
  return !enabled(s, GL_RASTERIZER_DISCARD);
}

// The window rectangle DrawPixels fills: 3.6.4 "Conversion to Fragments" with zoom (1, 1)
// and an integral raster position puts group (n, m) at (xrp + n, yrp + m) exactly.
bool drawPixelsRectangle(const State& s, int& x, int& y) {
  // 5.2 Selection and 5.3 Feedback: outside GL_RENDER, DrawPixels writes no pixels.
  if (integer(s, GL_RENDER_MODE) != GL_RENDER) return false;
  // 2.12: an invalid raster position makes DrawPixels do nothing (the callers check it too).
  GLboolean valid = GL_FALSE;
  s.driver.GetBooleanv(GL_CURRENT_RASTER_POSITION_VALID, &valid);
  if (valid == GL_FALSE) return false;
  GLfloat zoom[2] = {0, 0};
  s.driver.GetFloatv(GL_ZOOM_X, &zoom[0]);
  s.driver.GetFloatv(GL_ZOOM_Y, &zoom[1]);
  if (zoom[0] != 1.0f || zoom[1] != 1.0f) return false;
  GLfloat position[4] = {0, 0, 0, 0};
  s.driver.GetFloatv(GL_CURRENT_RASTER_POSITION, position);
  // Within int range and integral (a fractional position shifts fragments by the centre rule).
  constexpr float kMaxCoordinate = 1 << 24;  // floats are exact integers up to here
  for (int i = 0; i < 2; ++i)
    if (!(std::abs(position[i]) < kMaxCoordinate) || position[i] != float(int(position[i])))
      return false;
  x = int(position[0]);
  y = int(position[1]);
  return true;
}

// The texture the image is uploaded into and its framebuffer, made once per context at the
// window's size. DEVIATION (house rule "RAII for GL objects"): they belong to the context and
// are freed with it — the emulation's state outlives the OSMesa context by a few
// instructions (core/gl/context.cpp destroys the context first), so no destructor may call GL.
void ensureTexture(State& s) {
  WriteBack& wb = s.writeBack;
  const int w = s.context->spec().width, h = s.context->spec().height;
  if (wb.texture != 0 && wb.width == w && wb.height == h) return;
  s.driver.CreateTextures(GL_TEXTURE_2D, 1, &wb.texture);
  s.driver.TextureStorage2D(wb.texture, 1, GL_RGBA8, w, h);
  s.driver.CreateFramebuffers(1, &wb.framebuffer);
  s.driver.NamedFramebufferTexture(wb.framebuffer, GL_COLOR_ATTACHMENT0, wb.texture, kTextureLevel);
  wb.width = w;
  wb.height = h;
}

// Uploads the first h rows of the flipped buffer (w groups each, image row r in buffer row
// h-1-r) into the texture and mirrors them into the window at (x, y) with one blit; the
// rectangle must lie inside the window.
void uploadAndBlit(State& s, int x, int y, int w, int h) {
  ensureTexture(s);
  {
    ClientTransfers tight(s);  // also unbinds a pixel unpack buffer: the upload reads ours
    s.driver.TextureSubImage2D(s.writeBack.texture, kTextureLevel, 0, 0, w, h, GL_RGBA,
                               GL_UNSIGNED_BYTE, s.writeBack.flipped.data());
  }
  s.driver.BlitNamedFramebuffer(s.writeBack.framebuffer, 0, 0, h, w, 0, x, y, x + w, y + h,
                                GL_COLOR_BUFFER_BIT, GL_NEAREST);
}

// Writes rows [0, h) of the tight RGBA8 image `bytes` (w groups a row, bottom row first) with
// its lower left group at window (x, y), clipped to the window (4.1.1: the window owns no
// pixel outside it), by a flipped upload and a mirroring blit.
void blitBytes(State& s, int x, int y, int w, int h, const uint8_t* bytes) {
  const int ww = s.context->spec().width, wh = s.context->spec().height;
  const int x0 = std::max(x, 0), y0 = std::max(y, 0);
  const int x1 = int(std::min<long>(long(x) + w, ww)), y1 = int(std::min<long>(long(y) + h, wh));
  if (x1 <= x0 || y1 <= y0) return;
  const int cw = x1 - x0, ch = y1 - y0;
  const size_t rowBytes = size_t(cw) * 4;
  std::vector<uint8_t>& flipped = s.writeBack.flipped;
  flipped.resize(rowBytes * size_t(ch));  // every byte is written below
  const uint8_t* first = bytes + (size_t(y0 - y) * size_t(w) + size_t(x0 - x)) * 4;
  for (int r = 0; r < ch; ++r)
    std::memcpy(flipped.data() + size_t(ch - 1 - r) * rowBytes, first + size_t(r) * w * 4,
                rowBytes);
  uploadAndBlit(s, x0, y0, cw, ch);
}

void drawPixelsBytes(State& s, int w, int h, const uint8_t* bytes) {
  ClientTransfers tight(s);
  s.driver.DrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, bytes);
}

}  // namespace

bool blitEqualsDrawPixels(State& s, int& x, int& y) {
  if (s.writeBack.forced == WriteBackPath::kDrawPixels) return false;
  return blitTargetIsWindow(s) && drawPixelsRectangle(s, x, y) && fragmentsPassUnchanged(s);
}

bool blitEqualsReturn(State& s) {
  if (s.writeBack.forced == WriteBackPath::kDrawPixels) return false;
  // 4.2.4: RETURN applies only the pixel ownership and scissor tests, dithering (see
  // fragmentsPassUnchanged) and the colour mask (blitTargetIsWindow). The scissor box is
  // the region RETURN writes, and the blit applies the scissor test too.
  return blitTargetIsWindow(s);
}

void drawBytes(State& s, int w, int h, const uint8_t* bytes) {
  if (w <= 0 || h <= 0) return;
  int x = 0, y = 0;
  if (blitEqualsDrawPixels(s, x, y)) {
    s.writeBack.lastWasBlit = true;
    return blitBytes(s, x, y, w, h, bytes);
  }
  s.writeBack.lastWasBlit = false;
  drawPixelsBytes(s, w, h, bytes);
}

uint8_t* returnRows(State& s, int w, int h) {
  s.writeBack.flipped.resize(size_t(w) * size_t(h) * 4);  // the caller writes every byte
  return s.writeBack.flipped.data();
}

void blitReturnRows(State& s, int x, int y, int w, int h) {
  uploadAndBlit(s, x, y, w, h);
  s.writeBack.lastWasBlit = true;
}

}  // namespace sl::imaging::detail
