// imaging/pixel_paths.cpp — the commands whose pixels go through the pixel-transfer
// operations (glspec121 3.6.4 DrawPixels, 4.3.2 ReadPixels, 4.3.3 CopyPixels, 3.8.1-3.8.2
// TexImage2D, TexSubImage2D, CopyTexImage2D, CopyTexSubImage2D, and their one-dimensional
// forms, the only ones GL_CONVOLUTION_1D applies to).
//
// When every stage is identity the call goes to the driver untouched. Otherwise the groups
// are read (client memory or framebuffer), transformed by runPipeline (pixel_transfer.cpp),
// clamped ("Final Conversion") and written through the driver with its own pixel transfer
// left at identity (the emulation owns the RGBA pixel-transfer state), in the destination's
// precision: unsigned bytes for an 8-bit colour buffer or texture, unsigned shorts for a
// 16-bit buffer, floats otherwise. 8-bit framebuffer writes go through write_back.cpp (a
// texture upload and a blit where that equals glDrawPixels, else glDrawPixels).
#include <cmath>
#include <cstring>

#include "imaging/internal.h"

namespace sl::imaging::detail {

// The client type that carries the destination's precision without loss.
GLenum framebufferType(const State& s) {
  switch (s.context->spec().color) {
    case ColorFormat::kRgba8: return GL_UNSIGNED_BYTE;
    case ColorFormat::kRgba16: return GL_UNSIGNED_SHORT;
    case ColorFormat::kRgba32f: return GL_FLOAT;
  }
  return GL_FLOAT;
}

ClientTransfers::ClientTransfers(const State& s) : gl_(s.driver) {
  if (s.pixelBuffers) {
    gl_.GetIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &pack_);
    gl_.GetIntegerv(GL_PIXEL_UNPACK_BUFFER_BINDING, &unpack_);
    if (pack_ != 0) gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, 0);
    if (unpack_ != 0) gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, 0);
  }
  gl_.PushClientAttrib(GL_CLIENT_PIXEL_STORE_BIT);
  for (GLenum p :
       {GL_UNPACK_ROW_LENGTH, GL_UNPACK_SKIP_PIXELS, GL_UNPACK_SKIP_ROWS, GL_UNPACK_SKIP_IMAGES,
        GL_UNPACK_IMAGE_HEIGHT, GL_PACK_ROW_LENGTH, GL_PACK_SKIP_PIXELS, GL_PACK_SKIP_ROWS})
    gl_.PixelStorei(p, 0);
  for (GLenum p :
       {GL_UNPACK_SWAP_BYTES, GL_UNPACK_LSB_FIRST, GL_PACK_SWAP_BYTES, GL_PACK_LSB_FIRST})
    gl_.PixelStorei(p, GL_FALSE);
  gl_.PixelStorei(GL_UNPACK_ALIGNMENT, 1);
  gl_.PixelStorei(GL_PACK_ALIGNMENT, 1);
}

ClientTransfers::~ClientTransfers() {
  gl_.PopClientAttrib();
  if (pack_ != 0) gl_.BindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(pack_));
  if (unpack_ != 0) gl_.BindBuffer(GL_PIXEL_UNPACK_BUFFER, GLuint(unpack_));
}

