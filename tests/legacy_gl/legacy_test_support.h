// tests/legacy_gl/legacy_test_support.h — which GL back ends can run the imaging-subset
// techniques (legacy.pcf, legacy.fast-pcf), for the legacy_gl and parity suites.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/gl/context.h"

namespace sl::testing {

// The reference Mesa 7.8.2 is configured and present.
inline bool referenceAvailable() {
  const std::string path = referenceGlPath();
  return !path.empty() && std::filesystem::exists(path);
}

// Back ends on which the imaging subset works: Debian's OSMesa always (imaging/ emulates it;
// should the emulation break, the tests that use it fail rather than skip), and the reference
// Mesa 7.8.2 (native imaging) where it is present.
inline std::vector<Backend> imagingBackends() {
  std::vector<Backend> b{Backend::kOsmesa};
  if (referenceAvailable()) b.push_back(Backend::kReference);
  return b;
}

}  // namespace sl::testing
