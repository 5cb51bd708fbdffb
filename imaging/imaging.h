// imaging/imaging.h — the OpenGL 1.2 imaging subset (ARB_imaging) for contexts that lack it.
#pragma once

#include "core/gl/context.h"

namespace sl::imaging {

enum class Mode { kNative, kEmulated };

// Makes the imaging subset available on `context`: native pass-through when the context
// exposes GL_ARB_imaging, otherwise the software emulation replaces the imaging entry points
// of the context's dispatch table. Returns which one is in use.
Mode install(GlContext& context);
// As install(), with the implementation chosen: kEmulated installs the software emulation even
// where the context has native imaging (to compare the two on one rasteriser); kNative keeps
// the driver's and throws InputError when the context has none.
Mode install(GlContext& context, Mode wanted);
// The mode installed on the current context (kNative when install() was never called).
Mode currentMode();

}  // namespace sl::imaging