namespace {

bool eightBitTexture(GLenum internalformat) {
  switch (internalformat) {
    case 3:
    case 4:
    case GL_RGB:
    case GL_RGBA:
    case GL_RGB8:
    case GL_RGBA8:
    case GL_ALPHA:
    case GL_ALPHA8:
    case GL_LUMINANCE:
    case GL_LUMINANCE8:
    case GL_LUMINANCE_ALPHA:
    case GL_LUMINANCE8_ALPHA8:
    case GL_INTENSITY:
    case GL_INTENSITY8: return true;
    default: return false;
  }
}

// A depth internal format: glCopyTexImage then copies depth components (3.8.2), which the
// RGBA stages of 3.6.5 never touch, so the call belongs to the driver.
bool depthTexture(GLenum internalformat) {
  switch (internalformat) {
    case GL_DEPTH_COMPONENT:
    case GL_DEPTH_COMPONENT16:
    case GL_DEPTH_COMPONENT24:
    case GL_DEPTH_COMPONENT32:
    case GL_DEPTH_COMPONENT32F:
    case GL_DEPTH_STENCIL:
    case GL_DEPTH24_STENCIL8:
    case GL_DEPTH32F_STENCIL8: return true;
    default: return false;
  }
}

// The internal format of an existing texture level (for the sub-image copies).
GLenum levelFormat(const State& s, GLenum target, GLint level) {
  GLint format = 0;
  s.driver.GetTexLevelParameteriv(target, level, GL_TEXTURE_INTERNAL_FORMAT, &format);
  return GLenum(format);
}

// "Final Conversion": each component clamped to [0,1] (NaN becomes 0), then converted to the
// client type with round-to-nearest (table 4.7), as a tight RGBA array.
std::vector<unsigned char> finalConversion(const Image4& image, GLenum type) {
  const size_t n = image.px.size();
  const size_t size = type == GL_UNSIGNED_BYTE ? 1 : type == GL_UNSIGNED_SHORT ? 2 : 4;
  std::vector<unsigned char> out(n * size);
  auto clamp01 = [](float v) { return v > 0.0f ? (v < 1.0f ? v : 1.0f) : 0.0f; };
  parallelRows(image.height, size_t(image.width) * 4, [&](int y0, int y1) {
    const size_t b = size_t(y0) * image.width * 4, e = size_t(y1) * image.width * 4;
    const float* const in = image.px.data();
    if (type == GL_UNSIGNED_BYTE) {
      uint8_t* const o = out.data();  // raw pointer: see accumulation.cpp
      for (size_t i = b; i < e; ++i) o[i] = uint8_t(clamp01(in[i]) * 255.0f + 0.5f);
    } else if (type == GL_UNSIGNED_SHORT) {
      auto* o = reinterpret_cast<uint16_t*>(out.data());
      for (size_t i = b; i < e; ++i) o[i] = uint16_t(clamp01(in[i]) * 65535.0f + 0.5f);
    } else {
      auto* o = reinterpret_cast<float*>(out.data());
      for (size_t i = b; i < e; ++i) o[i] = clamp01(in[i]);
    }
  });
  return out;
}

void refreshColorMaps(State& s) {
  if (!s.transfer.mapColor) return;
  const GLenum maps[4] = {GL_PIXEL_MAP_R_TO_R, GL_PIXEL_MAP_G_TO_G, GL_PIXEL_MAP_B_TO_B,
                          GL_PIXEL_MAP_A_TO_A};
  const GLenum sizes[4] = {GL_PIXEL_MAP_R_TO_R_SIZE, GL_PIXEL_MAP_G_TO_G_SIZE,
                           GL_PIXEL_MAP_B_TO_B_SIZE, GL_PIXEL_MAP_A_TO_A_SIZE};
  for (int c = 0; c < 4; ++c) {
    GLint size = 0;
    s.driver.GetIntegerv(sizes[c], &size);
    s.transfer.colorMaps[c].assign(size_t(std::max(size, 1)), 0.0f);
    s.driver.GetPixelMapfv(maps[c], s.transfer.colorMaps[c].data());
  }
}

bool rasterPositionValid(State& s) {
  GLboolean valid = GL_FALSE;
  s.driver.GetBooleanv(GL_CURRENT_RASTER_POSITION_VALID, &valid);
  return valid != GL_FALSE;
}

// Draws a transformed image at the current raster position (zoom, masks and fragment
// operations are the driver's, as for any DrawPixels).
void drawImage(State& s, const Image4& image) {
  if (image.width == 0 || image.height == 0) return;
  const GLenum type = framebufferType(s);
  const std::vector<unsigned char> data = finalConversion(image, type);
  if (type == GL_UNSIGNED_BYTE) return drawBytes(s, image.width, image.height, data.data());
  ClientTransfers tight(s);
  s.driver.DrawPixels(image.width, image.height, GL_RGBA, type, data.data());
}

// Writes a transformed image into a texture of 1 or 2 dimensions (3.8.1 TexImage1D/2D, 3.8.2
// TexSubImage1D/2D) in the texture's precision: unsigned bytes for an 8-bit internal format,
// floats otherwise. A null image (a sink) still defines the texture, without data.
void uploadTexture(State& s, Dimensionality dims, bool sub, GLenum target, GLint level,
                   GLint internalformat, GLint xoffset, GLint yoffset, GLint border,
                   const Image4* image, int w, int h) {
  GLenum type = GL_FLOAT;
  if (sub) {
    GLint format = 0;
    s.driver.GetTexLevelParameteriv(target, level, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (eightBitTexture(GLenum(format))) type = GL_UNSIGNED_BYTE;
  } else if (eightBitTexture(GLenum(internalformat))) {
    type = GL_UNSIGNED_BYTE;
  }
  std::vector<unsigned char> data;
  if (image != nullptr) data = finalConversion(*image, type);
  ClientTransfers tight(s);
  const void* p = image != nullptr ? data.data() : nullptr;
  const bool oneD = dims == Dimensionality::k1D;
  if (sub) {
    if (image == nullptr || w == 0 || h == 0) return;
    if (oneD) return s.driver.TexSubImage1D(target, level, xoffset, w, GL_RGBA, type, p);
    return s.driver.TexSubImage2D(target, level, xoffset, yoffset, w, h, GL_RGBA, type, p);
  }
  if (oneD) return s.driver.TexImage1D(target, level, internalformat, w, border, GL_RGBA, type, p);
  s.driver.TexImage2D(target, level, internalformat, w, h, border, GL_RGBA, type, p);
}

// ---- the 8-bit path (fast_paths.cpp): bytes in, bytes out, no float images ----
bool eightBitFramebuffer(const State& s) { return framebufferType(s) == GL_UNSIGNED_BYTE; }

// Reads into the state's reusable input buffer; valid until the next readBytes.
std::vector<uint8_t>& readBytes(State& s, int x, int y, int w, int h) {
  std::vector<uint8_t>& bytes = s.scratchIn;
  bytes.resize(size_t(w) * h * 4);  // every byte is overwritten by the read
  ClientTransfers tight(s);
  s.driver.ReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
  return bytes;
}

// Client memory laid out exactly as a tight RGBA8 image (no row length or skips, rows
// already aligned).
bool tightRgba8(GLenum format, GLenum type, int w, const PixelStore& store) {
  return format == GL_RGBA && type == GL_UNSIGNED_BYTE && store.rowLength == 0 &&
         store.skipPixels == 0 && store.skipRows == 0 && (w * 4) % store.alignment == 0;
}

bool passThrough(State* s, Dimensionality dims = Dimensionality::k2D) {
  return s == nullptr || pipelineIsIdentity(s->transfer, dims);
}

}  // namespace

Image4 readFramebuffer(State& s, int x, int y, int w, int h) {
  Image4 image(std::max(w, 0), std::max(h, 0));
  if (w <= 0 || h <= 0) return image;
  const GLenum type = framebufferType(s);
  ClientTransfers tight(s);
  if (type == GL_FLOAT) {
    s.driver.ReadPixels(x, y, w, h, GL_RGBA, GL_FLOAT, image.px.data());
    return image;
  }
  if (type == GL_UNSIGNED_BYTE) {
    std::vector<unsigned char> bytes(image.px.size());
    s.driver.ReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_BYTE, bytes.data());
    float lut[256];
    for (int i = 0; i < 256; ++i) lut[i] = float(i) / 255.0f;  // table 2.6
    parallelRows(h, size_t(w) * 4, [&](int y0, int y1) {
      for (size_t i = size_t(y0) * w * 4; i < size_t(y1) * w * 4; ++i) image.px[i] = lut[bytes[i]];
    });
    return image;
  }
  std::vector<uint16_t> shorts(image.px.size());
  s.driver.ReadPixels(x, y, w, h, GL_RGBA, GL_UNSIGNED_SHORT, shorts.data());
  for (size_t i = 0; i < shorts.size(); ++i) image.px[i] = float(shorts[i]) / 65535.0f;
  return image;
}

