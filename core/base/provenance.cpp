#include "core/base/provenance.h"

#include <string_view>

#include "build_commit.h"  // generated: SHADOWLAB_BUILD_COMMIT (core/build_commit.cmake)

namespace sl {
namespace {
std::string& storedCommandLine() {
  static std::string line;
  return line;
}

bool isSafeShellCharacter(unsigned char c) {
  return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
         std::string_view("_@%+=:,./-").find(char(c)) != std::string_view::npos;
}

bool isPrintableAscii(unsigned char c) {
  constexpr unsigned char kFirstPrintable = 0x20, kLastPrintable = 0x7e;
  return c >= kFirstPrintable && c <= kLastPrintable;
}
}  // namespace

const std::string& buildCommit() {
  static const std::string kCommit = SHADOWLAB_BUILD_COMMIT;
  return kCommit;
}

std::string softwareName() { return "shadowlab " + buildCommit(); }

std::string shellQuote(const std::string& argument) {
  bool safe = !argument.empty(), printable = true;
  for (unsigned char c : argument) {
    safe = safe && isSafeShellCharacter(c);
    printable = printable && isPrintableAscii(c);
  }
  if (safe) return argument;
  std::string out;
  if (printable) {  // '...' keeps everything but ' itself, which closes, escapes and reopens
    out = "'";
    for (char c : argument) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
    return out + "'";
  }
  out = "$'";
  constexpr char kHex[] = "0123456789abcdef";
  for (unsigned char c : argument) {
    if (c == '\'' || c == '\\') {
      out += '\\';
      out += char(c);
    } else if (isPrintableAscii(c)) {
      out += char(c);
    } else {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 0xf];
    }
  }
  return out + "'";
}

std::string shellJoin(const std::vector<std::string>& arguments) {
  std::string line;
  for (const std::string& a : arguments) {
    if (!line.empty()) line += ' ';
    line += shellQuote(a);
  }
  return line;
}

void recordCommandLine(int argc, const char* const* argv) {
  std::vector<std::string> arguments;
  for (int i = 0; i < argc; ++i) arguments.emplace_back(argv[i]);
  storedCommandLine() = shellJoin(arguments);
}

void recordCommand(std::string command) { storedCommandLine() = std::move(command); }

const std::string& commandLine() { return storedCommandLine(); }

}  // namespace sl
