// core/technique/pass_table.cpp — see pass_table.h.
#include "core/technique/pass_table.h"

#include <set>
#include <stdexcept>

namespace sl {

const char* passFloorName(PassFloor floor) {
  switch (floor) {
    case PassFloor::kNone: return "none";
    case PassFloor::kCpuOnly: return "cpu-only";
    case PassFloor::kLightDepth: return "light-depth";
    case PassFloor::kLightDepthAndCopy: return "light-depth-and-copy";
    case PassFloor::kJitteredLightGroup: return "jittered-light-group";
    case PassFloor::kCopyToTexture: return "copy-to-texture";
    case PassFloor::kCameraDepth: return "camera-depth";
    case PassFloor::kProjectiveSubtract: return "projective-subtract";
    case PassFloor::kCopyPixels: return "copy-pixels";
    case PassFloor::kAccumulate: return "accumulate";
    case PassFloor::kAccumulationReturn: return "accumulation-return";
    case PassFloor::kLighting: return "lighting";
    case PassFloor::kCopyWindowToTexture: return "copy-window-to-texture";
    case PassFloor::kTexturedWindowQuad: return "textured-window-quad";
    case PassFloor::kStateOnly: return "state-only";
    case PassFloor::kDepthFromLight: return "depth-from-light";
    case PassFloor::kAmbientCamera: return "ambient-camera";
    case PassFloor::kShadowedDirectLight: return "shadowed-direct-light";
    case PassFloor::kVisibilityMask: return "visibility-mask";
  }
  return "?";
}

const PassSpec& findPassSpec(const PassTable& table, const std::string& id) {
  for (const PassSpec& p : table)
    if (p.id == id) return p;
  throw std::logic_error("the pass table has no pass \"" + id + "\"");
}

std::vector<std::string> passTableProblems(const PassTable& table) {
  std::vector<std::string> problems;
  std::set<std::string> ids;
  for (const PassSpec& p : table) {
    if (p.id.empty()) problems.push_back("a pass without an id (\"" + p.name + "\")");
    if (!ids.insert(p.id).second) problems.push_back("pass id \"" + p.id + "\" declared twice");
    if (p.name.empty()) problems.push_back("pass \"" + p.id + "\" has no name");
    if (p.reference.empty()) problems.push_back("pass \"" + p.id + "\" cites nothing");
    std::set<std::string> buffers;
    for (const PassBuffer& b : p.writes)
      if (b.name.empty() || !buffers.insert(b.name).second)
        problems.push_back("pass \"" + p.id + "\" declares buffer \"" + b.name +
                           "\" twice or empty");
  }
  return problems;
}

}  // namespace sl
