// measure/sweep.cpp — a sweep spec expanded into rows, each measured as the bench measures a
// variant (measure/sweep.h; the spec's keys: docs/python.md "Sweeps").
#include "measure/sweep.h"

#include <algorithm>
#include <set>

#include "core/base/errors.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"

namespace sl::figures {
namespace {

using Json = nlohmann::json;

// The spec's keys, in the order docs/python.md lists them.
const std::vector<std::string>& specKeys() {
  static const std::vector<std::string> kKeys = {
      "techniques", "scenes",  "sizes",  "shadow_maps", "filters",        "precisions", "params",
      "orbits",     "backend", "warmup", "repeat",      "soft_reference", "temporal"};
  return kKeys;
}

std::string joined(const std::vector<std::string>& items) {
  std::string out;
  for (const std::string& s : items) out += (out.empty() ? "" : ", ") + s;
  return out;
}

// A short form of a value for a message (a long list is cut).
std::string shown(const Json& v) {
  constexpr size_t kShownChars = 60;
  std::string text = v.dump(-1, ' ', false, Json::error_handler_t::replace);
  if (text.size() > kShownChars) text = text.substr(0, kShownChars) + "...";
  return text;
}

// The values of an axis: a list (a single value stands for a list of one). Empty: not given.
std::vector<Json> axisValues(const Json& spec, const std::string& key) {
  if (!spec.contains(key) || spec.at(key).is_null()) return {};
  const Json& v = spec.at(key);
  std::vector<Json> out;
  if (v.is_array()) {
    if (v.empty())
      throw InputError("sweep: \"" + key + "\" is an empty list (leave it out instead)");
    for (const Json& item : v) out.push_back(item);
  } else {
    out.push_back(v);
  }
  return out;
}

// A scalar as the command line spells it: strings as they are, numbers in their shortest form
// that reads back, true/false as on/off (the flags' words, core/technique/technique.h).
std::string optionText(const std::string& what, const Json& v) {
  if (v.is_string()) return v.get<std::string>();
  if (v.is_number_integer()) return std::to_string(v.get<long long>());
  if (v.is_number_float()) return formatNumber(v.get<double>());
  if (v.is_boolean()) return v.get<bool>() ? "on" : "off";
  throw InputError("sweep: " + what + " must be a string or a number, got " + shown(v));
}

std::vector<std::string> stringList(const Json& spec, const std::string& key) {
  std::vector<std::string> out;
  for (const Json& v : axisValues(spec, key)) {
    if (!v.is_string())
      throw InputError("sweep: \"" + key + "\" must hold names (strings), got " + shown(v));
    out.push_back(v.get<std::string>());
  }
  return out;
}

// "WxH" or [W, H], checked as --size is.
std::string sizeText(const Json& v) {
  if (v.is_array() && v.size() == 2 && v[0].is_number_integer() && v[1].is_number_integer())
    return std::to_string(v[0].get<long long>()) + "x" + std::to_string(v[1].get<long long>());
  if (v.is_string()) return v.get<std::string>();
  throw InputError("sweep: \"sizes\" holds \"WxH\" strings or [W, H] pairs, got " + shown(v));
}

// "AZ,EL,DIST" or [AZ, EL, DIST]; null: the scene's own camera.
std::optional<std::string> orbitText(const Json& v) {
  if (v.is_null()) return std::nullopt;
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array() && v.size() == 3 &&
      std::all_of(v.begin(), v.end(), [](const Json& x) { return x.is_number(); }))
    return optionText("an orbit", v[0]) + "," + optionText("an orbit", v[1]) + "," +
           optionText("an orbit", v[2]);
  throw InputError(
      "sweep: \"orbits\" holds null, \"AZ,EL,DIST\" strings or [AZ, EL, DIST] lists, got " +
      shown(v));
}

bool flagValue(const Json& spec, const std::string& key, bool fallback) {
  if (!spec.contains(key)) return fallback;
  if (!spec.at(key).is_boolean())
    throw InputError("sweep: \"" + key + "\" must be true or false, got " + shown(spec.at(key)));
  return spec.at(key).get<bool>();
}

int frameCount(const Json& spec, const std::string& key, int fallback, int least) {
  if (!spec.contains(key)) return fallback;
  const Json& v = spec.at(key);
  if (!v.is_number_integer() || v.get<long long>() < least || v.get<long long>() > kSweepMaxFrames)
    throw InputError("sweep: \"" + key + "\" must be a whole number in " + std::to_string(least) +
                     ".." + std::to_string(kSweepMaxFrames) + ", got " + shown(v));
  return int(v.get<long long>());
}

// The scene of a view as every command sees it: loaded, then --orbit applied (cli::viewScene).
cli::Args viewArgs(const SweepView& view) {
  cli::Args args;
  args.command = "render";
  if (view.orbit) args.options["orbit"] = {*view.orbit};
  return args;
}
Scene viewedScene(const SweepView& view) {
  Scene scene = loadScene(view.scene);
  cli::viewScene(viewArgs(view), scene);
  return scene;
}

// One option axis of a technique's rows: the command-line option and the values swept.
struct Axis {
  std::string option;  // "shadow-map", or "param" with `key`
  std::string key;
  std::vector<std::string> values;
  std::string label(const std::string& value) const {
    return (option == "param" ? key : option) + "=" + value;
  }
};

std::string viewKey(const SweepPlan& plan, size_t view) {
  const SweepView& v = plan.views[view];
  return v.scene + "|" + std::to_string(v.width) + "x" + std::to_string(v.height) + "|" +
         v.orbit.value_or("") + "|" + backendName(plan.backend) + "|" +
         (plan.softReference ? "soft" : "") + "|" + (plan.temporal ? "temporal" : "");
}

}  // namespace