void emDrawPixels(GLsizei w, GLsizei h, GLenum format, GLenum type, const void* data) {
  State* s = currentState();
  if (passThrough(s) || checkColorFormat(format, type) != GL_NO_ERROR || w < 0 || h < 0 ||
      !rasterPositionValid(*s))  // invalid raster position: nothing, not even histogram
    return s->driver.DrawPixels(w, h, format, type, data);
  refreshColorMaps(*s);
  if (data != nullptr && eightBitFramebuffer(*s) && bytePathApplies(s->transfer) &&
      tightRgba8(format, type, w, unpackStore(s->driver))) {
    const auto* p = static_cast<const uint8_t*>(data);
    std::vector<uint8_t> bytes(p, p + size_t(w) * h * 4);
    transformBytes(s->transfer, bytes, w, h);
    drawBytes(*s, w, h, bytes.data());
    return;
  }
  if (data != nullptr && w > 0 && h > 0 && eightBitFramebuffer(*s) &&
      matrixGroupsApply(s->transfer, format, type)) {  // RGB / float groups, matrix only
    std::vector<uint8_t>& bytes = s->scratchOut;
    bytes.resize(size_t(w) * h * 4);  // every byte is written
    matrixGroupsToBytes(s->transfer, data, w, h, format, type, unpackStore(s->driver),
                        bytes.data());
    drawBytes(*s, w, h, bytes.data());
    return;
  }
  Image4 image = unpackImage(data, w, h, format, type, unpackStore(s->driver));
  refreshColorMaps(*s);
  if (!runPipeline(s->transfer, image, Dimensionality::k2D)) return;  // sink
  drawImage(*s, image);
}

void emReadPixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum format, GLenum type, void* data) {
  State* s = currentState();
  if (passThrough(s) || checkColorFormat(format, type) != GL_NO_ERROR || w < 0 || h < 0)
    return s->driver.ReadPixels(x, y, w, h, format, type, data);
  refreshColorMaps(*s);
  if (eightBitFramebuffer(*s) && bytePathApplies(s->transfer) &&
      tightRgba8(format, type, w, packStore(s->driver))) {
    std::vector<uint8_t>& bytes = readBytes(*s, x, y, w, h);
    transformBytes(s->transfer, bytes, w, h);
    std::memcpy(data, bytes.data(), bytes.size());
    return;
  }
  Image4 image = readFramebuffer(*s, x, y, w, h);
  refreshColorMaps(*s);
  // Sink: "no pixel values are returned" (3.6.5 Histogram, Minmax).
  if (!runPipeline(s->transfer, image, Dimensionality::k2D)) return;
  // A REDUCE convolution returns a smaller image, placed with the row stride of the width
  // the call named (the rows the caller's buffer has).
  PixelStore store = packStore(s->driver);
  if (store.rowLength == 0) store.rowLength = w;
  packImage(image, data, format, type, store, true);
}

namespace {

// An identity-pipeline colour copy of an 8-bit window where the write-back's blit equals
// DrawPixels: 4.3.3 defines CopyPixels as a ReadPixels then a DrawPixels of its groups, so
// the read and the blit of write_back.cpp give its pixels (llvmpipe's own CopyPixels is a
// textured draw, tens of memcpys). True when done.
bool copyByBlit(State& s, GLint x, GLint y, GLsizei w, GLsizei h) {
  if (!eightBitFramebuffer(s) || w <= 0 || h <= 0) return false;
  int rx = 0, ry = 0;
  if (!blitEqualsDrawPixels(s, rx, ry)) return false;
  const std::vector<uint8_t>& bytes = readBytes(s, x, y, w, h);
  drawBytes(s, w, h, bytes.data());
  return true;
}

}  // namespace

