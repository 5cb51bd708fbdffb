// imaging/internal.h — the emulation's state tables and the helpers its files share.
//
// Not part of the public interface (imaging/imaging.h). The state mirrors the specification's
// state tables (glspec121 6.2, tables 6.14-6.16 "pixels"): three color tables and their
// proxies (3.6.3 "Color Table State and Proxy State"), the 1D/2D/separable convolution
// filters with border mode and colour and filter scale/bias ("Convolution Filter State"),
// post-convolution and post-color-matrix scale/bias (table 3.2), the color matrix stack
// (3.6.3 "Color Matrix Specification"), histogram and minmax (3.6.3), the RGBA pixel-transfer
// scale/bias and GL_MAP_COLOR (3.6.5), and the enables.
#pragma once

#include <algorithm>
#include <array>
#include <cstdint>
#include <functional>
#include <thread>
#include <vector>

#include "core/gl/context.h"
#include "imaging/imaging.h"

namespace sl::imaging::detail {

using Rgba = std::array<float, 4>;

// Implementation limits, chosen equal to the reference implementation (its README) so the
// parity suite can compare errors and proxies.
constexpr int kMaxColorTableWidth = 256;      // GL_MAX_COLOR_TABLE_WIDTH (not a GL query)
constexpr int kMaxHistogramWidth = 256;       // same limit for the histogram table
constexpr int kMaxConvolutionWidth = 9;       // GL_MAX_CONVOLUTION_WIDTH
constexpr int kMaxConvolutionHeight = 9;      // GL_MAX_CONVOLUTION_HEIGHT
constexpr int kMaxColorMatrixStackDepth = 4;  // GL_MAX_COLOR_MATRIX_STACK_DEPTH (spec minimum 2)
constexpr int kTableComponentBits = 8;        // reported GL_COLOR_TABLE_x_SIZE per component

// A float RGBA image, rows bottom-up (GL's order), 4 floats per pixel.
struct Image4 {
  int width = 0;
  int height = 0;
  std::vector<float> px;
  Image4() = default;
  Image4(int w, int h) : width(w), height(h), px(size_t(w) * size_t(h) * 4, 0.0f) {}
  float* row(int y) { return px.data() + size_t(y) * size_t(width) * 4; }
  const float* row(int y) const { return px.data() + size_t(y) * size_t(width) * 4; }
};

// Which of R, G, B, A (and L, I) a base internal format holds (table 3.15).
struct FormatComponents {
  bool r = false, g = false, b = false, a = false, l = false, i = false;
};
FormatComponents componentsOf(GLenum baseFormat);
// The base internal format of a color table / filter / texture internal format (tables 3.15,
// 3.16), or 0 when `internalformat` is not one of them.
GLenum baseInternalFormat(GLenum internalformat);

struct ColorTable {
  GLenum format = GL_RGBA;  // base internal format
  GLenum internalFormat = GL_RGBA;
  int width = 0;
  std::vector<Rgba> entries;  // table 3.15: R,G,B,A or L in [0], A in [3], I in [0]
  Rgba scale{1, 1, 1, 1};
  Rgba bias{0, 0, 0, 0};
};
struct ProxyTable {
  GLenum format = GL_RGBA;
  GLenum internalFormat = GL_RGBA;
  int width = 0;
};

struct ConvolutionFilter {
  GLenum format = GL_RGBA;  // base internal format
  GLenum internalFormat = GL_RGBA;
  int width = 0;
  int height = 0;                 // 1 for CONVOLUTION_1D
  std::vector<Rgba> image;        // width*height (2D/1D) or row then column (separable)
  std::vector<Rgba> row, column;  // separable only
  Rgba scale{1, 1, 1, 1};
  Rgba bias{0, 0, 0, 0};
  GLenum borderMode = GL_REDUCE;
  Rgba borderColor{0, 0, 0, 0};
};

struct Histogram {
  GLenum format = GL_RGBA;
  GLenum internalFormat = GL_RGBA;
  int width = 0;
  bool sink = false;
  std::vector<std::array<uint32_t, 4>> counts;
};
struct Minmax {
  GLenum format = GL_RGBA;
  GLenum internalFormat = GL_RGBA;
  bool sink = false;
  Rgba min{};
  Rgba max{};
};

struct Matrix4 {
  std::array<float, 16> m{1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};  // column-major
  bool isIdentity() const;
};

// Everything the pipeline reads (section 3.6.5), separated from the GL bookkeeping.
struct TransferState {
  Rgba scale{1, 1, 1, 1};  // GL_RED_SCALE ..
  Rgba bias{0, 0, 0, 0};   // GL_RED_BIAS ..
  bool mapColor = false;
  std::array<std::vector<float>, 4> colorMaps;  // PIXEL_MAP_R_TO_R .. A_TO_A (when mapColor)
  Rgba postConvolutionScale{1, 1, 1, 1};
  Rgba postConvolutionBias{0, 0, 0, 0};
  Rgba postColorMatrixScale{1, 1, 1, 1};
  Rgba postColorMatrixBias{0, 0, 0, 0};
  bool colorTableEnabled = false;
  bool postConvolutionTableEnabled = false;
  bool postColorMatrixTableEnabled = false;
  bool convolution1DEnabled = false;
  bool convolution2DEnabled = false;
  bool separable2DEnabled = false;
  bool histogramEnabled = false;
  bool minmaxEnabled = false;
  // Tables: [0] COLOR_TABLE, [1] POST_CONVOLUTION, [2] POST_COLOR_MATRIX.
  std::array<ColorTable, 3> tables;
  std::array<ProxyTable, 3> proxies;
  ConvolutionFilter conv1D, conv2D, separable2D;
  std::vector<Matrix4> colorMatrixStack{Matrix4{}};
  Histogram histogram;
  ProxyTable proxyHistogram;
  Minmax minmax;
};

// The emulated state glPushAttrib saves (glspec121 6.1.12, tables 6.17-6.21: the imaging
// enables belong to GL_ENABLE_BIT and GL_PIXEL_MODE_BIT, the scale/bias, border and
// GL_MAP_COLOR parameters to GL_PIXEL_MODE_BIT; tables, filters and the color matrix stack
// are not attributes. Table 6.16: the clear value of an emulated accumulation buffer belongs
// to GL_ACCUM_BUFFER_BIT).
struct AttribSnapshot {
  GLbitfield mask = 0;
  TransferState transfer;        // the saved fields only are restored
  bool colorMatrixMode = false;  // GL_TRANSFORM_BIT saves MATRIX_MODE (table 6.7): GL_COLOR too
  Rgba clearAccum{0, 0, 0, 0};   // GL_ACCUM_BUFFER_BIT, where the accumulation is emulated
};

// How 8-bit results are written into the framebuffer (write_back.cpp).
enum class WriteBackPath {
  kFastest,     // a texture upload and a blit where the state allows, else glDrawPixels
  kDrawPixels,  // always the driver's glDrawPixels (tests and imaging_bench compare the two)
};
struct WriteBack {
  WriteBackPath forced = WriteBackPath::kFastest;
  bool lastWasBlit = false;  // the path the last write took (tests read it)
  // The upload texture and its framebuffer, at the window's size; owned by the GL context.
  GLuint texture = 0, framebuffer = 0;
  int width = 0, height = 0;
  std::vector<uint8_t> flipped;  // the image, top row first, reused across calls
};

// Per-context emulation state (stored with GlContext::setLayerState("imaging", ...)).
struct State {
  GlDispatch driver;  // the entry points as the driver resolved them, before install()
  GlContext* context = nullptr;
  bool pixelBuffers = false;  // the context has pixel buffer objects (ClientTransfers)
  TransferState transfer;
  bool colorMatrixMode = false;             // glMatrixMode(GL_COLOR) is in effect
  std::vector<AttribSnapshot> attribStack;  // parallel to the driver's attribute stack
  // Sticky error flags raised by the emulation, in the order raised (section 2.5).
  std::vector<GLenum> errors;
  // Accumulation buffer where the visual has none (section 4.2.4); 16-bit signed fixed point.
  bool emulateAccum = false;
  Rgba clearAccum{0, 0, 0, 0};
  int accumWidth = 0, accumHeight = 0;
  std::vector<int16_t> accum;  // k / 32767 per component (accumulation.cpp)
  // Byte buffers the 8-bit paths reuse from call to call (pixel_paths.cpp), so that a
  // repeated glCopyPixels does not allocate and page-fault a fresh image each time.
  std::vector<uint8_t> scratchIn, scratchOut;
  // GL_RETURN's 65536-entry byte table for 8-bit colour, kept for the value it was built for
  // (a frame returns with the same value again and again).
  bool returnTableValid = false;
  float returnTableValue = 0.0f;
  std::vector<uint8_t> returnTable;
  // The vector form of that table (returnAccumBytes with this scale), where it gives every
  // entry of the table exactly (checked on all 65535 when the table is built).
  bool returnVectorExact = false;
  float returnScale = 0.0f;
  WriteBack writeBack;
};

// The state of the current context (nullptr when the emulation is not installed on it).
State* currentState();
void recordError(State& s, GLenum error);

// ---- the pipeline (pixel_transfer.cpp) ----
enum class Dimensionality { k1D, k2D };
// True when every stage of section 3.6.5 that applies to RGBA groups is identity, so a pixel
// path can be forwarded to the driver untouched.
bool pipelineIsIdentity(const TransferState& t, Dimensionality dims);
// Runs the RGBA pixel-transfer stages of section 3.6.5 in order on `image` (which may change
// size under GL_REDUCE). Returns false when histogram or minmax sink consumed the groups.
bool runPipeline(TransferState& t, Image4& image, Dimensionality dims);
// The output size of the convolution stage for a source of w x h (REDUCE shrinks it).
void convolvedSize(const TransferState& t, Dimensionality dims, int& w, int& h);

// The pipeline on 8-bit RGBA groups in place, for 8-bit destinations, when only
// per-component stages and the color matrix are active (fast_paths.cpp). Returns false
// (bytes untouched) when another stage is active; the general path is then used.
// kScalar forces the scalar loops (tests compare them with the vector maps).
enum class BytePath { kFastest, kScalar };
bool transformBytes(TransferState& t, std::vector<uint8_t>& bytes, int w, int h,
                    BytePath path = BytePath::kFastest);
bool bytePathApplies(const TransferState& t);

// ---- the colour matrix alone, client groups to bytes (color_matrix_groups.cpp) ----
struct PixelStore;  // client memory layout (below)
// Stage 6 (the color matrix, not identity, with its post-color-matrix scale and bias) is the
// only stage of 3.6.5 that changes RGBA groups: no histogram, minmax or table after it.
bool matrixOnlyPipeline(const TransferState& t);
// matrixOnlyPipeline, for client groups that matrixGroupsToBytes reads: GL_RGBA or GL_RGB of
// GL_UNSIGNED_BYTE or GL_FLOAT.
bool matrixGroupsApply(const TransferState& t, GLenum format, GLenum type);
// The instruction set of matrixGroupsToBytes: kBest picks the widest this processor has (tests
// run each available one and compare). kAvx512Vbmi: sixteen groups per block, one vector per
// component (planar; byte permutes of AVX-512 VBMI unpack the bytes); the others: four groups
// per vector, one group per four lanes.
enum class MatrixIsa { kBest, kAvx512Vbmi, kAvx512, kAvx2, kSse2 };
bool matrixIsaAvailable(MatrixIsa isa);
// w x h client groups (unpacked per `store`, 3.6.4) through stage 6 and the final conversion of
// 4.3.2 to tight RGBA8 in `out` (w * h * 4 bytes, rows bottom-up): bytes identical to
// unpackImage, runPipeline and the final conversion, in vectors.
void matrixGroupsToBytes(const TransferState& t, const void* data, int w, int h, GLenum format,
                         GLenum type, const PixelStore& store, uint8_t* out,
                         MatrixIsa isa = MatrixIsa::kBest);

// ---- vector maps of the 8-bit path (byte_maps.cpp) ----
constexpr int kMaxByteSteps = 4;  // breakpoints per component the vector maps test
constexpr int kMaxClasses = 16;   // classes of RGBA groups: one 16-byte shuffle table
// out = base + sum over k of (x >= at[k] ? delta[k] : 0), per component, in byte arithmetic.
struct StepMap {
  int steps = 0;
  uint8_t base[4] = {};
  uint8_t at[kMaxByteSteps][4] = {};
  uint8_t delta[kMaxByteSteps][4] = {};
};
// class = sum over k of (x >= at[k] ? weight[k] : 0) over the group's four bytes; the output
// group is table[r][class] for the components that vary, constant[r] for the others.
struct ClassMap {
  int steps = 0;
  uint8_t at[kMaxByteSteps][4] = {};
  uint8_t weight[kMaxByteSteps][4] = {};
  uint8_t table[4][kMaxClasses] = {};
  bool varies[4] = {false, false, false, false};
  uint8_t constant[4] = {};
};
// From a per-component byte table (lut[v * 4 + c]); false when a component has too many steps.
bool planStepMap(const uint8_t lut[256 * 4], StepMap& map);
// From the prefix values of the components that matter (sameAsPrevious(c, v): value v of
// component c equals value v - 1) and the scalar transform, run on one group per class.
bool planClassMap(const std::function<bool(int, int)>& sameAsPrevious, const bool matters[4],
                  const std::function<void(uint8_t*, size_t)>& scalar, ClassMap& map);
bool vectorMapsAvailable();    // AVX2 on this processor
bool vectorTablesAvailable();  // AVX-512 VBMI (byte permutes) on this processor
// Any per-component byte table (lut[v * 4 + c]) on the leading 64-byte blocks of p[0 .. n)
// in place; returns the bytes done.
size_t applyByteTable(const uint8_t lut[256 * 4], uint8_t* p, size_t n);
// GL_ACCUM / GL_LOAD on 8-bit colour (accumulation.cpp): accum[i] = clamp((keep ? accum[i] :
// 0) + scaled[color[i]], -32767, 32767) for the leading 64-component blocks of n, by byte
// permutes (AVX-512 VBMI) where the processor has them; returns the components done.
size_t accumulateBytes(const int16_t scaled[256], bool keep, const uint8_t* color, int16_t* accum,
                       size_t n);
// GL_RETURN on 8-bit colour (accumulation.cpp): out[i] = trunc(clamp(float(accum[i]) * scale,
// 0, 255) + 0.5) in float for the leading 16-component blocks of n (AVX2); returns the
// components done (0 without AVX2). The caller uses it only where it equals the exact table.
size_t returnAccumBytes(float scale, const int16_t* accum, uint8_t* out, size_t n);
// Apply a map to the leading whole vectors of p[0 .. n) bytes in place; returns the bytes done
// (the caller's scalar loop does the rest).
size_t applyStepMap(const StepMap& map, uint8_t* p, size_t n);
size_t applyClassMap(const ClassMap& map, uint8_t* p, size_t n);

// Convolution on an 8-bit source straight to 8-bit output with every stage of 3.6.5
// (convolution_bytes.cpp): a byte gather for kernels with one tap per component, else SIMD
// sums over rows that stay in cache; bytes identical to runPipeline's. `out` receives
// ow x oh groups; returns false when a sink consumed the groups (nothing to write).
// `simd` selects the instruction set of the sums: kBest (AVX2 where the CPU has it) or
// kBaseline (SSE2, what every x86-64 has; the tests run both).
enum class SimdLevel { kBest, kBaseline };
bool convolveBytes(TransferState& t, const std::vector<uint8_t>& src, int ws, int hs,
                   std::vector<uint8_t>& out, int& ow, int& oh, SimdLevel simd = SimdLevel::kBest);
// The same in strips of float rows with the general stage code (fast_paths.cpp): the
// fallback where the fast paths' conditions do not hold (non-finite stage values).
bool convolveBytesStrips(TransferState& t, const std::vector<uint8_t>& src, int ws, int hs,
                         std::vector<uint8_t>& out, int& ow, int& oh);
// A 2D or separable convolution with a non-empty filter is enabled.
bool convolveBytesApplies(const TransferState& t);

// The 3x3 binomial blur: the outer product of kBinomialRow with itself, over 2^kBinomialShift
// (the imaging blur stage; convolution_bytes.cpp sums it with adds only).
constexpr uint16_t kBinomialRow[3] = {1, 2, 1};
constexpr int kBinomialShift = 4;  // the weights are multiples of 1/16
// Its dense weights as glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA,
// GL_FLOAT, ...) takes them: row-major, four equal floats a tap (convolution.cpp).
std::vector<float> binomialBlur3x3Rgba();

// A tap of a convolution kernel: offset (n, m) into the (bordered) source, four weights.
struct Tap {
  int n, m;
  float w[4];
};
// The non-zero taps of a filter (pass-through components as a unit tap at the centre).
std::vector<Tap> kernelTaps(const ConvolutionFilter& f, bool separable, int& wf, int& hf);
// o[0 .. ow*4) += sum over taps of row(m)[n*4 + ...] * w, in tap order (convolution.cpp).
void accumulateTaps(const std::vector<Tap>& taps, const std::function<const float*(int)>& row,
                    int ow, float* o);

// ---- stages (one file each) ----
void applyColorTable(const ColorTable& table, Image4& image);                   // color_table.cpp
void convolve(const ConvolutionFilter& filter, bool separable, Image4& image);  // convolution.cpp
void applyColorMatrix(const Matrix4& m, const Rgba& scale, const Rgba& bias,
                      Image4& image);                         // color_matrix.cpp
void accumulateHistogram(Histogram& h, const Image4& image);  // histogram.cpp
void accumulateMinmax(Minmax& m, const Image4& image);        // histogram.cpp
void resetMinmax(Minmax& m);

// Runs body(y0, y1) over [0, rows) on both cores when the work is large enough to pay.
template <class Body>
void parallelRows(int rows, size_t workPerRow, const Body& body);

// ---- client memory (pixel_memory.cpp): unpack/pack following 3.6.4 and 4.3.2 ----
struct PixelStore {
  int alignment = 4, rowLength = 0, skipPixels = 0, skipRows = 0;
  bool swapBytes = false, lsbFirst = false;
};
PixelStore unpackStore(const GlDispatch& gl);
PixelStore packStore(const GlDispatch& gl);
// GL_NO_ERROR when format/type are a supported color format for the emulation, else the error
// GL would raise (INVALID_ENUM), or GL_INVALID_OPERATION for a packed type/format mismatch.
GLenum checkColorFormat(GLenum format, GLenum type);
// The error of a command taking a target and a format/type pair: INVALID_ENUM when the target
// is not valid, else checkColorFormat's answer (GL_NO_ERROR when both are accepted).
inline GLenum targetFormatError(bool targetValid, GLenum format, GLenum type) {
  return targetValid ? checkColorFormat(format, type) : GLenum(GL_INVALID_ENUM);
}
bool isColorFormat(GLenum format);
// Components per group of a color format the emulation takes (table 3.5), 0 for any other.
int componentCount(GLenum format);
// Unpacks w x h groups to RGBA floats ("Unpacking", "Conversion to floating-point",
// "Conversion to RGB", "Final Expansion to RGBA" of 3.6.4).
Image4 unpackImage(const void* data, int w, int h, GLenum format, GLenum type,
                   const PixelStore& store);
// Packs RGBA floats into client memory (4.3.2 "Conversion to L", "Final Conversion" with its
// clamp to [0,1] when clamp is true, "Placement in Client Memory").
void packImage(const Image4& image, void* data, GLenum format, GLenum type, const PixelStore& store,
               bool clamp);
// Returns internal components as RGBA per table 6.1.
Rgba tableReturnValue(GLenum baseFormat, const Rgba& stored);

constexpr size_t kParallelThreshold = 1u << 16;  // floats of work below which one core is faster

template <class Body>
void parallelRows(int rows, size_t workPerRow, const Body& body) {
  const unsigned cores = std::thread::hardware_concurrency();
  if (rows < 2 || cores < 2 || size_t(rows) * workPerRow < kParallelThreshold) {
    body(0, rows);
    return;
  }
  const int parts = int(cores < 4 ? cores : 4);
  std::vector<std::thread> threads;
  const int step = (rows + parts - 1) / parts;
  for (int p = 1; p < parts; ++p) {
    const int y0 = p * step, y1 = std::min(rows, y0 + step);
    if (y0 < y1) threads.emplace_back([&body, y0, y1] { body(y0, y1); });
  }
  body(0, std::min(rows, step));
  for (auto& t : threads) t.join();
}

}  // namespace sl::imaging::detail