SweepPlan planSweep(const Json& spec) {
  if (!spec.is_object()) throw InputError("sweep: the spec must be an object, got " + shown(spec));
  for (const auto& [key, value] : spec.items())
    if (std::find(specKeys().begin(), specKeys().end(), key) == specKeys().end())
      throw InputError("sweep: unknown key \"" + key + "\" (keys: " + joined(specKeys()) + ")");
  SweepPlan plan;
  // Techniques and scenes by name, as render finds them.
  const std::vector<std::string> techniqueNames = stringList(spec, "techniques");
  if (techniqueNames.empty()) throw InputError("sweep: \"techniques\" is required");
  std::vector<const Technique*> techniques;
  for (const std::string& name : techniqueNames) techniques.push_back(&findTechnique(name));
  std::vector<std::string> scenes = stringList(spec, "scenes");
  if (scenes.empty()) scenes = {kDefaultScene};
  if (spec.contains("backend")) {
    if (!spec.at("backend").is_string())
      throw InputError("sweep: \"backend\" must be a name, got " + shown(spec.at("backend")));
    plan.backend = parseBackend(spec.at("backend").get<std::string>());
  }
  plan.warmup = frameCount(spec, "warmup", kSweepDefaultWarmup, 0);
  plan.repeat = frameCount(spec, "repeat", kSweepDefaultRepeat, 1);
  plan.softReference = flagValue(spec, "soft_reference", true);
  plan.temporal = flagValue(spec, "temporal", true);

  // Window sizes, checked as --size is.
  std::vector<std::pair<int, int>> sizes;
  for (const Json& v : axisValues(spec, "sizes")) {
    int w = 0, h = 0;
    cli::parseSize(sizeText(v), w, h);
    sizes.emplace_back(w, h);
  }
  if (sizes.empty()) sizes = {{kSweepDefaultWidth, kSweepDefaultHeight}};

  // The common options, each swept only for the techniques that read it.
  struct CommonAxis {
    const char* key;
    const char* option;
    CommonOption reads;
  };
  const CommonAxis kCommonAxes[] = {{"shadow_maps", "shadow-map", CommonOption::kShadowMap},
                                    {"filters", "filter", CommonOption::kFilter},
                                    {"precisions", "precision", CommonOption::kPrecision}};
  std::vector<std::pair<CommonOption, Axis>> commonAxes;
  for (const CommonAxis& c : kCommonAxes) {
    Axis axis{c.option, "", {}};
    for (const Json& v : axisValues(spec, c.key)) {
      const std::string text = optionText("\"" + std::string(c.key) + "\"", v);
      cli::Args check;  // checked as the option is on render's command line
      check.options[c.option] = {text};
      cli::renderParams(check);
      axis.values.push_back(text);
    }
    if (!axis.values.empty()) commonAxes.emplace_back(c.reads, axis);
  }

  // --param axes: each key swept for the techniques that declare it.
  std::vector<Axis> paramAxes;
  if (spec.contains("params") && !spec.at("params").is_null()) {
    const Json& params = spec.at("params");
    if (!params.is_object())
      throw InputError("sweep: \"params\" must map --param keys to lists of values, got " +
                       shown(params));
    for (const auto& [key, values] : params.items()) {
      const bool declared = std::any_of(techniques.begin(), techniques.end(),
                                        [&](const Technique* t) { return findParam(*t, key); });
      if (!declared) {
        std::set<std::string> keys;
        for (const Technique* t : techniques)
          for (const std::string& k : paramKeys(*t)) keys.insert(k);
        throw InputError(
            "sweep: \"params\": no technique of the sweep has a parameter '" + key + "' (theirs: " +
            (keys.empty() ? std::string("none")
                          : joined(std::vector<std::string>(keys.begin(), keys.end()))) +
            ")");
      }
      Axis axis{"param", key, {}};
      Json wrapped = Json::object();
      wrapped[key] = values;
      for (const Json& v : axisValues(wrapped, key))
        axis.values.push_back(optionText("\"params\" " + key, v));
      paramAxes.push_back(axis);
    }
  }

  // Views: every scene x size x orbit, each orbit checked on each scene as --orbit is.
  std::vector<std::optional<std::string>> orbits;
  for (const Json& v : axisValues(spec, "orbits")) orbits.push_back(orbitText(v));
  if (orbits.empty()) orbits = {std::nullopt};
  for (const std::string& scene : scenes) {
    loadScene(scene);
    for (const auto& [w, h] : sizes)
      for (const auto& orbit : orbits) {
        plan.views.push_back({scene, w, h, orbit});
        viewedScene(plan.views.back());
      }
  }

  // Rows: per view, per technique, the product of the axes that apply to it.
  for (size_t view = 0; view < plan.views.size(); ++view) {
    const SweepView& v = plan.views[view];
    for (const Technique* t : techniques) {
      std::vector<const Axis*> axes;
      for (const auto& [reads, axis] : commonAxes)
        if (readsOption(*t, reads)) axes.push_back(&axis);
      for (const Axis& axis : paramAxes)
        if (findParam(*t, axis.key)) axes.push_back(&axis);
      std::vector<size_t> at(axes.size(), 0);  // the current value of each axis
      for (;;) {
        SweepRow row;
        row.view = view;
        row.technique = t;
        row.options.command = "render";
        row.options.options["technique"] = {t->name};
        row.options.options["size"] = {std::to_string(v.width) + "x" + std::to_string(v.height)};
        row.options.options["backend"] = {backendName(plan.backend)};
        std::string label;
        for (size_t i = 0; i < axes.size(); ++i) {
          const Axis& axis = *axes[i];
          const std::string& value = axis.values[at[i]];
          row.options.options[axis.option].push_back(axis.option == "param" ? axis.key + "=" + value
                                                                            : value);
          label += (label.empty() ? "" : " ") + axis.label(value);
        }
        row.variant = label.empty() ? "default" : label;
        plan.rows.push_back(std::move(row));
        if (plan.rows.size() > kSweepMaxRows)
          throw InputError("sweep: more than " + std::to_string(kSweepMaxRows) +
                           " rows; split the spec");
        size_t i = 0;  // the next combination: the last axis varies fastest
        for (i = axes.size(); i > 0; --i) {
          if (++at[i - 1] < axes[i - 1]->values.size()) break;
          at[i - 1] = 0;
        }
        if (i == 0) break;
      }
    }
  }
  return plan;
}

