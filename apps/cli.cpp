#include "apps/cli.h"

#include <cmath>
#include <filesystem>
#include <set>

#include <unistd.h>

#include "core/errors.h"

namespace sl::cli {
namespace fs = std::filesystem;

bool Args::has(const std::string& key) const {
  return options.count(key) != 0 ||
         std::find(flags.begin(), flags.end(), key) != flags.end();
}

std::optional<std::string> Args::value(const std::string& key) const {
  auto it = options.find(key);
  if (it == options.end() || it->second.empty()) return std::nullopt;
  return it->second.back();
}

std::string Args::required(const std::string& key) const {
  auto v = value(key);
  if (!v) throw InputError(command + " needs --" + key);
  return *v;
}

namespace {
const std::map<std::string, std::set<std::string>> kValueOptions = {
    {"list", {}},
    {"render",
     {"scene", "technique", "size", "shadow-map", "filter", "precision", "param", "backend", "out",
      "mask", "dump-passes"}},
    {"compare",
     {"scene", "a", "b", "size", "shadow-map", "filter", "precision", "param", "backend", "diff",
      "threshold"}},
    {"bench", {"scene", "technique", "csv", "size", "backend", "repeat", "out"}},
    {"plan", {"scene", "technique", "size", "shadow-map", "filter", "precision", "param"}},
    {"figures", {"out", "only"}},
};
const std::map<std::string, std::set<std::string>> kFlagOptions = {
    {"list", {}}, {"render", {}}, {"compare", {}}, {"bench", {"quick"}},
    {"plan", {}}, {"figures", {"no-progress"}},
};
}  // namespace

Args parse(int argc, char** argv) {
  Args a;
  if (argc < 2) throw InputError("no command given (try: shadowlab --help)");
  a.command = argv[1];
  auto values = kValueOptions.find(a.command);
  if (values == kValueOptions.end())
    throw InputError("unknown command '" + a.command + "' (try: shadowlab --help)");
  const auto& flags = kFlagOptions.at(a.command);
  for (int i = 2; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg.rfind("--", 0) != 0) throw InputError("unexpected argument '" + arg + "'");
    std::string key = arg.substr(2);
    std::optional<std::string> inlineValue;
    if (auto eq = key.find('='); eq != std::string::npos && values->second.count(key.substr(0, eq))) {
      inlineValue = key.substr(eq + 1);
      key = key.substr(0, eq);
    }
    if (flags.count(key)) {
      a.flags.push_back(key);
      continue;
    }
    if (!values->second.count(key))
      throw InputError("'" + a.command + "' has no option --" + key);
    if (inlineValue) {
      a.options[key].push_back(*inlineValue);
      continue;
    }
    if (i + 1 >= argc) throw InputError("--" + key + " needs a value");
    a.options[key].push_back(argv[++i]);
  }
  return a;
}

int parsePositiveInt(const std::string& what, const std::string& text, int maxValue) {
  size_t used = 0;
  long long v = 0;
  try {
    v = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw InputError(what + " must be a whole number, got '" + text + "'");
  if (v <= 0 || v > maxValue)
    throw InputError(what + " must lie in 1.." + std::to_string(maxValue) + ", got " + text);
  return int(v);
}

void parseSize(const std::string& text, int& width, int& height) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw InputError("--size must look like 800x600, got '" + text + "'");
  constexpr int kMaxWindowSide = 16384;
  width = parsePositiveInt("--size width", text.substr(0, x), kMaxWindowSide);
  height = parsePositiveInt("--size height", text.substr(x + 1), kMaxWindowSide);
}

RenderParams renderParams(const Args& args) {
  RenderParams p;
  if (auto v = args.value("size")) parseSize(*v, p.width, p.height);
  constexpr int kLargestShadowMap = 1 << 16;  // the GL maximum is checked once a context exists
  if (auto v = args.value("shadow-map")) p.shadowMapTexels = parsePositiveInt("--shadow-map", *v, kLargestShadowMap);
  if (auto v = args.value("filter")) p.filter = parsePositiveInt("--filter", *v, 16);
  if (auto v = args.value("precision")) p.precision = parsePrecision(*v);
  if (auto v = args.value("backend")) p.backend = parseBackend(*v);
  if (auto it = args.options.find("param"); it != args.options.end())
    for (const std::string& kv : it->second) {
      const auto eq = kv.find('=');
      if (eq == std::string::npos || eq == 0)
        throw InputError("--param must look like key=value, got '" + kv + "'");
      p.extra[kv.substr(0, eq)] = kv.substr(eq + 1);
    }
  return p;
}

void checkWritable(const std::string& path) {
  fs::path p(path);
  fs::path dir = p.parent_path().empty() ? fs::path(".") : p.parent_path();
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw InputError("cannot write " + path + ": directory " + dir.string() + " does not exist");
  if (::access(dir.c_str(), W_OK) != 0)
    throw InputError("cannot write " + path + ": directory " + dir.string() + " is not writable");
  if (fs::is_directory(p, ec)) throw InputError("cannot write " + path + ": it is a directory");
}

}  // namespace sl::cli