namespace sl::imaging::detail {

// ---- the replaced entry points (same signatures as the GL prototypes) ----
// color_table.cpp
void emColorTable(GLenum, GLenum, GLsizei, GLenum, GLenum, const void*);
void emColorSubTable(GLenum, GLsizei, GLsizei, GLenum, GLenum, const void*);
void emCopyColorTable(GLenum, GLenum, GLint, GLint, GLsizei);
void emCopyColorSubTable(GLenum, GLsizei, GLint, GLint, GLsizei);
void emColorTableParameterfv(GLenum, GLenum, const GLfloat*);
void emColorTableParameteriv(GLenum, GLenum, const GLint*);
void emGetColorTable(GLenum, GLenum, GLenum, void*);
void emGetColorTableParameterfv(GLenum, GLenum, GLfloat*);
void emGetColorTableParameteriv(GLenum, GLenum, GLint*);
// convolution.cpp
void emConvolutionFilter1D(GLenum, GLenum, GLsizei, GLenum, GLenum, const void*);
void emConvolutionFilter2D(GLenum, GLenum, GLsizei, GLsizei, GLenum, GLenum, const void*);
void emSeparableFilter2D(GLenum, GLenum, GLsizei, GLsizei, GLenum, GLenum, const void*,
                         const void*);
void emCopyConvolutionFilter1D(GLenum, GLenum, GLint, GLint, GLsizei);
void emCopyConvolutionFilter2D(GLenum, GLenum, GLint, GLint, GLsizei, GLsizei);
void emConvolutionParameterf(GLenum, GLenum, GLfloat);
void emConvolutionParameterfv(GLenum, GLenum, const GLfloat*);
void emConvolutionParameteri(GLenum, GLenum, GLint);
void emConvolutionParameteriv(GLenum, GLenum, const GLint*);
void emGetConvolutionFilter(GLenum, GLenum, GLenum, void*);
void emGetSeparableFilter(GLenum, GLenum, GLenum, void*, void*, void*);
void emGetConvolutionParameterfv(GLenum, GLenum, GLfloat*);
void emGetConvolutionParameteriv(GLenum, GLenum, GLint*);
// histogram.cpp
void emHistogram(GLenum, GLsizei, GLenum, GLboolean);
void emMinmax(GLenum, GLenum, GLboolean);
void emResetHistogram(GLenum);
void emResetMinmax(GLenum);
void emGetHistogram(GLenum, GLboolean, GLenum, GLenum, void*);
void emGetHistogramParameterfv(GLenum, GLenum, GLfloat*);
void emGetHistogramParameteriv(GLenum, GLenum, GLint*);
void emGetMinmax(GLenum, GLboolean, GLenum, GLenum, void*);
void emGetMinmaxParameterfv(GLenum, GLenum, GLfloat*);
void emGetMinmaxParameteriv(GLenum, GLenum, GLint*);
// color_matrix.cpp (matrix entries act on the color matrix only in GL_COLOR mode)
void emMatrixMode(GLenum);
void emLoadIdentity();
void emLoadMatrixf(const GLfloat*);
void emLoadMatrixd(const GLdouble*);
void emMultMatrixf(const GLfloat*);
void emMultMatrixd(const GLdouble*);
void emPushMatrix();
void emPopMatrix();
void emScalef(GLfloat, GLfloat, GLfloat);
void emTranslatef(GLfloat, GLfloat, GLfloat);
void emScaled(GLdouble, GLdouble, GLdouble);
void emTranslated(GLdouble, GLdouble, GLdouble);
void emRotatef(GLfloat, GLfloat, GLfloat, GLfloat);
void emRotated(GLdouble, GLdouble, GLdouble, GLdouble);
void emOrtho(GLdouble, GLdouble, GLdouble, GLdouble, GLdouble, GLdouble);
void emFrustum(GLdouble, GLdouble, GLdouble, GLdouble, GLdouble, GLdouble);
void emLoadTransposeMatrixf(const GLfloat*);
void emLoadTransposeMatrixd(const GLdouble*);
void emMultTransposeMatrixf(const GLfloat*);
void emMultTransposeMatrixd(const GLdouble*);
// pixel_paths.cpp
void emDrawPixels(GLsizei, GLsizei, GLenum, GLenum, const void*);
void emReadPixels(GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, void*);
void emCopyPixels(GLint, GLint, GLsizei, GLsizei, GLenum);
void emCopyTexImage2D(GLenum, GLint, GLenum, GLint, GLint, GLsizei, GLsizei, GLint);
void emCopyTexSubImage2D(GLenum, GLint, GLint, GLint, GLint, GLint, GLsizei, GLsizei);
void emTexImage2D(GLenum, GLint, GLint, GLsizei, GLsizei, GLint, GLenum, GLenum, const void*);
void emTexSubImage2D(GLenum, GLint, GLint, GLint, GLsizei, GLsizei, GLenum, GLenum, const void*);
void emTexImage1D(GLenum, GLint, GLint, GLsizei, GLint, GLenum, GLenum, const void*);
void emTexSubImage1D(GLenum, GLint, GLint, GLsizei, GLenum, GLenum, const void*);
void emCopyTexImage1D(GLenum, GLint, GLenum, GLint, GLint, GLsizei, GLint);
void emCopyTexSubImage1D(GLenum, GLint, GLint, GLint, GLint, GLsizei);
// Reads a framebuffer rectangle of the read buffer as RGBA floats, exactly ("stopping after
// the final expansion to RGBA": no pixel transfer), through the driver.
Image4 readFramebuffer(State& s, int x, int y, int w, int h);
// The emulation's own transfers between the driver and its client memory (its reads of the
// framebuffer, its glDrawPixels, texture uploads and the write-back): tight pixel storage
// (3.6.4 "Unpacking", 4.3.2 "Placement in Client Memory": no row length, skips or swapping,
// alignment 1) and no buffer bound to GL_PIXEL_PACK_BUFFER / GL_PIXEL_UNPACK_BUFFER — with one
// bound, the pointer argument is an offset into it (ARB_pixel_buffer_object, "Pixel Buffer
// Object Operations"), not the emulation's memory. The caller's storage and bindings are
// restored when it goes.
class ClientTransfers {
 public:
  explicit ClientTransfers(const State& s);
  ~ClientTransfers();
  ClientTransfers(const ClientTransfers&) = delete;
  ClientTransfers& operator=(const ClientTransfers&) = delete;