std::shared_ptr<const SweepViewData> SweepReferenceCache::get(const SweepPlan& plan, size_t view) {
  const std::string key = viewKey(plan, view);
  if (auto it = byKey_.find(key); it != byKey_.end()) return it->second;
  const SweepView& v = plan.views[view];
  auto data = std::make_shared<SweepViewData>();
  data->scene = viewedScene(v);
  RenderParams base;
  base.width = v.width;
  base.height = v.height;
  base.backend = plan.backend;
  data->references = renderBenchReferences(data->scene, base, plan.softReference, plan.temporal);
  if (order_.size() >= kMaxViews) {
    byKey_.erase(order_.front());
    order_.erase(order_.begin());
  }
  byKey_[key] = data;
  order_.push_back(key);
  return data;
}

std::vector<BenchRow> measureSweepRows(const SweepPlan& plan, const std::vector<size_t>& indices,
                                       SweepReferenceCache& cache) {
  std::vector<BenchRow> rows;
  for (size_t index : indices) {
    if (index >= plan.rows.size())
      throw InputError("sweep: row " + std::to_string(index) + " does not exist (the spec has " +
                       std::to_string(plan.rows.size()) + ")");
    const SweepRow& row = plan.rows[index];
    const std::shared_ptr<const SweepViewData> view = cache.get(plan, row.view);
    const BenchVariant variant{row.variant, cli::renderParams(row.options)};
    rows.push_back(measureBenchRow(*row.technique, view->scene, variant, *view->references,
                                   plan.warmup, plan.repeat, true));
    rows.back().orbit = plan.views[row.view].orbit.value_or("");
  }
  return rows;
}

void assignSweepParetoRanks(std::vector<BenchRow>& rows, const std::vector<std::string>& groups) {
  if (groups.size() != rows.size())
    throw InputError("sweep: " + std::to_string(groups.size()) + " groups for " +
                     std::to_string(rows.size()) + " rows");
  std::vector<std::string> scenes;
  for (size_t i = 0; i < rows.size(); ++i) {
    scenes.push_back(rows[i].scene);
    rows[i].scene = groups[i];  // assignParetoRanks ranks within a scene: here, within a group
  }
  assignParetoRanks(rows);
  for (size_t i = 0; i < rows.size(); ++i) rows[i].scene = scenes[i];
}

}  // namespace sl::figures
