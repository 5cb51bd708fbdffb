// imaging/imaging.h — the OpenGL 1.2 imaging subset (ARB_imaging) for contexts that lack it.
#pragma once

#include "core/context.h"

namespace sl::imaging {

enum class Mode { kNative, kEmulated };

// Makes the imaging subset available on `context`: native pass-through when the context
// exposes GL_ARB_imaging, otherwise the software emulation replaces the imaging entry points
// of the context's dispatch table. Returns which one is in use.
Mode install(GlContext& context);
// The mode installed on the current context (kNative when install() was never called).
Mode currentMode();

}  // namespace sl::imaging
