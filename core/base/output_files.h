// core/base/output_files.h — a run writes all its outputs or none.
//
// A command names every destination to one OutputSet before it renders anything:
//
//   OutputSet outputs;
//   outputs.addInput(sceneFile);                              // no output may replace it
//   const std::string png = outputs.addFile("--out", outPath);  // where to write it for now
//   const std::string dump = outputs.addDirectory("--dump-passes", dumpDir);
//   ... render ...
//   outputs.beginWriting();                                   // creates the temporary folders
//   writePng(png, image); ...                                 // write into the temporaries
//   outputs.commit();                                         // rename every one into place
//
// addFile and addDirectory check their destination at once and throw InputError (exit 2)
// naming it: the folder must exist (a directory's missing parents are made at commit) and be
// writable, the name must fit the file system, the temporary name must be creatable, the
// destination must not be an existing directory (a file) or non-directory (a directory), not
// an input, not another destination, and not inside a destination directory.
//
// Temporaries live beside their destination: `<dir>/.<name>.tmp-<pid>` (same file system, so
// the final rename is atomic). Until commit() no destination is touched; the destructor removes
// every temporary when commit() was not reached, so a run that fails (an exception) leaves no
// file behind and replaces none. commit() renames the temporaries in the order they were
// added; should one rename fail, the ones already made are undone (an existing file is kept
// through a hard link while its replacement is renamed in) and commit() throws InputError.
//
// A destination directory that already exists is replaced as a whole on success, but only
// when it is empty or holds nothing but a previous dump: regular *.png files, passes.json and
// index.html (what --dump-passes writes, teach/pass_dump.h). Any other content (another file, a
// sub-directory, a link) is refused with exit 2, so that a mistyped directory name never deletes
// a user's files.
#pragma once

#include <filesystem>
#include <functional>
#include <iosfwd>
#include <string>
#include <vector>

namespace sl {

// The files of a --dump-passes directory besides its *.png (teach/pass_dump.h): a directory
// holding only these and PNGs is a previous dump, which addDirectory may replace.
inline constexpr const char* kDumpIndexFiles[2] = {"passes.json", "index.html"};

class OutputSet {
 public:
  OutputSet() = default;
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;
  ~OutputSet();

  // A file the command reads: no destination may be this file (compared after resolving
  // links, and by identity when both exist). A path that does not exist is ignored.
  void addInput(const std::string& path);
  // Checks a file destination (see the head of this file) and returns the temporary path to
  // write it to. `option` names it in messages ("--out").
  std::string addFile(const std::string& option, const std::string& path);
  // Checks a directory destination and returns the temporary directory to fill (made by
  // beginWriting()).
  std::string addDirectory(const std::string& option, const std::string& path);
  // Makes the temporary directories (empty). Call after rendering, before writing.
  void beginWriting();
  // Renames every temporary into place (see the head of this file).
  void commit();

 private:
  struct Destination {
    std::string option;            // "--out"
    std::string path;              // as the user gave it, for messages
    std::filesystem::path target;  // the destination, links resolved
    bool directory = false;
    // Directories: the first component of `target` that does not exist yet, or `target`
    // itself; the temporary stands in for it, `temporary` / (target relative to it) is filled.
    std::filesystem::path top;
    std::filesystem::path temporaryTop;
    std::filesystem::path temporary;  // files: the temporary file; directories: what to fill
    std::filesystem::path backup;     // the previous destination during commit(), or empty
    bool committed = false;
  };
  void checkAgainstOthers(const Destination& d) const;
  void rollBack();

  std::vector<std::filesystem::path> inputs_;
  std::vector<Destination> destinations_;
  bool committed_ = false;
};

// Checks before a long run that `path` is a directory that can be written, or can be made
// (its nearest existing ancestor is a writable directory). Throws InputError naming `option`.
void checkDirectoryCreatable(const std::string& option, const std::string& path);

// Writes a file through a temporary beside it and a rename: a reader, or a run that fails,
// never finds a half-written file under `path`. `write` fills the stream; a stream error, or
// an exception from `write`, removes the temporary. Throws InputError naming `path`.
void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// The temporary name of `name` in the same directory: ".<name>.tmp-<pid>", the name shortened
// when needed so that it and a writer's own suffix (core/base/image.cpp writePng's ".part-<pid>")
// stay within the file system's name limit.
std::filesystem::path temporaryName(const std::filesystem::path& path, const char* kind = "tmp");

}  // namespace sl
