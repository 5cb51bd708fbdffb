// core/base/output_files.h as the commands use it: every destination checked up
// front, written through temporaries, renamed together at the end, or none at all. The
// commands' own cases are in cli_test.cpp; these drive OutputSet directly, including a commit
// that fails half-way.
#include "core/base/output_files.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "command_util.h"
#include "core/base/errors.h"

namespace sl {
namespace {
namespace fs = std::filesystem;
using test::slurp;

fs::path freshDir() { return test::testDir("output_files", true); }

// A fresh directory per test (ctest runs the cases as parallel processes).
void put(const fs::path& p, const std::string& text) { std::ofstream(p) << text; }

// The names in `d`, sorted.
std::set<std::string> names(const fs::path& d) {
  std::set<std::string> out;
  for (const auto& e : fs::directory_iterator(d)) out.insert(e.path().filename().string());
  return out;
}

TEST(OutputSet, CommitReplacesAndCreatesEveryDestination) {
  const fs::path d = freshDir();
  put(d / "old.txt", "old");
  {
    OutputSet outputs;
    const std::string a = outputs.addFile("--a", (d / "old.txt").string());
    const std::string b = outputs.addFile("--b", (d / "new.txt").string());
    const std::string dump = outputs.addDirectory("--dump", (d / "x" / "y").string());
    EXPECT_EQ(names(d), (std::set<std::string>{"old.txt"})) << "nothing exists before writing";
    outputs.beginWriting();
    put(a, "A");
    put(b, "B");
    put(fs::path(dump) / "p.png", "P");
    outputs.commit();
  }
  EXPECT_EQ(slurp(d / "old.txt"), "A");
  EXPECT_EQ(slurp(d / "new.txt"), "B");
  EXPECT_EQ(slurp(d / "x" / "y" / "p.png"), "P");
  EXPECT_EQ(names(d), (std::set<std::string>{"new.txt", "old.txt", "x"})) << "no temporary left";
}

TEST(OutputSet, WithoutCommitNothingChanges) {
  const fs::path d = freshDir();
  put(d / "old.txt", "old");
  {
    OutputSet outputs;
    put(outputs.addFile("--a", (d / "old.txt").string()), "A");
    put(outputs.addFile("--b", (d / "new.txt").string()), "B");
    outputs.addDirectory("--dump", (d / "dump").string());
    outputs.beginWriting();
  }  // a failed run: the destructor runs without commit()
  EXPECT_EQ(slurp(d / "old.txt"), "old");
  EXPECT_EQ(names(d), (std::set<std::string>{"old.txt"}));
}

// The second rename fails (its temporary is gone): the first destination, already renamed,
// gets its previous content back, a new one disappears, and commit() throws.
TEST(OutputSet, FailedCommitIsUndone) {
  const fs::path d = freshDir();
  put(d / "first.txt", "old first");
  fs::create_directories(d / "dump");
  put(d / "dump" / "old.png", "old pass");
  {
    OutputSet outputs;
    put(outputs.addFile("--first", (d / "first.txt").string()), "new first");
    put(outputs.addFile("--new", (d / "new.txt").string()), "new");
    const std::string dump = outputs.addDirectory("--dump", (d / "dump").string());
    const std::string lost = outputs.addFile("--lost", (d / "lost.txt").string());
    outputs.beginWriting();
    put(fs::path(dump) / "new.png", "new pass");
    // `lost` is never written.
    EXPECT_THROW(outputs.commit(), InputError);
    (void)lost;
  }
  EXPECT_EQ(slurp(d / "first.txt"), "old first");
  EXPECT_EQ(names(d / "dump"), (std::set<std::string>{"old.png"}));
  EXPECT_EQ(names(d), (std::set<std::string>{"dump", "first.txt"}));
}

// A previous dump (PNGs, passes.json, index.html, teach/pass_dump.h) is replaced as a whole; a
// directory holding anything else is refused untouched.
TEST(OutputSet, ReplacesOnlyAPreviousDump) {
  const fs::path d = freshDir();
  fs::create_directories(d / "dump");
  for (const char* name : {"01-old.png", "passes.json", "index.html"})
    put(d / "dump" / name, "old");
  {
    OutputSet outputs;
    const std::string dump = outputs.addDirectory("--dump", (d / "dump").string());
    outputs.beginWriting();
    put(fs::path(dump) / "01-new.png", "new");
    put(fs::path(dump) / "passes.json", "{}");
    outputs.commit();
  }
  EXPECT_EQ(names(d / "dump"), (std::set<std::string>{"01-new.png", "passes.json"}));
  for (const char* other : {"notes.txt", "index.html.bak", "passes.json.txt"}) {
    put(d / "dump" / other, "mine");
    OutputSet outputs;
    EXPECT_THROW(outputs.addDirectory("--dump", (d / "dump").string()), InputError) << other;
    EXPECT_EQ(slurp(d / "dump" / other), "mine");
    fs::remove(d / "dump" / other);
  }
  fs::create_directories(d / "dump" / "index.html" / "sub");
  OutputSet outputs;
  EXPECT_THROW(outputs.addDirectory("--dump", (d / "dump").string()), InputError)
      << "a directory named index.html is no dump file";
}

TEST(OutputSet, RefusesCollisionsAndUnsafeDestinations) {
  const fs::path d = freshDir();
  put(d / "scene.json", "{}");
  fs::create_directories(d / "mine");
  put(d / "mine" / "notes.txt", "keep");
  OutputSet outputs;
  outputs.addInput((d / "scene.json").string());
  outputs.addFile("--out", (d / "out.png").string());
  EXPECT_THROW(outputs.addFile("--mask", (d / "out.png").string()), InputError);
  EXPECT_THROW(outputs.addFile("--mask", (d / "sub" / ".." / "out.png").string()), InputError);
  EXPECT_THROW(outputs.addFile("--mask", (d / "scene.json").string()), InputError);
  EXPECT_THROW(outputs.addFile("--mask", (d / "mine").string()), InputError) << "a directory";
  EXPECT_THROW(outputs.addFile("--mask", (d / "nowhere" / "m.png").string()), InputError);
  EXPECT_THROW(outputs.addFile("--mask", (d / std::string(300, 'm')).string()), InputError);
  EXPECT_THROW(outputs.addFile("--mask", "/proc/m.png"), InputError);
  EXPECT_THROW(outputs.addFile("--mask", "/dev/null"), InputError) << "not a regular file";
  EXPECT_THROW(outputs.addFile("--mask", ""), InputError);
  EXPECT_THROW(outputs.addDirectory("--dump", (d / "mine").string()), InputError)
      << "holds a file that is not a previous dump's PNG";
  EXPECT_THROW(outputs.addDirectory("--dump", d.string()), InputError) << "holds --out";
  EXPECT_THROW(outputs.addDirectory("--dump", "."), InputError) << "the current directory";
  EXPECT_EQ(slurp(d / "mine" / "notes.txt"), "keep");
  EXPECT_EQ(names(d), (std::set<std::string>{"mine", "scene.json"}));
}

// A destination that is a symbolic link is written through it: the file it names is
// replaced, the link stays.
TEST(OutputSet, WritesThroughASymbolicLink) {
  const fs::path d = freshDir();
  put(d / "target.png", "old");
  fs::create_symlink(d / "target.png", d / "link.png");
  OutputSet outputs;
  put(outputs.addFile("--out", (d / "link.png").string()), "new");
  outputs.commit();
  EXPECT_TRUE(fs::is_symlink(d / "link.png"));
  EXPECT_EQ(slurp(d / "target.png"), "new");
}

// Temporaries of long names are shortened so that a writer's own suffix still fits.
TEST(OutputSet, TemporaryOfALongNameFits) {
  const fs::path d = freshDir();
  const fs::path longName = d / (std::string(250, 'n') + ".png");
  OutputSet outputs;
  const std::string temp = outputs.addFile("--out", longName.string());
  EXPECT_LE(fs::path(temp).filename().string().size() + std::string(".part-4194304").size(), 255u);
  put(temp, "x");
  outputs.commit();
  EXPECT_EQ(slurp(longName), "x");
}

TEST(WriteFileAtomically, AFailedWriterLeavesNothing) {
  const fs::path d = freshDir();
  put(d / "data.csv", "old");
  EXPECT_THROW(writeFileAtomically((d / "data.csv").string(),
                                   [](std::ostream& out) {
                                     out << "half";
                                     throw InputError("failed half-way");
                                   }),
               InputError);
  EXPECT_EQ(slurp(d / "data.csv"), "old");
  EXPECT_EQ(names(d), (std::set<std::string>{"data.csv"}));
  writeFileAtomically((d / "data.csv").string(), [](std::ostream& out) { out << "new"; });
  EXPECT_EQ(slurp(d / "data.csv"), "new");
  EXPECT_EQ(names(d), (std::set<std::string>{"data.csv"}));
}

TEST(CheckDirectoryCreatable, FindsTheNearestExistingFolder) {
  const fs::path d = freshDir();
  EXPECT_NO_THROW(checkDirectoryCreatable("--out", (d / "a" / "b").string()));
  EXPECT_FALSE(fs::exists(d / "a")) << "checked, not made";
  EXPECT_THROW(checkDirectoryCreatable("--out", "/proc/nonexistent/bench"), InputError);
  put(d / "file", "x");
  EXPECT_THROW(checkDirectoryCreatable("--out", (d / "file").string()), InputError);
  EXPECT_THROW(checkDirectoryCreatable("--out", (d / "file" / "sub").string()), InputError);
  EXPECT_EQ(names(d), (std::set<std::string>{"file"}));
}

}  // namespace
}  // namespace sl
