// The links between a modern twin and its legacy twin, by pass id (core/technique/pass_table.h):
// every modern twin's pass table says which legacy passes each of its passes `replaces`, and the
// GLSL it runs says the same in `// @replaces legacy.X ID` lines (core/gl/shaders.h). For every
// twin (registry/twins.h): each id named by the table or by a shader exists in the legacy twin's
// table, the table and the shaders agree pass by pass, and every legacy pass but the mesh
// feeding (which has no counterpart: the shaders light per fragment) is replaced by some
// modern pass.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "core/gl/shaders.h"
#include "registry/registry.h"
#include "registry/twins.h"

namespace sl {
namespace {

// The id of the mesh-feeding pass of the legacy camera passes (legacy_gl/spotlight_tessellation.h).
const std::string kMeshFeeding = "mesh";
// Each twin pair of registry/twins.cpp: ramp, pcf, fast-pcf, hw, woo, second-depth.
constexpr size_t kTwins = 6;

// One pair per modern twin.
std::map<std::string, twins::TwinPair> pairByModern() {
  std::map<std::string, twins::TwinPair> out;
  for (const twins::TwinPair& p : twins::twinPairs()) out.emplace(p.modern, p);
  return out;
}

// The ids of the legacy twin's passes, from its table.
std::vector<std::string> legacyPassIds(const twins::TwinPair& pair) {
  std::vector<std::string> ids;
  for (const PassSpec& spec : findTechnique(pair.legacy).passes) ids.push_back(spec.id);
  return ids;
}

// The legacy pass ids that the `// @replaces` lines of marker `marker` name for `legacy`.
std::set<std::string> markerReplaces(const std::string& marker, const std::string& legacy) {
  std::set<std::string> out;
  for (const ShaderPassMarker& m : shaderPassMarkers())
    if (m.id == marker)
      for (const ShaderReplaces& r : m.replaces)
        if (r.technique == legacy) out.insert(r.passId);
  return out;
}

// Every `// @replaces` line names a technique of the legacy family (Technique::family, as the
// registry declares it) and a pass of its table.
TEST(TwinPassLinks, EveryReplacesMarkerNamesALegacyTechniquesPass) {
  size_t lines = 0;
  for (const ShaderPassMarker& m : shaderPassMarkers())
    for (const ShaderReplaces& r : m.replaces) {
      ++lines;
      const Technique& legacy = findTechnique(r.technique);
      EXPECT_EQ(legacy.family, TechniqueFamily::kLegacy) << m.file << " @pass " << m.id;
      EXPECT_NO_THROW(findPassSpec(legacy.passes, r.passId)) << m.file << " @pass " << m.id;
    }
  EXPECT_GT(lines, 0u) << "no @replaces line in the embedded shaders";
}

TEST(TwinPassLinks, EveryTwinPassTableAndItsShadersNameTheLegacyPassesTheyReplace) {
  const auto pairs = pairByModern();
  ASSERT_EQ(pairs.size(), kTwins) << "a twin pair is missing from this build";
  for (const auto& [modernName, pair] : pairs) {
    SCOPED_TRACE(modernName + " (twin of " + pair.legacy + ")");
    const PassTable& table = findTechnique(modernName).passes;
    ASSERT_FALSE(table.empty()) << modernName << " declares no pass table";
    EXPECT_TRUE(passTableProblems(table).empty());
    const std::vector<std::string> legacyIds = legacyPassIds(pair);
    ASSERT_FALSE(legacyIds.empty());
    const std::set<std::string> legacy(legacyIds.begin(), legacyIds.end());

    std::set<std::string> replaced;
    std::set<std::string> markersRun;
    for (const PassSpec& spec : table) {
      SCOPED_TRACE("pass " + spec.id + " " + spec.name);
      EXPECT_FALSE(spec.shaders.empty()) << "a modern pass runs GLSL";
      EXPECT_FALSE(spec.replaces.empty()) << "a twin's pass does some legacy pass's work";
      std::set<std::string> fromShaders;
      for (const std::string& marker : spec.shaders) {
        markersRun.insert(marker);
        const std::set<std::string> ids = markerReplaces(marker, pair.legacy);
        fromShaders.insert(ids.begin(), ids.end());
      }
      for (const std::string& id : spec.replaces) {
        EXPECT_TRUE(legacy.count(id)) << "replaces " << pair.legacy << " pass " << id << ", which "
                                      << pair.legacy << " does not have";
        replaced.insert(id);
      }
      EXPECT_EQ(std::set<std::string>(spec.replaces.begin(), spec.replaces.end()), fromShaders)
          << "the table's replaces and the @replaces lines of the shaders it runs differ";
    }
    // Every @replaces line for this twin names a legacy pass and sits in a marker the modern
    // twin runs.
    for (const ShaderPassMarker& m : shaderPassMarkers())
      for (const ShaderReplaces& r : m.replaces) {
        if (r.technique != pair.legacy) continue;
        EXPECT_TRUE(legacy.count(r.passId))
            << m.file << " @pass " << m.id << " replaces " << pair.legacy << " " << r.passId
            << ", which " << pair.legacy << " does not have";
        EXPECT_TRUE(markersRun.count(m.id))
            << m.file << " @pass " << m.id << " replaces " << pair.legacy << " " << r.passId
            << ", but no pass of " << modernName << " runs that marker";
      }
    for (const std::string& id : legacyIds) {
      if (id == kMeshFeeding) continue;
      EXPECT_TRUE(replaced.count(id))
          << pair.legacy << " pass " << id << " is replaced by no pass of " << modernName;
    }
  }
}

}  // namespace
}  // namespace sl
