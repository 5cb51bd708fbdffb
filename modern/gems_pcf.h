// modern/gems_pcf.h — modern.gems16 and modern.gems4: Bunnell & Pellacini, GPU Gems ch. 11.
#pragma once

#include "core/technique/technique.h"

namespace sl::modern {
Technique gems16Technique();  // 16 hardware-filtered samples over 4x4 texels (§11.3)
Technique gems4Technique();   // 4 dithered samples per pixel (§11.4, Fig. 11-4)
}  // namespace sl::modern
