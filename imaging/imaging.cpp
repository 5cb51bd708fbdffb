// imaging/imaging.cpp — install(): native pass-through or the software emulation of the
// OpenGL 1.2 imaging subset (glspec121 3.6.2 "the imaging subset"), by replacing entries of
// the context's dispatch table, as a driver's dispatch layer would.
//
// One GL feature per file, like Mesa's old imaging code:
//   color_table.cpp     color tables, sub-tables, copies, proxies, queries, lookup stage
//   convolution.cpp     1D / 2D / separable filters, border modes, queries, convolution stage
//   color_matrix.cpp    GL_COLOR matrix stack and the color matrix stage
//   histogram.cpp       histogram and minmax tables, stages and queries
//   pixel_transfer.cpp  the stages of 3.6.5 in order on float RGBA images
//   pixel_memory.cpp    unpacking from and packing to client memory
//   pixel_paths.cpp     DrawPixels, ReadPixels, CopyPixels, TexImage2D, CopyTex(Sub)Image2D
//   accumulation.cpp    the accumulation buffer where the visual has none
//   write_back.cpp      8-bit results into the window: a blit where it equals DrawPixels
//   state.cpp           enables, queries, pixel-transfer parameters, errors
#include "imaging/imaging.h"

#include <atomic>
#include <cstdint>
#include <memory>

#include "core/base/errors.h"
#include "imaging/internal.h"

