#include "core/base/output_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <climits>
#include <cstring>
#include <fstream>

#include "core/base/errors.h"

namespace sl {
namespace fs = std::filesystem;

namespace {

// Room left in a temporary's name for a writer's own temporary suffix: core/base/image.cpp writePng
// appends ".part-<pid>" (6 + up to 7 digits of a Linux pid), plus "-<n>" when two shortened
// temporaries would collide.
constexpr size_t kWriterSuffixReserve = 20;
// The longest file name when the file system does not say (POSIX NAME_MAX of ext4, xfs, tmpfs).
constexpr long kDefaultNameMax = 255;

std::string errnoText() { return std::strerror(errno); }

// The longest file name `dir`'s file system allows.
size_t nameMax(const fs::path& dir) {
  errno = 0;
  const long limit = ::pathconf(dir.empty() ? "." : dir.c_str(), _PC_NAME_MAX);
  return size_t(limit > 0 ? limit : kDefaultNameMax);
}

// Absolute, with "." and ".." and symbolic links resolved as far as the path exists (so that
// a link is replaced through, not by, the output); no trailing separator.
fs::path resolve(const std::string& path) {
  std::error_code ec;
  fs::path absolute = fs::absolute(path, ec);
  if (ec) absolute = fs::path(path);
  fs::path resolved = fs::weakly_canonical(absolute, ec);
  if (ec) resolved = absolute.lexically_normal();
  while (!resolved.has_filename() && resolved.has_relative_path())
    resolved = resolved.parent_path();
  return resolved;
}

bool entryExists(const fs::path& p) {
  std::error_code ec;
  return fs::exists(fs::symlink_status(p, ec));
}

// The same file: equal paths, or one file under two names (hard links, bind mounts).
bool sameFile(const fs::path& a, const fs::path& b) {
  if (a == b) return true;
  std::error_code ec;
  return fs::equivalent(a, b, ec) && !ec;
}

// `path` is `dir` or lies under it.
bool within(const fs::path& path, const fs::path& dir) {
  const fs::path relative = path.lexically_relative(dir);
  return !relative.empty() && *relative.begin() != "..";
}

// Every component of `path` from `from` (included) on fits the file system's name limit.
void checkNameLengths(const fs::path& from, const fs::path& path, const fs::path& existingDir,
                      const std::string& where) {
  const size_t limit = nameMax(existingDir);
  fs::path relative = path.lexically_relative(from.parent_path());
  for (const fs::path& component : relative)
    if (component.string().size() > limit)
      throw InputError(where + ": the name '" + component.string().substr(0, 32) + "...' is " +
                       std::to_string(component.string().size()) +
                       " bytes long, longer than this file system's limit of " +
                       std::to_string(limit));
  if (path.string().size() >= size_t(PATH_MAX))
    throw InputError(where + ": the path is " + std::to_string(path.string().size()) +
                     " bytes long, at or over the limit of " + std::to_string(PATH_MAX));
}

// Creates and removes a file (or a directory) named `temp`: proof that the destination's
// directory takes new entries (a writable mode bit says nothing on /proc or a read-only mount).
// A leftover of a dead run with this process's id is removed first.
void probeTemporary(const fs::path& temp, bool directory, const std::string& where) {
  std::error_code ec;
  if (entryExists(temp)) fs::remove_all(temp, ec);
  if (directory) {
    if (::mkdir(temp.c_str(), 0755) != 0)
      throw InputError(where + ": cannot create a directory in " + temp.parent_path().string() +
                       ": " + errnoText());
    ::rmdir(temp.c_str());
    return;
  }
  const int fd = ::open(temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0)
    throw InputError(where + ": cannot create a file in " + temp.parent_path().string() + ": " +
                     errnoText());
  ::close(fd);
  ::unlink(temp.c_str());
}

}  // namespace

fs::path temporaryName(const fs::path& path, const char* kind) {
  const fs::path dir = path.parent_path();
  const std::string name = path.filename().string();
  std::string suffix = ".";
  suffix.append(kind).append("-").append(std::to_string(::getpid()));
  const size_t limit = nameMax(dir);
  const size_t used = 1 + suffix.size() + kWriterSuffixReserve;
  const size_t room = limit > used ? limit - used : 1;
  std::string temporary = ".";
  temporary.append(name, 0, std::min(name.size(), room)).append(suffix);
  return dir / temporary;
}

OutputSet::~OutputSet() {
  if (committed_) return;
  std::error_code ec;
  for (const Destination& d : destinations_) {
    if (d.directory)
      fs::remove_all(d.temporaryTop, ec);
    else
      fs::remove(d.temporary, ec);
  }
}

void OutputSet::addInput(const std::string& path) {
  if (path.empty() || !entryExists(path)) return;
  inputs_.push_back(resolve(path));
}

void OutputSet::checkAgainstOthers(const Destination& d) const {
  const std::string where = d.option + " " + d.path;
  for (const fs::path& input : inputs_) {
    if (sameFile(d.target, input))
      throw InputError(where + ": it is an input of this run (" + input.string() +
                       "): refusing to replace it");
    if (d.directory && within(input, d.target))
      throw InputError(where + ": it holds an input of this run (" + input.string() + ")");
  }
  for (const Destination& other : destinations_) {
    const std::string otherName = other.option + " " + other.path;
    if (sameFile(d.target, other.target))
      throw InputError(where + ": the same file as " + otherName);
    if (other.directory && within(d.target, other.target))
      throw InputError(where + ": it lies inside " + otherName);
    if (d.directory && within(other.target, d.target))
      throw InputError(where + ": it holds " + otherName);
  }
}

std::string OutputSet::addFile(const std::string& option, const std::string& path) {
  const std::string where = option + " " + path;
  if (path.empty()) throw InputError(option + ": empty file name");
  if (path.back() == '/') throw InputError(where + ": names a directory, not a file");
  Destination d;
  d.option = option;
  d.path = path;
  d.target = resolve(path);
  const fs::path dir = d.target.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError(where + ": directory " + dir.string() + " does not exist");
  checkNameLengths(d.target, d.target, dir, where);
  const fs::file_status status = fs::status(d.target, ec);
  if (fs::exists(status)) {
    if (fs::is_directory(status)) throw InputError(where + ": it is a directory");
    if (!fs::is_regular_file(status))
      throw InputError(where + ": it exists and is not a regular file (a device or a pipe)");
    if (::access(d.target.c_str(), W_OK) != 0)
      throw InputError(where + ": it exists and is read-only");
  }
  if (::access(dir.c_str(), W_OK) != 0)
    throw InputError(where + ": directory " + dir.string() + " is not writable");
  checkAgainstOthers(d);
  d.temporary = temporaryName(d.target);
  for (const Destination& other : destinations_)  // two shortened long names may meet
    if (other.temporary == d.temporary || other.temporaryTop == d.temporary)
      d.temporary += std::string("-").append(std::to_string(destinations_.size()));
  probeTemporary(d.temporary, false, where);
  destinations_.push_back(d);
  return d.temporary.string();
}

std::string OutputSet::addDirectory(const std::string& option, const std::string& path) {
  const std::string where = option + " " + path;
  if (path.empty()) throw InputError(option + ": empty directory name");
  Destination d;
  d.option = option;
  d.path = path;
  d.directory = true;
  d.target = resolve(path);
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  if (!d.target.has_relative_path() || (!ec && within(cwd, d.target)))
    throw InputError(where + ": refusing to replace the root or the current directory");
  const fs::file_status status = fs::status(d.target, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) throw InputError(where + ": it exists and is not a directory");
    // Only an empty directory or a previous dump (*.png, passes.json, index.html) is replaced.
    for (const fs::directory_entry& entry : fs::directory_iterator(d.target, ec)) {
      const fs::path name = entry.path().filename();
      const bool dumpFile =
          entry.is_regular_file(ec) && !entry.is_symlink(ec) &&
          (name.extension() == ".png" || name == kDumpIndexFiles[0] || name == kDumpIndexFiles[1]);
      if (!dumpFile)
        throw InputError(where + ": the directory holds " + name.string() +
                         ", not only a previous dump's files (*.png, passes.json, index.html); "
                         "give an empty or a new directory (its content is replaced)");
    }
    if (ec) throw InputError(where + ": cannot read the directory: " + ec.message());
    d.top = d.target;
  } else {
    // The first missing component: it and everything below it are made at commit.
    d.top = d.target;
    while (d.top.has_relative_path() && !entryExists(d.top.parent_path()))
      d.top = d.top.parent_path();
  }
  const fs::path parent = d.top.parent_path();
  if (!fs::is_directory(parent, ec))
    throw InputError(where + ": " + parent.string() + " is not a directory");
  checkNameLengths(d.top, d.target, parent, where);
  if (::access(parent.c_str(), W_OK) != 0)
    throw InputError(where + ": directory " + parent.string() + " is not writable");
  checkAgainstOthers(d);
  d.temporaryTop = temporaryName(d.top);
  for (const Destination& other : destinations_)
    if (other.temporary == d.temporaryTop || other.temporaryTop == d.temporaryTop)
      d.temporaryTop += std::string("-").append(std::to_string(destinations_.size()));
  d.temporary = d.temporaryTop / d.target.lexically_relative(d.top);
  probeTemporary(d.temporaryTop, true, where);
  destinations_.push_back(d);
  return d.temporary.lexically_normal().string();
}