void emCopyPixels(GLint x, GLint y, GLsizei w, GLsizei h, GLenum type) {
  State* s = currentState();
  if (s != nullptr && passThrough(s) && type == GL_COLOR && copyByBlit(*s, x, y, w, h)) return;
  if (passThrough(s) || type != GL_COLOR || w < 0 || h < 0 || !rasterPositionValid(*s))
    return s->driver.CopyPixels(x, y, w, h, type);
  refreshColorMaps(*s);
  if (eightBitFramebuffer(*s) && bytePathApplies(s->transfer)) {
    std::vector<uint8_t>& bytes = readBytes(*s, x, y, w, h);
    transformBytes(s->transfer, bytes, w, h);
    drawBytes(*s, w, h, bytes.data());
    return;
  }
  if (eightBitFramebuffer(*s) && convolveBytesApplies(s->transfer)) {  // strips, bytes to bytes
    const std::vector<uint8_t>& bytes = readBytes(*s, x, y, w, h);
    std::vector<uint8_t>& out = s->scratchOut;
    int ow = 0, oh = 0;
    if (!convolveBytes(s->transfer, bytes, w, h, out, ow, oh)) return;
    drawBytes(*s, ow, oh, out.data());
    return;
  }
  Image4 image = readFramebuffer(*s, x, y, w, h);
  refreshColorMaps(*s);
  if (!runPipeline(s->transfer, image, Dimensionality::k2D)) return;
  drawImage(*s, image);
}

void emCopyTexImage2D(GLenum target, GLint level, GLenum internalformat, GLint x, GLint y,
                      GLsizei w, GLsizei h, GLint border) {
  State* s = currentState();
  if (passThrough(s) || w < 0 || h < 0 || depthTexture(internalformat))
    return s->driver.CopyTexImage2D(target, level, internalformat, x, y, w, h, border);
  refreshColorMaps(*s);
  if (eightBitFramebuffer(*s) && bytePathApplies(s->transfer) && eightBitTexture(internalformat)) {
    std::vector<uint8_t>& bytes = readBytes(*s, x, y, w, h);
    transformBytes(s->transfer, bytes, w, h);
    ClientTransfers tight(*s);
    s->driver.TexImage2D(target, level, GLint(internalformat), w, h, border, GL_RGBA,
                         GL_UNSIGNED_BYTE, bytes.data());
    return;
  }
  Image4 image = readFramebuffer(*s, x, y, w, h);
  refreshColorMaps(*s);
  const bool kept = runPipeline(s->transfer, image, Dimensionality::k2D);
  // A sink leaves texture memory undefined but still (re)defines the texture's state.
  uploadTexture(*s, Dimensionality::k2D, false, target, level, GLint(internalformat), 0, 0, border,
                kept ? &image : nullptr, image.width, image.height);
}

