// legacy_gl/legacy.h — the 2001 techniques in OpenGL 1.x fixed function (public header).
//
//   legacy.hw           Everitt, Rege, Cebenoyan 2001: ARB_depth_texture + ARB_shadow
//   legacy.ramp         Brabec & Seidel 2001 §2: depth as colour through a 1D ramp texture
//   legacy.pcf          Brabec & Seidel 2001 §3: jittered channel packing + colour table/matrix
//   legacy.fast-pcf     Brabec & Seidel 2001 §4: convolution packing + accumulation buffer
//   legacy.woo          Woo's midpoint shadow map (Everitt §3 discussion)
//   legacy.second-depth Wang & Molnar's second-depth shadow map
#pragma once

#include <vector>

#include "core/technique/technique.h"

namespace sl::legacy {

std::vector<Technique> techniques();

}  // namespace sl::legacy
