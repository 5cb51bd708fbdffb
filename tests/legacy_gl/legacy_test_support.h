// tests/legacy_gl/legacy_test_support.h — which GL back ends can run the imaging-subset
// techniques (legacy.pcf, legacy.fast-pcf), for the legacy_gl and parity suites.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "core/context.h"
#include "core/gl.h"
#include "imaging/imaging.h"

namespace sl::testing {

// The reference Mesa 7.8.2 is configured and present.
inline bool referenceAvailable() {
  const std::string path = referenceGlPath();
  return !path.empty() && std::filesystem::exists(path);
}

// Debian's OSMesa with imaging::install() really provides a colour table (the imaging
// emulation of the imaging issue has landed): probed with one glColorTable call.
inline bool emulatedImagingWorks() {
  try {
    ContextSpec spec;
    spec.width = 8;
    spec.height = 8;
    auto ctx = GlContext::create(spec);
    imaging::install(*ctx);
    const float table[2 * 4] = {0, 0, 0, 0, 1, 1, 1, 1};
    while (gl::glGetError() != GL_NO_ERROR) {
    }
    gl::glColorTable(GL_COLOR_TABLE, GL_RGBA8, 2, GL_RGBA, GL_FLOAT, table);
    return gl::glGetError() == GL_NO_ERROR;
  } catch (const std::exception&) {
    return false;
  }
}

// Back ends on which the imaging subset works, native or emulated.
inline std::vector<Backend> imagingBackends() {
  std::vector<Backend> b;
  if (emulatedImagingWorks()) b.push_back(Backend::kOsmesa);
  if (referenceAvailable()) b.push_back(Backend::kReference);
  return b;
}

constexpr const char* kNoImagingMessage =
    "no GL with the imaging subset: the reference GL (../shared/reference-gl) is absent and the "
    "imaging emulation on Debian OSMesa has not landed (branch imaging)";

}  // namespace sl::testing
