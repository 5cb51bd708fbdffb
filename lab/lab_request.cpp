// lab/lab_request.cpp — the lab's queries parsed as `shadowlab render`'s command line
// (lab/lab_request.h).
#include "lab/lab_request.h"

#include <algorithm>

#include "core/base/decimal.h"
#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "lab/lab_server.h"
#include "registry/registry.h"

namespace sl::lab {
namespace {

constexpr int kMaxQueryValueBytes = 1024;  // one query value
constexpr int kMaxQueryKeys = 64;          // keys of one query
constexpr size_t kMaxLaneName = 16;

// The query's key=value pairs in the order given, each decoded by httplib. (httplib's own
// Request::params sorts the keys, which would change which error the CLI's parser meets
// first, keeps only the text after the last '=' of a value, "param=pixel=area" -> "area",
// and drops repeated pairs.)
std::vector<std::pair<std::string, std::string>> queryPairs(const httplib::Request& req) {
  std::vector<std::pair<std::string, std::string>> pairs;
  const size_t question = req.target.find('?');
  if (question == std::string::npos) return pairs;
  const std::string query = req.target.substr(question + 1);
  httplib::detail::split(
      query.data(), query.data() + query.size(), '&', [&](const char* b, const char* e) {
        const std::string item(b, e);
        if (item.empty()) return;  // "a=1&&b=2"
        const size_t eq = item.find('=');
        pairs.emplace_back(httplib::detail::decode_url(item.substr(0, eq), true),
                           eq == std::string::npos
                               ? std::string()
                               : httplib::detail::decode_url(item.substr(eq + 1), true));
      });
  return pairs;
}

}  // namespace

std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  return text;
}

std::vector<std::string> servedSceneNames() {
  std::vector<std::string> names = builtinSceneNames();
  for (const std::string& s : sceneFileNames()) names.push_back(s);
  return names;
}

LabRequest parseRequest(const httplib::Request& req, const std::vector<std::string>& views) {
  LabRequest r;
  r.view = views.front();
  const auto pairs = queryPairs(req);
  if (pairs.size() > size_t(kMaxQueryKeys))
    throw InputError("too many query keys (at most " + std::to_string(kMaxQueryKeys) + ")");
  std::vector<std::string> argv = {"shadowlab", "render"};
  std::vector<std::string> commandLine = {"shadowlab", "render"};
  for (const auto& [key, value] : pairs) {
    if (value.size() > size_t(kMaxQueryValueBytes))
      throw InputError("the value of " + key.substr(0, 32) + " is longer than " +
                       std::to_string(kMaxQueryValueBytes) + " bytes");
    for (char c : key + value)
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
        throw InputError("query keys and values must be printable text");
    if (key == "view") {
      if (std::find(views.begin(), views.end(), value) == views.end()) {
        std::string list;
        for (const auto& v : views) list += (list.empty() ? "" : ", ") + v;
        throw InputError("view must be one of " + list + ", got '" + value + "'");
      }
      r.view = value;
      continue;
    }
    if (key == "lane") {
      const bool ok = !value.empty() && value.size() <= kMaxLaneName &&
                      std::all_of(value.begin(), value.end(), [](char c) {
                        return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-';
                      });
      if (!ok) throw InputError("lane must be 1-16 of a-z, 0-9 and -, got '" + value + "'");
      r.lane = value;
      continue;
    }
    if (key == "out" || key == "mask" || key == "dump-passes")
      throw InputError("the lab writes no files: --" + key + " is not served");
    if (key == "backend")
      throw InputError("the lab renders on its own back end (osmesa): --backend is not served");
    // As the command line spells it: the option and its value as two arguments.
    argv.push_back("--" + key);
    argv.push_back(value);
    commandLine.push_back("--" + key);
    commandLine.push_back(value);
  }
  std::vector<char*> pointers;
  for (std::string& a : argv) pointers.push_back(a.data());
  try {
    r.args = cli::parse(int(pointers.size()), pointers.data());
  } catch (const cli::HelpRequested&) {
    throw InputError("--help is not served (GET /api/techniques lists the options)");
  }
  // A value spelled as an option ("scene=--out=x") is parsed as one, as on the command line:
  // the options that name files or back ends are refused whichever way they came in.
  for (const char* key : {"out", "mask", "dump-passes"})
    if (r.args.has(key))
      throw InputError(std::string("the lab writes no files: --") + key + " is not served");
  if (r.args.has("backend"))
    throw InputError("the lab renders on its own back end (osmesa): --backend is not served");
  r.sceneName = r.args.value("scene").value_or(kDefaultScene);
  const std::vector<std::string> scenes = servedSceneNames();
  if (std::find(scenes.begin(), scenes.end(), r.sceneName) == scenes.end()) {
    std::string known;
    for (const auto& n : scenes) known += (known.empty() ? "" : ", ") + n;
    throw InputError("unknown scene '" + r.sceneName + "' (known: " + known + ")");
  }
  r.technique = &findTechnique(r.args.required("technique"));
  r.params = cli::renderParams(r.args);
  r.params.readLog = std::make_shared<ParamReadLog>();
  rejectIgnoredOptions(*r.technique, cli::givenCommonOptions(r.args));
  if (r.params.width > kMaxServedWidth || r.params.height > kMaxServedHeight)
    throw InputError("the lab serves --size up to " + std::to_string(kMaxServedWidth) + "x" +
                     std::to_string(kMaxServedHeight) + " (shadowlab render makes larger frames)");
  if (r.params.shadowMapTexels > kMaxServedShadowMap)
    throw InputError("the lab serves --shadow-map up to " + std::to_string(kMaxServedShadowMap) +
                     " (shadowlab render makes larger maps)");
  if (r.params.filter > kMaxServedFilter)
    throw InputError("the lab serves --filter up to " + std::to_string(kMaxServedFilter) +
                     " (shadowlab render filters wider)");
  // The ray-traced references' work per pixel: at most their declared defaults (288 shadow rays,
  // 8x8 sub-pixel samples), so that one request cannot hold the single worker for minutes.
  for (const char* key : {"rays", "pixel-samples"}) {
    const ParamSpec* spec = findParam(*r.technique, key);
    const auto given = r.params.extra.find(key);
    if (!spec || given == r.params.extra.end()) continue;
    const std::optional<double> v = parseDecimal(given->second);
    if (v && *v > spec->fallback)
      throw InputError("the lab serves --param " + std::string(key) + " up to " +
                       spec->defaultText() + " (shadowlab render traces more)");
  }
  // The outputs of the reproducing command: the image, and the mask or the pass dump that
  // the view shows (the error views compare the mask).
  commandLine.push_back("--out");
  commandLine.push_back("image.png");
  if (r.view == "passes") {
    commandLine.push_back("--dump-passes");
    commandLine.push_back("passes");
  } else if (r.view != "image") {
    commandLine.push_back("--mask");
    commandLine.push_back("mask.png");
  }
  r.command = shellJoin(commandLine);
  r.parameters = nlohmann::json::object();
  for (const auto& [key, values] : r.args.options) r.parameters[key] = values;
  return r;
}

}  // namespace sl::lab
