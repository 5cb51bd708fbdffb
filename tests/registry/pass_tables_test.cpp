// Every technique declares its passes once (core/technique/pass_table.h): the table is well formed,
// every pass a render runs and every buffer it dumps is one of the table's, every floor the legacy
// roofline needs is declared, and every DEVIATION comment of the lessons' source files is a
// departure some pass declares (the lessons read the tables, never the source files; a helper
// several techniques share may depart for one of them only, e.g. the float clamp of legacy.ramp's
// pass 4, so the comment is matched against every table).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "core/scene/scene_library.h"
#include "core/technique/pass_table.h"
#include "registry/registry.h"

namespace sl {
namespace {

namespace fs = std::filesystem;

constexpr int kSmallWidth = 96;  // a render small enough to run every technique quickly
constexpr int kSmallHeight = 72;
constexpr int kSmallMapTexels = 128;

// A technique's tables with the --params that select each: the default table with none, each
// variant (Technique::passVariants) with its own.
struct SelectedTable {
  std::map<std::string, std::string> params;
  const PassTable* table = nullptr;
  std::string label;  // "modern.gems16 kernel=bicubic"
};
std::vector<SelectedTable> selectedTables(const Technique& t) {
  std::vector<SelectedTable> out = {{{}, &t.passes, t.name}};
  for (const PassVariant& v : t.passVariants) {
    SelectedTable s{v.params, &v.passes, t.name};
    for (const auto& [key, value] : v.params) s.label += " " + key + "=" + value;
    out.push_back(s);
  }
  return out;
}

TEST(PassTables, EveryTechniqueDeclaresAWellFormedTable) {
  for (const Technique& t : allTechniques())
    for (const SelectedTable& s : selectedTables(t)) {
      EXPECT_FALSE(s.table->empty()) << s.label << " declares no passes";
      for (const std::string& problem : passTableProblems(*s.table))
        ADD_FAILURE() << s.label << ": " << problem;
    }
}

// The variants are reachable: modern.gems16's bicubic kernel and modern.csm's table without
// the mip chain each have a table of their own, with the passes their renders run.
TEST(PassTables, VariantTablesAreDeclared) {
  struct Expected {
    std::string technique, key, value;
  };
  for (const Expected& e : {Expected{"modern.gems16", "kernel", "bicubic"},
                            Expected{"modern.csm", "filtering", "bilinear"}}) {
    const Technique& t = findTechnique(e.technique);
    EXPECT_TRUE(std::any_of(t.passVariants.begin(), t.passVariants.end(),
                            [&](const PassVariant& v) {
                              const auto at = v.params.find(e.key);
                              return at != v.params.end() && at->second == e.value;
                            }))
        << e.technique << " declares no table for --param " << e.key << "=" << e.value;
  }
}

// Each pass a frame ran, and each buffer it captured, names a pass of the table its --params
// select; the frame's pass carries that table's reference and floor.
TEST(PassTables, EveryPassAndBufferOfARenderIsDeclared) {
  const Scene scene = builtinScene("brabec");
  for (const Technique& t : allTechniques())
    for (const SelectedTable& s : selectedTables(t)) {
      RenderParams p;
      p.width = kSmallWidth;
      p.height = kSmallHeight;
      p.shadowMapTexels = kSmallMapTexels;
      p.capturePasses = true;
      if (t.name == "reference.soft") p.extra["rays"] = "4";  // the dump, not the noise
      for (const auto& [key, value] : s.params) p.extra[key] = value;
      const Frame frame = renderTechnique(t, scene, p);
      ASSERT_FALSE(frame.passes.empty()) << s.label;
      for (const PassTime& pass : frame.passes) {
        ASSERT_FALSE(pass.id.empty()) << s.label << ": pass '" << pass.name << "' has no id";
        const PassSpec& spec = findPassSpec(*s.table, pass.id);
        EXPECT_EQ(pass.section, spec.reference) << s.label << " " << pass.id;
        EXPECT_EQ(pass.floor, spec.floor) << s.label << " " << pass.id;
      }
      for (const PassImage& image : frame.intermediates) {
        ASSERT_FALSE(image.passId.empty()) << s.label << ": buffer " << image.name;
        EXPECT_NO_THROW(findPassSpec(*s.table, image.passId)) << s.label << " " << image.name;
      }
    }
}

// The lines a pass table declares as key (PassSpec::keyState, highlighted on the lessons' state
// cards) are there: each word is in some traced line of its pass at the 2x2 and at the 4x4
// footprint, so a renamed call or a moved state change cannot leave a card without its
// highlight unnoticed.
TEST(PassTables, EveryDeclaredKeyStateWordIsInItsPassesTrace) {
  const Scene scene = builtinScene("brabec");
  size_t checked = 0;
  for (const Technique& t : allTechniques()) {
    std::map<std::string, std::set<std::string>> found;  // pass id -> key words seen
    std::set<std::string> ran;
    for (const int filter : {2, 4}) {
      RenderParams p;
      p.width = kSmallWidth;
      p.height = kSmallHeight;
      p.shadowMapTexels = kSmallMapTexels;
      p.filter = filter;
      p.capturePasses = true;
      if (t.name == "reference.soft") p.extra["rays"] = "4";
      const Frame frame = renderTechnique(t, scene, p);
      for (const PassTime& pass : frame.passes) {
        ran.insert(pass.id);
        for (const std::string& key : pass.keyState)
          for (const auto* lines : {&pass.gl.setup, &pass.gl.state})
            for (const GlStateLine& l : *lines)
              if (l.text.find(key) != std::string::npos) found[pass.id].insert(key);
      }
    }
    for (const PassSpec& spec : t.passes) {
      if (!ran.count(spec.id)) continue;  // a pass of another configuration (csm's "5")
      for (const std::string& key : spec.keyState) {
        EXPECT_TRUE(found[spec.id].count(key))
            << t.name << " pass " << spec.id << " declares the key state \"" << key
            << "\", which none of its traced lines holds";
        ++checked;
      }
    }
  }
  EXPECT_GT(checked, 20u) << "the pass tables declare hardly any key state";
}

// The text of every `DEVIATION (source, section): why` comment of a file: from "DEVIATION (" to
// the end of its comment block (a blank comment line or code ends it), spaces normalised.
std::vector<std::string> deviationComments(const fs::path& file) {
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  static const std::regex kComment(R"(^\s*//\s?(.*)$)");
  std::vector<std::string> out;
  for (size_t i = 0; i < lines.size(); ++i) {
    const size_t at = lines[i].find("DEVIATION (");
    const size_t slashes = lines[i].find("//");
    if (at == std::string::npos || slashes == std::string::npos || slashes > at) continue;
    std::string text = lines[i].substr(at);
    std::smatch m;
    for (size_t j = i + 1; j < lines.size() && std::regex_match(lines[j], m, kComment); ++j) {
      const std::string more = m[1].str();
      if (more.empty() || more.find("DEVIATION (") != std::string::npos) break;
      text += " " + more;
    }
    out.push_back(std::regex_replace(text, std::regex(R"(\s+)"), " "));
  }
  return out;
}

// A declared departure matches a comment when it is the comment's beginning, at least its
// first sentence (the comment may go on with the reasons for a constant).
bool declares(const std::string& declared, const std::string& comment) {
  const std::string d = std::regex_replace(declared, std::regex(R"(\s+)"), " ");
  const size_t firstSentence = comment.find(". ");
  const size_t needed = firstSentence == std::string::npos ? comment.size() : firstSentence + 1;
  return d.size() >= needed && comment.compare(0, d.size(), d) == 0;
}

TEST(PassTables, EveryDeviationCommentOfALessonsSourcesIsDeclaredByAPass) {
  const fs::path assets(assetDirectory());
  const fs::path root = assets.parent_path();
  std::vector<std::string> declared;
  for (const Technique& t : allTechniques())
    for (const PassTable* table : allPassTables(t))
      for (const PassSpec& p : *table)
        declared.insert(declared.end(), p.deviations.begin(), p.deviations.end());
  int checked = 0;
  for (const auto& entry : fs::directory_iterator(assets / "lessons")) {
    std::ifstream in(entry.path());
    const nlohmann::json text = nlohmann::json::parse(in);
    for (const nlohmann::json& lesson : text["lessons"]) {
      for (const std::string& source : lesson.value("sources", std::vector<std::string>{}))
        for (const std::string& comment : deviationComments(root / source)) {
          ++checked;
          EXPECT_TRUE(std::any_of(declared.begin(), declared.end(),
                                  [&](const std::string& d) { return declares(d, comment); }))
              << source << ": " << comment << "\n  is declared by no pass (lesson of "
              << lesson["techniques"].dump() << ")";
        }
    }
  }
  EXPECT_GT(checked, 0) << "no DEVIATION comment found: the sources were not read";
}

}  // namespace
}  // namespace sl
