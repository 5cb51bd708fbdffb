// modern/hybrid_shadows.h — modern.hybrid (Chan 2004, ch. 3: hybrid shadow maps and shadow
// volumes with a computation mask).
#pragma once

#include "core/technique/technique.h"

namespace sl::modern {
Technique hybridShadowsTechnique();
}  // namespace sl::modern
