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

// The options beyond a table's --params that make a render run its optional passes: the PCF
// footprints above 2x2 save and restore the camera pass and sum groups in the accumulation
// buffer (Brabec & Seidel §3), modern.csm reconstructs every pixel without the depth bounds'
// skip (pass 5 instead of 5c), the references rasterise sub-pixel points with pixel=area.
// A technique whose table gains a pass that only some option runs lists that option here.
std::vector<RenderParams> optionalPassRenders(const Technique& t, const RenderParams& base) {
  std::vector<RenderParams> out;
  if (readsOption(t, CommonOption::kFilter)) {
    RenderParams p = base;
    p.filter = 4;
    out.push_back(p);
  }
  if (t.name == "modern.csm") {
    RenderParams p = base;
    p.extra["skip-error"] = "0";
    out.push_back(p);
  }
  if (findParam(t, "pixel") != nullptr) {
    RenderParams p = base;
    p.extra["pixel"] = "area";
    p.extra["pixel-samples"] = "2";  // which passes run, not the quality of the integral
    out.push_back(p);
  }
  return out;
}

// Each pass a frame ran, and each buffer it captured, names a pass of the table its --params
// select; and the table declares no pass that neither the frame nor the renders with its
// optional passes (optionalPassRenders) run: a pass renamed, dropped or moved to another table
// shows here. (The section and floor a frame reports are copied from the table by
// core/technique/passes.cpp, so only the ids can disagree.)
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
      std::vector<RenderParams> renders = {p};
      for (const RenderParams& o : optionalPassRenders(t, p)) renders.push_back(o);
      std::set<std::string> ran;
      for (const RenderParams& r : renders) {
        const Frame frame = renderTechnique(t, scene, r);
        ASSERT_FALSE(frame.passes.empty()) << s.label;
        for (const PassTime& pass : frame.passes) {
          ASSERT_FALSE(pass.id.empty()) << s.label << ": pass '" << pass.name << "' has no id";
          EXPECT_NO_THROW(findPassSpec(*s.table, pass.id)) << s.label << " " << pass.id;
          ran.insert(pass.id);
        }
        for (const PassImage& image : frame.intermediates) {
          ASSERT_FALSE(image.passId.empty()) << s.label << ": buffer " << image.name;
          EXPECT_NO_THROW(findPassSpec(*s.table, image.passId)) << s.label << " " << image.name;
        }
      }
      for (const PassSpec& spec : *s.table)
        EXPECT_TRUE(ran.count(spec.id)) << s.label << " declares pass " << spec.id << " ("
                                        << spec.name << ") that no render of it runs";
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