void OutputSet::beginWriting() {
  for (const Destination& d : destinations_) {
    if (!d.directory) continue;
    std::error_code ec;
    fs::create_directories(d.temporary, ec);
    if (ec)
      throw InputError(d.option + " " + d.path + ": cannot create a directory: " + ec.message());
  }
}

void OutputSet::rollBack() {
  for (auto d = destinations_.rbegin(); d != destinations_.rend(); ++d) {
    if (!d->committed) continue;
    if (d->directory) {
      ::rename(d->top.c_str(), d->temporaryTop.c_str());  // the destructor removes it
      if (!d->backup.empty()) ::rename(d->backup.c_str(), d->top.c_str());
    } else if (!d->backup.empty()) {
      ::rename(d->backup.c_str(), d->target.c_str());  // atomic: the old file is back
    } else {
      ::unlink(d->target.c_str());  // it did not exist before
    }
    d->committed = false;
    d->backup.clear();
  }
}

void OutputSet::commit() {
  for (Destination& d : destinations_) {
    const std::string where = d.option + " " + d.path;
    if (d.directory) {
      if (entryExists(d.top)) {
        const fs::path backup = temporaryName(d.top, "old");
        std::error_code ec;
        fs::remove_all(backup, ec);
        if (::rename(d.top.c_str(), backup.c_str()) != 0) {
          const std::string why = errnoText();
          rollBack();
          throw InputError(where + ": cannot move the previous directory aside: " + why);
        }
        d.backup = backup;
      }
      if (::rename(d.temporaryTop.c_str(), d.top.c_str()) != 0) {
        const std::string why = errnoText();
        if (!d.backup.empty()) ::rename(d.backup.c_str(), d.top.c_str());
        d.backup.clear();
        rollBack();
        throw InputError(where + ": cannot rename the directory into place: " + why);
      }
    } else {
      if (entryExists(d.target)) {
        // A second name for the existing file, so that a later failure can put it back.
        const fs::path backup = temporaryName(d.target, "old");
        ::unlink(backup.c_str());
        if (::link(d.target.c_str(), backup.c_str()) == 0) d.backup = backup;
      }
      if (::rename(d.temporary.c_str(), d.target.c_str()) != 0) {
        const std::string why = errnoText();
        if (!d.backup.empty()) ::unlink(d.backup.c_str());
        d.backup.clear();
        rollBack();
        throw InputError(where + ": cannot rename the file into place: " + why);
      }
    }
    d.committed = true;
  }
  committed_ = true;
  std::error_code ec;
  for (Destination& d : destinations_)
    if (!d.backup.empty()) fs::remove_all(d.backup, ec);
}

