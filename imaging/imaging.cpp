#include "imaging/imaging.h"

namespace sl::imaging {

Mode install(GlContext& context) {
  if (context.caps().nativeImaging()) return Mode::kNative;
  // TODO(imaging issue): install the software emulation.
  return Mode::kEmulated;
}

Mode currentMode() { return Mode::kNative; }

}  // namespace sl::imaging
