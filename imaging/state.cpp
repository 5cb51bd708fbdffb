// imaging/state.cpp — enables, state queries, pixel-transfer parameters and errors of the
// emulation (glspec121 2.5 "GL Errors", 3.6.3 table 3.2 "PixelTransfer parameters", 6.1.2
// "Data Conversions", 6.1.6 "Color Matrix Query", state tables 6.14-6.16).
#include <cmath>

#include "imaging/internal.h"

namespace sl::imaging::detail {

// 2.5: one sticky flag per error code; a flag already set is not set again. The emulation and
// the driver share the flags: the driver's pending errors are taken in first, so that
// glGetError returns the codes in the order the calls raised them, each code once.
namespace {
void addFlag(State& s, GLenum error) {
  for (GLenum e : s.errors)
    if (e == error) return;
  s.errors.push_back(error);
}
void takeDriverErrors(State& s) {
  constexpr int kMaxDriverFlags = 16;  // GL has at most a handful of distinct error codes
  for (int i = 0; i < kMaxDriverFlags; ++i) {
    const GLenum e = s.driver.GetError();
    if (e == GL_NO_ERROR) return;
    addFlag(s, e);
  }
}
}  // namespace

void recordError(State& s, GLenum error) {
  takeDriverErrors(s);
  addFlag(s, error);
}

GLenum emGetError() {
  State& s = *currentState();
  takeDriverErrors(s);
  if (s.errors.empty()) return GL_NO_ERROR;
  const GLenum e = s.errors.front();
  s.errors.erase(s.errors.begin());
  return e;
}

namespace {

bool* enableFlag(State& s, GLenum cap) {
  TransferState& t = s.transfer;
  switch (cap) {
    case GL_COLOR_TABLE: return &t.colorTableEnabled;
    case GL_POST_CONVOLUTION_COLOR_TABLE: return &t.postConvolutionTableEnabled;
    case GL_POST_COLOR_MATRIX_COLOR_TABLE: return &t.postColorMatrixTableEnabled;
    case GL_CONVOLUTION_1D: return &t.convolution1DEnabled;
    case GL_CONVOLUTION_2D: return &t.convolution2DEnabled;
    case GL_SEPARABLE_2D: return &t.separable2DEnabled;
    case GL_HISTOGRAM: return &t.histogramEnabled;
    case GL_MINMAX: return &t.minmaxEnabled;
    default: return nullptr;
  }
}

// The float parameters of table 3.2 that the emulation owns.
float* transferParameter(State& s, GLenum pname) {
  TransferState& t = s.transfer;
  switch (pname) {
    case GL_RED_SCALE: return &t.scale[0];
    case GL_GREEN_SCALE: return &t.scale[1];
    case GL_BLUE_SCALE: return &t.scale[2];
    case GL_ALPHA_SCALE: return &t.scale[3];
    case GL_RED_BIAS: return &t.bias[0];
    case GL_GREEN_BIAS: return &t.bias[1];
    case GL_BLUE_BIAS: return &t.bias[2];
    case GL_ALPHA_BIAS: return &t.bias[3];
    case GL_POST_CONVOLUTION_RED_SCALE: return &t.postConvolutionScale[0];
    case GL_POST_CONVOLUTION_GREEN_SCALE: return &t.postConvolutionScale[1];
    case GL_POST_CONVOLUTION_BLUE_SCALE: return &t.postConvolutionScale[2];
    case GL_POST_CONVOLUTION_ALPHA_SCALE: return &t.postConvolutionScale[3];
    case GL_POST_CONVOLUTION_RED_BIAS: return &t.postConvolutionBias[0];
    case GL_POST_CONVOLUTION_GREEN_BIAS: return &t.postConvolutionBias[1];
    case GL_POST_CONVOLUTION_BLUE_BIAS: return &t.postConvolutionBias[2];
    case GL_POST_CONVOLUTION_ALPHA_BIAS: return &t.postConvolutionBias[3];
    case GL_POST_COLOR_MATRIX_RED_SCALE: return &t.postColorMatrixScale[0];
    case GL_POST_COLOR_MATRIX_GREEN_SCALE: return &t.postColorMatrixScale[1];
    case GL_POST_COLOR_MATRIX_BLUE_SCALE: return &t.postColorMatrixScale[2];
    case GL_POST_COLOR_MATRIX_ALPHA_SCALE: return &t.postColorMatrixScale[3];
    case GL_POST_COLOR_MATRIX_RED_BIAS: return &t.postColorMatrixBias[0];
    case GL_POST_COLOR_MATRIX_GREEN_BIAS: return &t.postColorMatrixBias[1];
    case GL_POST_COLOR_MATRIX_BLUE_BIAS: return &t.postColorMatrixBias[2];
    case GL_POST_COLOR_MATRIX_ALPHA_BIAS: return &t.postColorMatrixBias[3];
    default: return nullptr;
  }
}

// Values of an emulated query as doubles; false when the query is not the emulation's.
bool emulatedQuery(State& s, GLenum pname, double* v, int& n) {
  n = 1;
  if (bool* flag = enableFlag(s, pname)) {
    v[0] = *flag ? 1.0 : 0.0;
    return true;
  }
  if (float* p = transferParameter(s, pname)) {
    v[0] = *p;
    return true;
  }
  switch (pname) {
    case GL_MAP_COLOR: v[0] = s.transfer.mapColor ? 1.0 : 0.0; return true;
    case GL_COLOR_MATRIX:
      n = 16;
      for (int i = 0; i < 16; ++i) v[i] = s.transfer.colorMatrixStack.back().m[i];
      return true;
    case GL_TRANSPOSE_COLOR_MATRIX:  // glspec14 6.1.2: the same matrix, row by row
      n = 16;
      for (int r = 0; r < 4; ++r)
        for (int c = 0; c < 4; ++c) v[r * 4 + c] = s.transfer.colorMatrixStack.back().m[c * 4 + r];
      return true;
    case GL_COLOR_MATRIX_STACK_DEPTH:
      v[0] = double(s.transfer.colorMatrixStack.size());
      return true;
    case GL_MAX_COLOR_MATRIX_STACK_DEPTH: v[0] = kMaxColorMatrixStackDepth; return true;
    case GL_MATRIX_MODE:
      if (!s.colorMatrixMode) return false;
      v[0] = GL_COLOR;
      return true;
    default: break;
  }
  if (s.emulateAccum) {
    switch (pname) {
      case GL_ACCUM_RED_BITS:
      case GL_ACCUM_GREEN_BITS:
      case GL_ACCUM_BLUE_BITS:
      case GL_ACCUM_ALPHA_BITS:
        v[0] = 16;  // the emulated buffer keeps 16-bit signed fixed point (accumulation.cpp)
        return true;
      case GL_ACCUM_CLEAR_VALUE:
        n = 4;
        for (int c = 0; c < 4; ++c) v[c] = s.clearAccum[c];
        return true;
      default: break;
    }
  }
  return false;
}

bool isColorQuery(GLenum pname) {
  return pname == GL_ACCUM_CLEAR_VALUE;  // 6.1.2: colours map [-1,1] to the integer range
}

}  // namespace

void emEnable(GLenum cap) {
  State& s = *currentState();
  if (bool* flag = enableFlag(s, cap)) {
    *flag = true;
    return;
  }
  s.driver.Enable(cap);
}

void emDisable(GLenum cap) {
  State& s = *currentState();
  if (bool* flag = enableFlag(s, cap)) {
    *flag = false;
    return;
  }
  s.driver.Disable(cap);
}

GLboolean emIsEnabled(GLenum cap) {
  State& s = *currentState();
  if (bool* flag = enableFlag(s, cap)) return *flag ? GL_TRUE : GL_FALSE;
  return s.driver.IsEnabled(cap);
}

void emGetFloatv(GLenum pname, GLfloat* out) {
  State& s = *currentState();
  double v[16];
  int n = 0;
  if (!emulatedQuery(s, pname, v, n)) return s.driver.GetFloatv(pname, out);
  for (int i = 0; i < n; ++i) out[i] = float(v[i]);
}

void emGetDoublev(GLenum pname, GLdouble* out) {
  State& s = *currentState();
  double v[16];
  int n = 0;
  if (!emulatedQuery(s, pname, v, n)) return s.driver.GetDoublev(pname, out);
  for (int i = 0; i < n; ++i) out[i] = v[i];
}

void emGetIntegerv(GLenum pname, GLint* out) {
  State& s = *currentState();
  double v[16];
  int n = 0;
  if (!emulatedQuery(s, pname, v, n)) return s.driver.GetIntegerv(pname, out);
  for (int i = 0; i < n; ++i) {
    if (isColorQuery(pname)) {
      out[i] = GLint(std::lround((v[i] * 4294967295.0 - 1.0) / 2.0));
    } else {
      out[i] = GLint(std::lround(v[i]));  // 6.1.2: floating-point to integer rounds
    }
  }
}

void emGetBooleanv(GLenum pname, GLboolean* out) {
  State& s = *currentState();
  double v[16];
  int n = 0;
  if (!emulatedQuery(s, pname, v, n)) return s.driver.GetBooleanv(pname, out);
  for (int i = 0; i < n; ++i) out[i] = v[i] != 0.0 ? GL_TRUE : GL_FALSE;  // 6.1.2
}

void emPixelTransferf(GLenum pname, GLfloat value) {
  State& s = *currentState();
  if (float* p = transferParameter(s, pname)) {
    *p = value;
    return;
  }
  if (pname == GL_MAP_COLOR) {
    s.transfer.mapColor = value != 0.0f;
    return;
  }
  s.driver.PixelTransferf(pname, value);  // depth, index and stencil parameters stay native
}

void emPixelTransferi(GLenum pname, GLint value) { emPixelTransferf(pname, float(value)); }

namespace {

void copyEnables(const TransferState& from, TransferState& to) {
  to.colorTableEnabled = from.colorTableEnabled;
  to.postConvolutionTableEnabled = from.postConvolutionTableEnabled;
  to.postColorMatrixTableEnabled = from.postColorMatrixTableEnabled;
  to.convolution1DEnabled = from.convolution1DEnabled;
  to.convolution2DEnabled = from.convolution2DEnabled;
  to.separable2DEnabled = from.separable2DEnabled;
  to.histogramEnabled = from.histogramEnabled;
  to.minmaxEnabled = from.minmaxEnabled;
}

void copyPixelMode(const TransferState& from, TransferState& to) {
  copyEnables(from, to);
  to.scale = from.scale;
  to.bias = from.bias;
  to.mapColor = from.mapColor;
  to.postConvolutionScale = from.postConvolutionScale;
  to.postConvolutionBias = from.postConvolutionBias;
  to.postColorMatrixScale = from.postColorMatrixScale;
  to.postColorMatrixBias = from.postColorMatrixBias;
  for (size_t i = 0; i < from.tables.size(); ++i) {
    to.tables[i].scale = from.tables[i].scale;
    to.tables[i].bias = from.tables[i].bias;
  }
  for (auto member :
       {&TransferState::conv1D, &TransferState::conv2D, &TransferState::separable2D}) {
    (to.*member).scale = (from.*member).scale;
    (to.*member).bias = (from.*member).bias;
    (to.*member).borderMode = (from.*member).borderMode;
    (to.*member).borderColor = (from.*member).borderColor;
  }
}

}  // namespace

void emPushAttrib(GLbitfield mask) {
  State& s = *currentState();
  GLint before = 0, after = 0;
  s.driver.GetIntegerv(GL_ATTRIB_STACK_DEPTH, &before);
  s.driver.PushAttrib(mask);
  s.driver.GetIntegerv(GL_ATTRIB_STACK_DEPTH, &after);
  if (after == before) return;  // the driver raised GL_STACK_OVERFLOW: nothing pushed
  AttribSnapshot snap;
  snap.mask = mask;
  if ((mask & (GL_PIXEL_MODE_BIT | GL_ENABLE_BIT)) != 0) copyPixelMode(s.transfer, snap.transfer);
  snap.colorMatrixMode = s.colorMatrixMode;
  snap.clearAccum = s.clearAccum;
  s.attribStack.push_back(std::move(snap));
}

void emPopAttrib() {
  State& s = *currentState();
  s.driver.PopAttrib();
  if (s.attribStack.empty()) return;  // the driver raised GL_STACK_UNDERFLOW
  const AttribSnapshot& snap = s.attribStack.back();
  if ((snap.mask & GL_PIXEL_MODE_BIT) != 0) {
    copyPixelMode(snap.transfer, s.transfer);
  } else if ((snap.mask & GL_ENABLE_BIT) != 0) {
    copyEnables(snap.transfer, s.transfer);
  }
  if ((snap.mask & GL_TRANSFORM_BIT) != 0) s.colorMatrixMode = snap.colorMatrixMode;
  if ((snap.mask & GL_ACCUM_BUFFER_BIT) != 0) s.clearAccum = snap.clearAccum;
  s.attribStack.pop_back();
}

}  // namespace sl::imaging::detail
