// figures/overrides.cpp — `figures --only ID --set key=value` (see overrides.h).
#include "figures/overrides.h"

#include <algorithm>
#include <set>
#include <sstream>

#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"

namespace sl::figures {
namespace {

constexpr int kLargestShadowMap = 1 << 16;  // the GL's own limit is checked with a context
constexpr int kLargestFilter = 16;          // as `render --filter`

const Technique* lookup(const std::string& name) {
  for (const Technique& t : allTechniques())
    if (t.name == name) return &t;
  return nullptr;
}

bool hasParam(const Technique& t, const std::string& key) {
  const std::vector<std::string> keys = sl::paramKeys(t);
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

bool rendersTechnique(const PanelSpec& p) {
  return p.kind == PanelKind::kRender || p.kind == PanelKind::kIntermediates;
}

// Panels a scene or window override concerns: everything that renders the scene.
bool rendersScene(const PanelSpec& p) { return p.kind != PanelKind::kPlot; }

std::string join(const std::set<std::string>& values) {
  std::string out;
  for (const std::string& v : values) out += (out.empty() ? "" : ", ") + v;
  return out.empty() ? "none" : out;
}

std::string number(double v) {
  std::ostringstream s;
  s << v;
  return s.str();
}

std::string slugOf(const std::string& text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.')
      out += char(std::tolower(static_cast<unsigned char>(c)));
    else if (!out.empty() && out.back() != '-')
      out += '-';
  }
  while (!out.empty() && out.back() == '-') out.pop_back();
  return out;
}

}  // namespace

const std::vector<std::string>& overrideKeys() {
  static const std::vector<std::string> keys = {"size",          "shadow-map",      "filter",
                                                "precision",     "camera-distance", "light-radius",
                                                "light-position"};
  return keys;
}

std::string FigureOverrides::describe() const {
  std::string out;
  for (const auto& [k, v] : given) out += (out.empty() ? "" : ", ") + k + "=" + v;
  return out;
}

std::string FigureOverrides::slug() const {
  std::string out;
  for (const auto& [k, v] : given) out += (out.empty() ? "" : "--") + slugOf(k + "-" + v);
  return out;
}

FigureOverrides parseOverrideList(const std::vector<std::string>& sets) {
  FigureOverrides o;
  std::set<std::string> seen;
  for (const std::string& kv : sets) {
    const auto eq = kv.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == kv.size())
      throw InputError("--set must look like key=value, got '" + kv + "'");
    const std::string key = kv.substr(0, eq), value = kv.substr(eq + 1);
    if (!seen.insert(key).second) throw InputError("--set " + key + " is given twice");
    const std::string what = "--set " + key;
    if (key == "size") {
      int w = 0, h = 0;
      try {
        cli::parseSize(value, w, h);
      } catch (const InputError& e) {
        throw InputError("--set size: " + std::string(e.what()));
      }
      o.width = w;
      o.height = h;
    } else if (key == "shadow-map") {
      o.shadowMapTexels = cli::parsePositiveInt(what, value, kLargestShadowMap);
    } else if (key == "filter") {
      o.filter = cli::parsePositiveInt(what, value, kLargestFilter);
    } else if (key == "precision") {
      try {
        o.precision = parsePrecision(value);
      } catch (const InputError&) {
        throw InputError(what + " must be 8, 12 or float, got '" + value + "'");
      }
    } else if (key == "camera-distance" || key == "light-radius" || key == "light-position") {
      cli::Args args;  // the render options' own parsing and ranges (registry/cli.h)
      args.options[key] = {value};
      try {
        const SceneAdjustments a = cli::sceneAdjustments(args);
        if (a.cameraDistance) o.scene.cameraDistance = a.cameraDistance;
        if (a.lightRadius) o.scene.lightRadius = a.lightRadius;
        if (a.lightPosition) o.scene.lightPosition = a.lightPosition;
      } catch (const InputError& e) {
        std::string why = e.what();
        if (why.rfind("--", 0) == 0) why = why.substr(2);
        throw InputError("--set " + why);
      }
    } else if (std::all_of(key.begin(), key.end(), [](char c) {
                 return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_';
               })) {
      o.params[key] = value;  // checked against the figure's techniques in applyOverrides
    } else {
      throw InputError("--set key '" + key + "' is not a key (letters, digits, - and _)");
    }
    o.given.push_back({key, value});
  }
  return o;
}