void emCopyTexSubImage2D(GLenum target, GLint level, GLint xoffset, GLint yoffset, GLint x, GLint y,
                         GLsizei w, GLsizei h) {
  State* s = currentState();
  if (passThrough(s) || w < 0 || h < 0 || depthTexture(levelFormat(*s, target, level)))
    return s->driver.CopyTexSubImage2D(target, level, xoffset, yoffset, x, y, w, h);
  refreshColorMaps(*s);
  if (eightBitFramebuffer(*s) && bytePathApplies(s->transfer)) {
    GLint format = 0;
    s->driver.GetTexLevelParameteriv(target, level, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (eightBitTexture(GLenum(format))) {
      std::vector<uint8_t>& bytes = readBytes(*s, x, y, w, h);
      transformBytes(s->transfer, bytes, w, h);
      ClientTransfers tight(*s);
      s->driver.TexSubImage2D(target, level, xoffset, yoffset, w, h, GL_RGBA, GL_UNSIGNED_BYTE,
                              bytes.data());
      return;
    }
  }
  if (eightBitFramebuffer(*s) && convolveBytesApplies(s->transfer)) {
    GLint format = 0;
    s->driver.GetTexLevelParameteriv(target, level, GL_TEXTURE_INTERNAL_FORMAT, &format);
    if (eightBitTexture(GLenum(format))) {
      const std::vector<uint8_t>& bytes = readBytes(*s, x, y, w, h);
      std::vector<uint8_t>& out = s->scratchOut;
      int ow = 0, oh = 0;
      if (!convolveBytes(s->transfer, bytes, w, h, out, ow, oh) || ow == 0 || oh == 0) return;
      ClientTransfers tight(*s);
      s->driver.TexSubImage2D(target, level, xoffset, yoffset, ow, oh, GL_RGBA, GL_UNSIGNED_BYTE,
                              out.data());
      return;
    }
  }
  Image4 image = readFramebuffer(*s, x, y, w, h);
  refreshColorMaps(*s);
  if (!runPipeline(s->transfer, image, Dimensionality::k2D)) return;
  uploadTexture(*s, Dimensionality::k2D, true, target, level, 0, xoffset, yoffset, 0, &image,
                image.width, image.height);
}

void emTexImage2D(GLenum target, GLint level, GLint internalformat, GLsizei w, GLsizei h,
                  GLint border, GLenum format, GLenum type, const void* data) {
  State* s = currentState();
  if (passThrough(s) || checkColorFormat(format, type) != GL_NO_ERROR || w < 0 || h < 0)
    return s->driver.TexImage2D(target, level, internalformat, w, h, border, format, type, data);
  if (data == nullptr) {
    // 3.6.5 REDUCE: "the dimensions of the resulting texture image are those that would
    // result from the convolution of the specified image", even with a null pointer.
    int cw = w, ch = h;
    convolvedSize(s->transfer, Dimensionality::k2D, cw, ch);
    return s->driver.TexImage2D(target, level, internalformat, cw, ch, border, format, type,
                                nullptr);
  }
  refreshColorMaps(*s);
  if (w > 0 && h > 0 && eightBitTexture(GLenum(internalformat)) &&
      matrixGroupsApply(s->transfer, format, type)) {
    std::vector<uint8_t>& bytes = s->scratchOut;
    bytes.resize(size_t(w) * h * 4);
    matrixGroupsToBytes(s->transfer, data, w, h, format, type, unpackStore(s->driver),
                        bytes.data());
    ClientTransfers tight(*s);
    s->driver.TexImage2D(target, level, internalformat, w, h, border, GL_RGBA, GL_UNSIGNED_BYTE,
                         bytes.data());
    return;
  }
  Image4 image = unpackImage(data, w, h, format, type, unpackStore(s->driver));
  const bool kept = runPipeline(s->transfer, image, Dimensionality::k2D);
  uploadTexture(*s, Dimensionality::k2D, false, target, level, internalformat, 0, 0, border,
                kept ? &image : nullptr, image.width, image.height);
}

void emTexSubImage2D(GLenum target, GLint level, GLint xoffset, GLint yoffset, GLsizei w, GLsizei h,
                     GLenum format, GLenum type, const void* data) {
  State* s = currentState();
  if (passThrough(s) || checkColorFormat(format, type) != GL_NO_ERROR || w < 0 || h < 0 ||
      data == nullptr)
    return s->driver.TexSubImage2D(target, level, xoffset, yoffset, w, h, format, type, data);
  refreshColorMaps(*s);
  if (w > 0 && h > 0 && matrixGroupsApply(s->transfer, format, type) &&
      eightBitTexture(levelFormat(*s, target, level))) {
    std::vector<uint8_t>& bytes = s->scratchOut;
    bytes.resize(size_t(w) * h * 4);
    matrixGroupsToBytes(s->transfer, data, w, h, format, type, unpackStore(s->driver),
                        bytes.data());
    ClientTransfers tight(*s);
    s->driver.TexSubImage2D(target, level, xoffset, yoffset, w, h, GL_RGBA, GL_UNSIGNED_BYTE,
                            bytes.data());
    return;
  }
  Image4 image = unpackImage(data, w, h, format, type, unpackStore(s->driver));
  if (!runPipeline(s->transfer, image, Dimensionality::k2D)) return;
  uploadTexture(*s, Dimensionality::k2D, true, target, level, 0, xoffset, yoffset, 0, &image,
                image.width, image.height);
}

// ---- one-dimensional textures: the only images GL_CONVOLUTION_1D applies to (3.6.5
// "Convolution": "the one-dimensional convolution filter is applied only to the one-
// dimensional texture images passed to TexImage1D, TexSubImage1D, CopyTexImage1D, and
// CopyTexSubImage1D"; the 2D filters do not apply to them). The same sentence adds images
// "returned by GetTexImage", but 6.1.4 says "No pixel transfer operations are performed" on
// them; GetTexImage is left to the driver, as 6.1.4 says. ----

void emTexImage1D(GLenum target, GLint level, GLint internalformat, GLsizei w, GLint border,
                  GLenum format, GLenum type, const void* data) {
  State* s = currentState();
  if (passThrough(s, Dimensionality::k1D) || checkColorFormat(format, type) != GL_NO_ERROR || w < 0)
    return s->driver.TexImage1D(target, level, internalformat, w, border, format, type, data);
  if (data == nullptr) {  // REDUCE shrinks the width even without data (as for 2D)
    int cw = w, ch = 1;
    convolvedSize(s->transfer, Dimensionality::k1D, cw, ch);
    return s->driver.TexImage1D(target, level, internalformat, cw, border, format, type, nullptr);
  }
  Image4 image = unpackImage(data, w, 1, format, type, unpackStore(s->driver));
  refreshColorMaps(*s);
  const bool kept = runPipeline(s->transfer, image, Dimensionality::k1D);
  uploadTexture(*s, Dimensionality::k1D, false, target, level, internalformat, 0, 0, border,
                kept ? &image : nullptr, image.width, 1);
}

void emTexSubImage1D(GLenum target, GLint level, GLint xoffset, GLsizei w, GLenum format,
                     GLenum type, const void* data) {
  State* s = currentState();
  if (passThrough(s, Dimensionality::k1D) || checkColorFormat(format, type) != GL_NO_ERROR ||
      w < 0 || data == nullptr)
    return s->driver.TexSubImage1D(target, level, xoffset, w, format, type, data);
  Image4 image = unpackImage(data, w, 1, format, type, unpackStore(s->driver));
  refreshColorMaps(*s);
  if (!runPipeline(s->transfer, image, Dimensionality::k1D)) return;
  uploadTexture(*s, Dimensionality::k1D, true, target, level, 0, xoffset, 0, 0, &image, image.width,
                1);
}

void emCopyTexImage1D(GLenum target, GLint level, GLenum internalformat, GLint x, GLint y,
                      GLsizei w, GLint border) {
  State* s = currentState();
  if (passThrough(s, Dimensionality::k1D) || w < 0 || depthTexture(internalformat))
    return s->driver.CopyTexImage1D(target, level, internalformat, x, y, w, border);
  Image4 image = readFramebuffer(*s, x, y, w, 1);
  refreshColorMaps(*s);
  const bool kept = runPipeline(s->transfer, image, Dimensionality::k1D);
  // A sink leaves texture memory undefined but still (re)defines the texture's state.
  uploadTexture(*s, Dimensionality::k1D, false, target, level, GLint(internalformat), 0, 0, border,
                kept ? &image : nullptr, image.width, 1);
}

void emCopyTexSubImage1D(GLenum target, GLint level, GLint xoffset, GLint x, GLint y, GLsizei w) {
  State* s = currentState();
  if (passThrough(s, Dimensionality::k1D) || w < 0 || depthTexture(levelFormat(*s, target, level)))
    return s->driver.CopyTexSubImage1D(target, level, xoffset, x, y, w);
  Image4 image = readFramebuffer(*s, x, y, w, 1);
  refreshColorMaps(*s);
  if (!runPipeline(s->transfer, image, Dimensionality::k1D)) return;
  uploadTexture(*s, Dimensionality::k1D, true, target, level, 0, xoffset, 0, 0, &image, image.width,
                1);
}

}  // namespace sl::imaging::detail
