// core/base/provenance.h — what made an output: the commit of the source tree the binary was built
// from, the command line of the run, and the effective parameters. The JSON
// lines of `render`/`compare`, the tEXt chunks of every PNG (core/base/image.h writePng) and
// report.html carry them.
#pragma once

#include <string>
#include <vector>

namespace sl {

// The source tree this binary was built from: `git rev-parse --short HEAD`, with "-dirty" when
// `git status --porcelain` listed changes at build time; "unknown" when git or the repository
// was absent. Refreshed by every build (core/build_commit.cmake), not only at configure time.
const std::string& buildCommit();

// "shadowlab <commit>": the PNG "Software" text.
std::string softwareName();

// One argument as a POSIX shell reads it back: unchanged when it holds only safe characters,
// in single quotes otherwise, and as $'...' with \xNN escapes when it holds control or
// non-ASCII bytes (so the result is always printable ASCII).
std::string shellQuote(const std::string& argument);
std::string shellJoin(const std::vector<std::string>& arguments);

// The command line of this process: main() records it once; "" until then.
void recordCommandLine(int argc, const char* const* argv);
const std::string& commandLine();
// What made this process's next outputs when no main() command line did: the Python module
// records each call ("shadowlab.render(scene='brabec', ...)") before it runs.
void recordCommand(std::string command);

// What a PNG says about how it was made (core/base/image.h writePng). Every PNG carries "Software"
// (softwareName()); "shadowlab:command" carries `command`, or commandLine() when `command` is
// empty; "shadowlab:parameters" carries `parameters` when it is not empty.
struct Provenance {
  std::string command;
  std::string parameters;  // the effective parameters, as the text of one JSON object
};

}  // namespace sl
