// tests/figures/gallery_test.cpp — the artefact gallery (figures/gallery.h): every entry's
// `shadowlab render` command parses with the CLI's parser and names what the entry says, its lab
// link names the same state, and its one parameter really changes the picture where the
// artefact is (the wrong and right images differ inside the close-up window).
#include "figures/gallery.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "core/base/image.h"
#include "registry/cli.h"

using namespace sl;
using namespace sl::figures;

namespace {

// A pixel differs visibly when a colour channel moves by more than this (about 25 of 255 8-bit
// levels: well above the 1-level noise of re-rendering, well below an artefact's contrast).
constexpr float kVisibleDifference = 0.1f;
// Pixels of the close-up window that must differ visibly: the thinnest artefact here (the
// ragged terminator of projective aliasing, a line of steps across the sphere) measures 71, the
// light gap of Peter-panning and the hybrid's missing bar shadow about 150; a change of a few
// stray pixels (re-rendering noise, an edge moved by one pixel) stays far below 50.
constexpr long long kMinDifferingPixels = 50;

std::vector<std::string> splitWords(const std::string& command) {
  std::vector<std::string> words;
  std::istringstream in(command);
  for (std::string w; in >> w;) words.push_back(w);
  return words;
}

cli::Args parseCommand(const std::string& command) {
  std::vector<std::string> words = splitWords(command);
  std::vector<char*> argv;
  for (std::string& w : words) argv.push_back(w.data());
  return cli::parse(int(argv.size()), argv.data());
}

// The query's key=value pairs, percent-decoded (the gallery encodes only what needs it).
std::vector<std::pair<std::string, std::string>> queryPairs(const std::string& query) {
  std::vector<std::pair<std::string, std::string>> out;
  std::istringstream in(query);
  for (std::string item; std::getline(in, item, '&');) {
    const size_t eq = item.find('=');
    std::string value = item.substr(eq + 1), decoded;
    for (size_t i = 0; i < value.size(); ++i) {
      if (value[i] == '%' && i + 2 < value.size()) {
        decoded += char(std::stoi(value.substr(i + 1, 2), nullptr, 16));
        i += 2;
      } else {
        decoded += value[i];
      }
    }
    out.emplace_back(item.substr(0, eq), decoded);
  }
  return out;
}

// One side's options as the lab link names them, in the CLI's spelling ("--shadow-map 128"),
// sorted: the global keys, the side's technique, and its a-/b- keys.
std::multiset<std::string> linkSide(const std::string& query, const std::string& lane) {
  std::multiset<std::string> out;
  for (const auto& [k, v] : queryPairs(query)) {
    if (k == "zoom" || k == "center" || k == "wipe" || k == "view") continue;
    if (k == lane)
      out.insert("--technique " + v);
    else if (k.rfind(lane + "-", 0) == 0)
      out.insert("--" + k.substr(lane.size() + 1) + " " + v);
    else if (k != "a" && k != "b" && k.rfind("a-", 0) != 0 && k.rfind("b-", 0) != 0)
      out.insert("--" + k + " " + v);
  }
  return out;
}

std::multiset<std::string> commandSide(const GalleryEntry& e, bool wrongSide) {
  const std::vector<std::string> a = galleryRenderArguments(e, wrongSide);
  std::multiset<std::string> out;
  for (size_t i = 0; i + 1 < a.size(); i += 2) out.insert(a[i] + " " + a[i + 1]);
  return out;
}

}  // namespace

TEST(Gallery, EntriesAreUniqueAndTheirWindowsLieInsideThePicture) {
  std::set<std::string> ids;
  ASSERT_GE(galleryEntries().size(), 10u);
  for (const GalleryEntry& e : galleryEntries()) {
    EXPECT_TRUE(ids.insert(e.id).second) << e.id;
    EXPECT_FALSE(e.title.empty() || e.shows.empty() || e.parameter.empty() || e.fix.empty())
        << e.id;
    const GalleryWindow& w = e.closeup;
    EXPECT_GE(w.x, 0) << e.id;
    EXPECT_GE(w.y, 0) << e.id;
    EXPECT_LE(w.x + w.width, e.width) << e.id;
    EXPECT_LE(w.y + w.height, e.height) << e.id;
    EXPECT_GE(w.magnify, 2) << e.id;
    // The pair differs: in a parameter, or in the technique.
    EXPECT_TRUE(e.wrong != e.right || e.wrongTechnique != e.rightTechnique) << e.id;
  }
}

TEST(Gallery, EveryCommandParsesAndTheLabLinkNamesTheSameState) {
  for (const GalleryEntry& e : galleryEntries())
    for (bool wrongSide : {true, false}) {
      const std::string command = galleryRenderCommand(e, wrongSide);
      SCOPED_TRACE(command);
      ASSERT_EQ(command.find_first_of("'\"\\"), std::string::npos);  // no quoting to undo
      const cli::Args args = parseCommand(command);
      EXPECT_EQ(args.command, "render");
      EXPECT_EQ(args.required("technique"), wrongSide ? e.wrongTechnique : e.rightTechnique);
      EXPECT_EQ(args.required("scene"), e.scene);
      EXPECT_EQ(args.required("out"), e.id + (wrongSide ? "-wrong.png" : "-right.png"));
      // The options take effect as the CLI reads them (numbers in range, known keys).
      const RenderParams p = cli::renderParams(args);
      EXPECT_EQ(p.width, e.width);
      EXPECT_EQ(p.height, e.height);
      EXPECT_EQ(linkSide(galleryLabQuery(e), wrongSide ? "a" : "b"), commandSide(e, wrongSide));
    }
}

TEST(Gallery, TheParameterChangesThePictureWhereTheArtefactIs) {
  const std::filesystem::path dir = std::filesystem::path(SHADOWLAB_TEST_OUTPUT_DIR) / "gallery";
  std::filesystem::create_directories(dir);
  for (const GalleryEntry& e : galleryEntries()) {
    SCOPED_TRACE(e.id);
    const Image wrong = renderGalleryPicture(e, true);
    const Image right = renderGalleryPicture(e, false);
    ASSERT_EQ(wrong.width, e.width);
    ASSERT_EQ(wrong.height, e.height);
    ASSERT_EQ(right.width, wrong.width);
    ASSERT_EQ(right.height, wrong.height);
    const GalleryWindow& w = e.closeup;
    long long inside = 0, outside = 0;
    for (int y = 0; y < e.height; ++y)
      for (int x = 0; x < e.width; ++x) {
        const int row = e.height - 1 - y;  // the image's rows count from the bottom
        float largest = 0.0f;
        for (int c = 0; c < std::min(wrong.channels, 3); ++c)
          largest = std::max(largest, std::fabs(wrong.at(x, row, c) - right.at(x, row, c)));
        if (!(largest > kVisibleDifference)) continue;
        const bool in = x >= w.x && x < w.x + w.width && y >= w.y && y < w.y + w.height;
        ++(in ? inside : outside);
      }
    const long long windowPixels = (long long)w.width * w.height;
    const double insideShare = double(inside) / double(windowPixels);
    const double outsideShare =
        double(outside) / double((long long)e.width * e.height - windowPixels);
    std::cout << e.id << ": " << inside << " of " << windowPixels
              << " close-up pixels differ visibly (" << 100.0 * insideShare << " %), outside "
              << 100.0 * outsideShare << " %\n";
    EXPECT_GE(inside, kMinDifferingPixels);
    // The window frames the artefact: differences are denser inside it than outside.
    EXPECT_GT(insideShare, outsideShare);
  }
}