void checkDirectoryCreatable(const std::string& option, const std::string& path) {
  const std::string where = option + " " + path;
  if (path.empty()) throw InputError(option + ": empty directory name");
  const fs::path target = resolve(path);
  std::error_code ec;
  const fs::file_status status = fs::status(target, ec);
  if (fs::exists(status)) {
    if (!fs::is_directory(status)) throw InputError(where + ": it exists and is not a directory");
    if (::access(target.c_str(), W_OK) != 0)
      throw InputError(where + ": the directory is not writable");
    return;
  }
  fs::path top = target;
  while (top.has_relative_path() && !entryExists(top.parent_path())) top = top.parent_path();
  const fs::path parent = top.parent_path();
  if (!fs::is_directory(parent, ec))
    throw InputError(where + ": " + parent.string() + " is not a directory");
  checkNameLengths(top, target, parent, where);
  if (::access(parent.c_str(), W_OK) != 0)
    throw InputError(where + ": cannot create it: directory " + parent.string() +
                     " is not writable");
  probeTemporary(temporaryName(top), true, where);
}

void writeFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const fs::path temp = temporaryName(fs::path(path));
  std::error_code ec;
  {
    std::ofstream out(temp, std::ios::binary | std::ios::trunc);
    if (!out) throw InputError("cannot write " + path + ": " + errnoText());
    try {
      write(out);
      out.close();
    } catch (...) {
      out.close();
      fs::remove(temp, ec);
      throw;
    }
    if (!out) {
      fs::remove(temp, ec);
      throw InputError("cannot write " + path + ": the write failed (disk full?)");
    }
  }
  if (::rename(temp.c_str(), path.c_str()) != 0) {
    const std::string why = errnoText();
    fs::remove(temp, ec);
    throw InputError("cannot write " + path + ": " + why);
  }
}

}  // namespace sl