namespace sl::imaging {

namespace {
constexpr const char* kLayerKey = "imaging";

// Bumped whenever an emulation state is installed on a context or dropped with it, so that a
// lookup cached before (detail::currentState) is never taken for a context whose state has
// changed or gone, not even for a new context made at a freed one's address.
std::atomic<uint64_t> gStateGeneration{0};

// The current context's state as last looked up on this thread.
struct CachedLookup {
  const GlContext* context = nullptr;
  uint64_t generation = 0;
  detail::State* state = nullptr;
};
thread_local CachedLookup tLookup;
}  // namespace

// Every emulated call asks for the state; the context keeps it by name (a map lookup that was
// most of the drop-in library's cost on calls it passes through, docs/legacy-programs.md
// "Cost"), so the answer is kept per thread until the current context or the generation
// changes.
detail::State* detail::currentState() {
  GlContext* c = GlContext::current();
  const uint64_t generation = gStateGeneration.load(std::memory_order_acquire);
  CachedLookup& k = tLookup;
  if (c == k.context && generation == k.generation) return k.state;
  State* s = c == nullptr ? nullptr : static_cast<State*>(c->layerState(kLayerKey));
  k = CachedLookup{c, generation, s};
  return s;
}

Mode install(GlContext& context) {
  if (context.layerState(kLayerKey) != nullptr) return Mode::kEmulated;  // chosen earlier
  return install(context, context.caps().nativeImaging() ? Mode::kNative : Mode::kEmulated);
}

Mode install(GlContext& context, Mode wanted) {
  if (wanted == Mode::kNative) {
    if (!context.caps().nativeImaging())
      throw InputError(std::string("the ") + backendName(context.spec().backend) +
                       " back end has no native imaging subset (GL_ARB_imaging); only the "
                       "emulated one exists there");
    if (context.layerState(kLayerKey) != nullptr)
      throw GlError("the imaging emulation is already installed on this context");
    return Mode::kNative;  // the driver's own entries stay
  }
  if (context.layerState(kLayerKey) != nullptr) return Mode::kEmulated;  // already installed
  std::shared_ptr<detail::State> state(new detail::State, [](detail::State* dropped) {
    delete dropped;
    gStateGeneration.fetch_add(1, std::memory_order_acq_rel);
  });
  detail::State& s = *state;
  GlDispatch& d = context.dispatch();
  s.driver = d;
  s.context = &context;
  s.emulateAccum = context.caps().accumRedBits == 0;
  s.pixelBuffers = context.caps().hasExtension("GL_ARB_pixel_buffer_object") ||
                   context.caps().hasExtension("GL_EXT_pixel_buffer_object");
  detail::resetMinmax(s.transfer.minmax);
  using namespace detail;
  // The imaging subset's own entry points.
  d.ColorTable = emColorTable;
  d.ColorSubTable = emColorSubTable;
  d.CopyColorTable = emCopyColorTable;
  d.CopyColorSubTable = emCopyColorSubTable;
  d.ColorTableParameterfv = emColorTableParameterfv;
  d.ColorTableParameteriv = emColorTableParameteriv;
  d.GetColorTable = emGetColorTable;
  d.GetColorTableParameterfv = emGetColorTableParameterfv;
  d.GetColorTableParameteriv = emGetColorTableParameteriv;
  d.ConvolutionFilter1D = emConvolutionFilter1D;
  d.ConvolutionFilter2D = emConvolutionFilter2D;
  d.SeparableFilter2D = emSeparableFilter2D;
  d.CopyConvolutionFilter1D = emCopyConvolutionFilter1D;
  d.CopyConvolutionFilter2D = emCopyConvolutionFilter2D;
  d.ConvolutionParameterf = emConvolutionParameterf;
  d.ConvolutionParameterfv = emConvolutionParameterfv;
  d.ConvolutionParameteri = emConvolutionParameteri;
  d.ConvolutionParameteriv = emConvolutionParameteriv;
  d.GetConvolutionFilter = emGetConvolutionFilter;
  d.GetSeparableFilter = emGetSeparableFilter;
  d.GetConvolutionParameterfv = emGetConvolutionParameterfv;
  d.GetConvolutionParameteriv = emGetConvolutionParameteriv;
  d.Histogram = emHistogram;
  d.Minmax = emMinmax;
  d.ResetHistogram = emResetHistogram;
  d.ResetMinmax = emResetMinmax;
  d.GetHistogram = emGetHistogram;
  d.GetHistogramParameterfv = emGetHistogramParameterfv;
  d.GetHistogramParameteriv = emGetHistogramParameteriv;
  d.GetMinmax = emGetMinmax;
  d.GetMinmaxParameterfv = emGetMinmaxParameterfv;
  d.GetMinmaxParameteriv = emGetMinmaxParameteriv;
  // Entries whose behaviour the subset changes.
  d.Enable = emEnable;
  d.Disable = emDisable;
  d.IsEnabled = emIsEnabled;
  d.MatrixMode = emMatrixMode;
  d.LoadIdentity = emLoadIdentity;
  d.LoadMatrixf = emLoadMatrixf;
  d.LoadMatrixd = emLoadMatrixd;
  d.MultMatrixf = emMultMatrixf;
  d.MultMatrixd = emMultMatrixd;
  d.PushMatrix = emPushMatrix;
  d.PopMatrix = emPopMatrix;
  d.Scalef = emScalef;
  d.Translatef = emTranslatef;
  d.Scaled = emScaled;
  d.Translated = emTranslated;
  d.Rotatef = emRotatef;
  d.Rotated = emRotated;
  d.Ortho = emOrtho;
  d.Frustum = emFrustum;
  d.LoadTransposeMatrixf = emLoadTransposeMatrixf;
  d.LoadTransposeMatrixd = emLoadTransposeMatrixd;
  d.MultTransposeMatrixf = emMultTransposeMatrixf;
  d.MultTransposeMatrixd = emMultTransposeMatrixd;
  d.GetIntegerv = emGetIntegerv;
  d.GetFloatv = emGetFloatv;
  d.GetBooleanv = emGetBooleanv;
  d.GetDoublev = emGetDoublev;
  d.PixelTransferf = emPixelTransferf;
  d.PixelTransferi = emPixelTransferi;
  d.GetError = emGetError;
  d.PushAttrib = emPushAttrib;
  d.PopAttrib = emPopAttrib;
  d.DrawPixels = emDrawPixels;
  d.ReadPixels = emReadPixels;
  d.CopyPixels = emCopyPixels;
  d.CopyTexImage2D = emCopyTexImage2D;
  d.CopyTexSubImage2D = emCopyTexSubImage2D;
  d.TexImage2D = emTexImage2D;
  d.TexSubImage2D = emTexSubImage2D;
  d.TexImage1D = emTexImage1D;
  d.TexSubImage1D = emTexSubImage1D;
  d.CopyTexImage1D = emCopyTexImage1D;
  d.CopyTexSubImage1D = emCopyTexSubImage1D;
  if (s.emulateAccum) {
    d.Accum = emAccum;
    d.ClearAccum = emClearAccum;
    d.Clear = emClear;
  }
  context.setLayerState(kLayerKey, std::move(state));
  gStateGeneration.fetch_add(1, std::memory_order_acq_rel);
  return Mode::kEmulated;
}

Mode currentMode() { return detail::currentState() != nullptr ? Mode::kEmulated : Mode::kNative; }

}  // namespace sl::imaging