 private:
  const GlDispatch& gl_;
  GLint pack_ = 0, unpack_ = 0;
};
// The client type that carries the colour buffer's precision without loss: unsigned bytes for
// 8-bit, unsigned shorts for 16-bit, floats otherwise (pixel_paths.cpp).
GLenum framebufferType(const State& s);
// write_back.cpp: the end of every 8-bit emulated DrawPixels / CopyPixels / Accum(RETURN).
// glDrawPixels(w, h, GL_RGBA, GL_UNSIGNED_BYTE, bytes) at the current raster position (tight
// rows, bottom row first), by a texture upload and a blit where blitEqualsDrawPixels holds,
// else by the driver's glDrawPixels.
void drawBytes(State& s, int w, int h, const uint8_t* bytes);
// True when the state makes a copy of the bytes into the window at (x, y) = the raster
// position the same as glDrawPixels (the conditions, with their sections, are in the file).
bool blitEqualsDrawPixels(State& s, int& x, int& y);
// Accum(RETURN)'s write of w x h groups at window (x, y), inside the window: true when only
// the colour mask needs a condition (4.2.4) and it holds, so a blit may write them. The caller
// then writes the groups straight into returnRows(s, w, h), image row r at row h-1-r (the
// flipped upload, saving a copy), and calls blitReturnRows(s, x, y, w, h).
bool blitEqualsReturn(State& s);
uint8_t* returnRows(State& s, int w, int h);
void blitReturnRows(State& s, int x, int y, int w, int h);
// accumulation.cpp
void emAccum(GLenum, GLfloat);
void emClearAccum(GLfloat, GLfloat, GLfloat, GLfloat);
void emClear(GLbitfield);
// state.cpp (enables, queries, pixel transfer parameters, errors)
void emEnable(GLenum);
void emDisable(GLenum);
GLboolean emIsEnabled(GLenum);
void emGetIntegerv(GLenum, GLint*);
void emGetFloatv(GLenum, GLfloat*);
void emGetBooleanv(GLenum, GLboolean*);
void emGetDoublev(GLenum, GLdouble*);
void emPixelTransferf(GLenum, GLfloat);
void emPixelTransferi(GLenum, GLint);
void emPushAttrib(GLbitfield);
void emPopAttrib();
GLenum emGetError();

}  // namespace sl::imaging::detail