FigureOverrides parseOverrides(const cli::Args& args) {
  const auto it = args.options.find("set");
  if (it == args.options.end() || it->second.empty()) return {};
  const auto only = args.options.find("only");
  if (only == args.options.end() || only->second.size() != 1)
    throw InputError(
        "--set needs exactly one --only ID: one figure is re-made with parameters "
        "changed");
  return parseOverrideList(it->second);
}

FigureSpec applyOverrides(const FigureSpec& figure, const FigureOverrides& o) {
  if (o.empty()) return figure;
  FigureSpec f = figure;
  // What the listed figure had, per key, for the caption ("shadow-map=1024 (listed: 512)").
  std::map<std::string, std::set<std::string>> listed;
  std::map<std::string, int> concerned;  // key -> panels it changes
  std::set<std::string> paramKeys;       // every --param key of the figure's techniques
  for (const PanelSpec& p : f.panels)
    if (rendersTechnique(p))
      if (const Technique* t = lookup(p.technique))
        for (const std::string& k : sl::paramKeys(*t)) paramKeys.insert(k);

  if (o.width) {
    listed["size"].insert(std::to_string(f.width) + "x" + std::to_string(f.height));
    f.width = *o.width;
    f.height = *o.height;
  }
  if (o.shadowMapTexels) {
    listed["shadow-map"].insert(std::to_string(f.shadowMapTexels));
    f.shadowMapTexels = *o.shadowMapTexels;
  }
  for (PanelSpec& p : f.panels) {
    if (!rendersScene(p)) continue;
    // The keys this panel changes: those whose count of concerned panels it raises.
    const std::map<std::string, int> before = concerned;
    const Technique* t = rendersTechnique(p) ? lookup(p.technique) : nullptr;
    if (o.width) {
      if (p.width) listed["size"].insert(std::to_string(p.width) + "x" + std::to_string(p.height));
      p.width = p.height = 0;  // the figure's, now the override
      ++concerned["size"];
    }
    if (o.shadowMapTexels && (t == nullptr || readsOption(*t, CommonOption::kShadowMap))) {
      if (p.shadowMapTexels) listed["shadow-map"].insert(std::to_string(p.shadowMapTexels));
      p.shadowMapTexels = 0;
      ++concerned["shadow-map"];
    }
    if (o.filter && t && readsOption(*t, CommonOption::kFilter)) {
      listed["filter"].insert(std::to_string(p.filter ? p.filter : RenderParams{}.filter));
      p.filter = *o.filter;
      ++concerned["filter"];
    }
    if (o.precision && t && readsOption(*t, CommonOption::kPrecision)) {
      listed["precision"].insert(precisionName(p.precision.value_or(RenderParams{}.precision)));
      p.precision = o.precision;
      ++concerned["precision"];
    }
    if (o.scene.cameraDistance) {
      listed["camera-distance"].insert(number(p.cameraDistance));
      p.cameraDistance = *o.scene.cameraDistance;
      ++concerned["camera-distance"];
    }
    if (o.scene.lightRadius) {
      listed["light-radius"].insert(p.lightRadius ? number(*p.lightRadius) : "the scene's");
      p.lightRadius = o.scene.lightRadius;
      // Only the soft-shadow reference reads it (as the panel or as the figure's reference).
      if ((t && t->name == "reference.soft") || f.reference == "reference.soft")
        ++concerned["light-radius"];
    }
    if (o.scene.lightPosition) {
      listed["light-position"].insert("the scene's");
      p.lightPosition = o.scene.lightPosition;
      ++concerned["light-position"];
    }
    for (const auto& [key, value] : o.params) {
      if (!t || !hasParam(*t, key)) continue;
      const auto had = p.params.find(key);
      listed[key].insert(had == p.params.end() ? "default" : had->second);
      p.params[key] = value;
      ++concerned[key];
    }
    for (const auto& [key, value] : o.given) {
      const auto had = before.find(key);
      if (concerned[key] > (had == before.end() ? 0 : had->second))
        p.overridden.push_back(key + "=" + value);
    }
  }
  // A key that changes nothing in this figure is an input error (as `render` refuses options
  // its technique ignores).
  for (const auto& [key, value] : o.given) {
    if (concerned[key] > 0) continue;
    const bool known =
        std::find(overrideKeys().begin(), overrideKeys().end(), key) != overrideKeys().end();
    if (known)
      throw InputError("--set " + key + " has no effect on " + figure.id +
                       " (no panel of it reads " + key + ")");
    throw InputError("--set " + key + ": no technique of " + figure.id +
                     " has that --param key (keys: " + join(paramKeys) +
                     "; or one of size, shadow-map, filter, precision, camera-distance, "
                     "light-radius, light-position)");
  }
  // The values the techniques would refuse (a map above GL_MAX_TEXTURE_SIZE, an order a
  // technique does not support): render's own checks, once per distinct render.
  std::set<std::string> checked;
  for (const PanelSpec& p : f.panels) {
    if (!rendersTechnique(p)) continue;
    const Technique* t = lookup(p.technique);
    if (t == nullptr) continue;
    RenderParams params;
    params.width = p.width ? p.width : f.width;
    params.height = p.height ? p.height : f.height;
    params.shadowMapTexels = p.shadowMapTexels ? p.shadowMapTexels : f.shadowMapTexels;
    params.filter = p.filter ? p.filter : RenderParams{}.filter;
    if (p.precision) params.precision = *p.precision;
    params.extra = p.params;
    std::ostringstream key;
    key << t->name << "|" << params.width << "x" << params.height << "|" << params.shadowMapTexels
        << "|" << params.filter << "|" << precisionName(params.precision);
    for (const auto& [k, v] : params.extra) key << "|" << k << "=" << v;
    if (!checked.insert(key.str()).second) continue;
    bool paramsKnown = true;  // a panel listed with a parameter its technique lacks is shown
    for (const auto& [k, v] : params.extra)  // as missing by figures.cpp, not refused here
      paramsKnown = paramsKnown && hasParam(*t, k);
    if (!paramsKnown) continue;
    try {
      checkRenderable(*t, params);
    } catch (const InputError& e) {
      throw InputError("--set " + o.describe() + ": " + p.technique + " refuses it: " + e.what());
    }
  }
  // The scene knobs: the adjusted scene must still be usable (light not on its target).
  for (const PanelSpec& p : f.panels)
    if (rendersScene(p) && !o.scene.empty()) {
      Scene scene = loadScene(p.scene.empty() ? f.scene : p.scene);
      try {
        adjustScene(scene, o.scene);
      } catch (const InputError& e) {
        throw InputError("--set " + o.describe() + ": " + e.what());
      }
    }

  f.sourceId = figure.id;
  for (const auto& [k, v] : o.given) f.overrides.push_back(k + "=" + v);
  f.fileSuffix = "--" + o.slug();
  f.id = figure.id + f.fileSuffix;
  std::string changed;
  for (const auto& [key, value] : o.given)
    changed += (changed.empty() ? "" : "; ") + key + "=" + value + " in " +
               std::to_string(concerned[key]) + " panel" + (concerned[key] == 1 ? "" : "s") +
               " (listed: " + join(listed[key]) + ")";
  f.caption += " Re-made with --set " + o.describe() + ": " + changed +
               ". The rest of this caption and the panel labels describe the listed figure; "
               "the overrides apply to the panels counted here.";
  return f;
}

}  // namespace sl::figures
