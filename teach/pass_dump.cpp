// teach/pass_dump.cpp — see pass_dump.h.
#include "teach/pass_dump.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>

#include "core/base/errors.h"
#include "core/base/html.h"
#include "core/base/image.h"
#include "core/base/output_files.h"
#include "core/gl/shaders.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

constexpr int kPassNumberDigits = 2;  // "01" .. "99": techniques have fewer than 100 passes
constexpr int kLettersInAlphabet = 26;
// index.html: small maps (128^2) are shown enlarged, wide strips scaled down; height follows.
constexpr int kMinShownWidthPixels = 256;
constexpr int kMaxShownWidthPixels = 1100;

// A buffer's name in its file: its name without the id of its pass (core/technique/passes.cpp
// names a buffer "ID-NAME"), "3a-projected-map" -> "projected-map"; a buffer of a named pass
// ("mesh-...") keeps its whole name, so that its file says which pass made it.
std::string bufferFileName(const PassImage& p) {
  const bool numbered = passIdNumber(p.passId) >= 0;
  if (numbered && p.name.compare(0, p.passId.size() + 1, p.passId + "-") == 0)
    return p.name.substr(p.passId.size() + 1);
  return p.name;
}

// A file-name-safe form: letters, digits, '.', '_' and '-'; anything else becomes '-'.
std::string fileSafe(const std::string& text) {
  std::string out;
  for (char c : text)
    out +=
        std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '_' || c == '-' ? c : '-';
  return out.empty() ? "buffer" : out;
}

// "05", "05a", "05b" ...: the pass number and, for one of several images, its position.
std::string passPrefix(int pass, size_t index, size_t count) {
  char number[16];
  std::snprintf(number, sizeof number, "%0*d", kPassNumberDigits, std::max(pass, 0));
  std::string prefix = number;
  if (count <= 1) return prefix;
  if (count <= size_t(kLettersInAlphabet)) return prefix + char('a' + index);
  char sub[16];
  std::snprintf(sub, sizeof sub, ".%02zu", index + 1);
  return prefix + sub;
}

// The channel names of an image with alpha: gray+alpha or RGBA.
std::vector<std::string> channelNames(int channels) {
  if (channels == 2) return {"L", "A"};
  return {"R", "G", "B", "A"};
}

std::string channelWord(const std::string& c) {
  static const std::map<std::string, std::string> words = {
      {"R", "red"}, {"G", "green"}, {"B", "blue"}, {"A", "alpha"}, {"L", "luminance"}};
  return words.at(c);
}

Image opaque(const Image& image) {
  Image out = image;
  for (size_t i = size_t(image.channels) - 1; i < out.data.size(); i += size_t(image.channels))
    out.data[i] = 1.0f;
  return out;
}

// The range of a packed map's values below the far plane (1), over all channels.
struct PackedRange {
  float lo;
  float hi;
};
constexpr float kFarDepth = 1.0f;
PackedRange drawnRange(const Image& image) {
  PackedRange r{kFarDepth, kFarDepth};
  bool any = false;
  for (float v : image.data) {
    if (v >= kFarDepth) continue;
    r.lo = any ? std::min(r.lo, v) : v;
    r.hi = any ? std::max(r.hi, v) : v;
    any = true;
  }
  return r;
}

// Channel c as grey over `range` (lo black, hi white, far white).
Image stretched(const Image& image, int c, PackedRange range) {
  Image out = channel(image, c);
  const float span = range.hi - range.lo;
  for (float& v : out.data)
    v = v >= kFarDepth ? 1.0f : span > 0.0f ? std::clamp((v - range.lo) / span, 0.0f, 1.0f) : 0.5f;
  return out;
}

// Channel c minus channel `centre` on a diverging scale (blue < 0 < red, 0 white), scaled to
// the largest difference where both samples were drawn (`limit`); larger ones clamp.
Image minusCentre(const Image& image, int c, int centre, float& limit) {
  limit = 0.0f;
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float a = image.at(x, y, c), b = image.at(x, y, centre);
      if (a < kFarDepth && b < kFarDepth) limit = std::max(limit, std::abs(a - b));
    }
  Image out(image.width, image.height, 3);
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      const float d = image.at(x, y, c) - image.at(x, y, centre);
      const float t = limit > 0.0f ? std::clamp(d / limit, -1.0f, 1.0f) : 0.0f;
      // white at 0, towards pure red (t = 1) or pure blue (t = -1)
      out.at(x, y, 0) = t < 0.0f ? 1.0f + t : 1.0f;
      out.at(x, y, 1) = 1.0f - std::abs(t);
      out.at(x, y, 2) = t > 0.0f ? 1.0f - t : 1.0f;
    }
  return out;
}

std::string milliseconds(double ms) {
  char text[32];
  std::snprintf(text, sizeof text, "%.2f ms", ms);
  return text;
}

// The JSON text of a value for a page: strings without quotes.
std::string shownValue(const nlohmann::json& v) {
  return v.is_string() ? v.get<std::string>()
                       : v.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// A legacy pass that a twin's pass replaces: its place in the twin's pass table, its id (the
// technique and the pass of its table) and its name there, for the page.
struct ReplacedPass {
  size_t order = 0;
  std::string technique;  // "legacy.fast-pcf"
  std::string pass;       // "6a"
  std::string name;       // "accumulate"
};

// A "replaces" entry of passes.json: the id, and the name for a reader.
nlohmann::json replacedJson(const ReplacedPass& r) {
  return {{"technique", r.technique}, {"pass", r.pass}, {"name", r.name}};
}

// Pass `id` of the header's twin, named from the twin's pass table. Throws GlError when the
// table has no such pass (a shader's @replaces line names a pass that is not there).
ReplacedPass replacedPass(const PassDumpHeader& header, const std::string& id) {
  if (header.twinPasses == nullptr)
    throw std::logic_error("passes.json: the header names the twin " + header.twin +
                           " without its pass table");
  const PassTable& table = *header.twinPasses;
  for (size_t i = 0; i < table.size(); ++i)
    if (table[i].id == id) return {i, header.twin, id, table[i].name};
  throw GlError("a shader's @replaces names " + header.twin + " pass " + id + ", which is not in " +
                header.twin + "'s pass table");
}

// The GLSL lines marked `// @pass id` (core/gl/shaders.h), added to a pass of passes.json once
// each, and the passes of the header's twin they replace (none without a twin) to `replaced`.
void addShaderPass(nlohmann::json& pass, const std::string& id, const PassDumpHeader& header,
                   std::vector<ReplacedPass>& replaced) {
  bool found = false;
  for (const ShaderPassMarker& m : shaderPassMarkers()) {
    if (m.id != id) continue;
    found = true;
    nlohmann::json where = {{"file", m.file},
                            {"first_line", m.firstLine},
                            {"last_line", m.lastLine},
                            {"marker", m.id},
                            {"title", m.title}};
    if (std::find(pass["glsl"].begin(), pass["glsl"].end(), where) == pass["glsl"].end())
      pass["glsl"].push_back(where);
    for (const ShaderReplaces& r : m.replaces) {
      if (header.twin.empty() || r.technique != header.twin) continue;  // a twin's passes only
      ReplacedPass named = replacedPass(header, r.passId);
      if (std::none_of(replaced.begin(), replaced.end(), [&](const ReplacedPass& p) {
            return p.technique == named.technique && p.pass == named.pass;
          }))
        replaced.push_back(std::move(named));
    }
  }
  if (!found) throw GlError("a pass names the shader marker @pass " + id + ", which no shader has");
}

// A value legend under an image: a gradient bar with its end values.
std::string legendHtml(const nlohmann::json& legend) {
  const bool diverging = legend["kind"] == "diverging";
  char low[32], high[32];
  std::snprintf(low, sizeof low, "%.4g", legend["low"].get<double>());
  std::snprintf(high, sizeof high, "%.4g", legend["high"].get<double>());
  std::ostringstream html;
  html << "<div class=\"legend\"><span>" << low << "</span><span class=\"bar\" style=\"background: "
       << (diverging ? "linear-gradient(to right, #00f, #fff, #f00)"
                     : "linear-gradient(to right, #000, #fff)")
       << "\"></span><span>" << high << "</span>";
  if (diverging) html << " <span>(0 = white)</span>";
  const std::string note = legend.value("note", "");
  if (!note.empty()) html << "<br><span class=\"note\">" << htmlEscape(note) << "</span>";
  html << "</div>";
  return html.str();
}

// The pass's section, source and GL state (core/gl/gl_trace.h) as a card.
std::string stateCard(const nlohmann::json& pass) {
  std::ostringstream html;
  const nlohmann::json& source = pass["source"];
  html << "<p class=\"where\">" << htmlEscape(pass["section"].get<std::string>());
  if (!source["file"].get<std::string>().empty())
    html << " &middot; <code>" << htmlEscape(source["file"].get<std::string>()) << "</code> <code>"
         << htmlEscape(source["function"].get<std::string>()) << "()</code>";
  html << "</p>\n<div class=\"state-card\"><b>GL state</b> ";
  const nlohmann::json& state = pass["state"];
  if (state.empty()) {
    html << "<i>no GL call that changes state or draws was made in this pass</i></div>\n";
    return html.str();
  }
  html << "(" << state.size()
       << " lines, in call order; grey: set before the pass's timer started)<table>\n";
  for (const nlohmann::json& l : state) {
    const std::string group = l["group"].get<std::string>();
    const char* cls = group == "part"                 ? " class=\"part\""
                      : l.value("before_pass", false) ? " class=\"before\""
                                                      : "";
    html << "<tr" << cls << "><td class=\"group\">" << htmlEscape(group) << "</td><td>"
         << htmlEscape(l["text"].get<std::string>()) << "</td></tr>\n";
  }
  html << "</table></div>\n";
  return html.str();
}

// The key a pass is grouped by: its id from the technique's pass table (core/technique/
// passes.h gives every pass of a render and every buffer it captures one).
const std::string& passKeyOf(const PassTime& t) { return t.id; }
const std::string& passKeyOf(const PassImage& p) { return p.passId; }

// Pipeline order of pass keys: by number ("mesh" and other named ids first), then the id
// ("5a" < "5b").
struct PipelineOrder {
  bool operator()(const std::string& a, const std::string& b) const {
    const int na = passIdNumber(a), nb = passIdNumber(b);
    return na != nb ? na < nb : a < b;
  }
};

// A pass's name without its id: "1 light pass" -> "light pass", "5a depth bounds" -> "depth
// bounds" (core/technique/passes.cpp puts a numbered id before the declared name).
std::string nameAfterId(const PassTime& t) {
  if (passIdNumber(t.id) >= 0 && t.name.compare(0, t.id.size() + 1, t.id + " ") == 0)
    return t.name.substr(t.id.size() + 1);
  return t.name;
}

}  // namespace

std::string replacedPassText(const nlohmann::json& replaced) {
  return replaced.value("technique", "") + " pass " + replaced.value("pass", "") + " " +
         replaced.value("name", "");
}

int passIdNumber(const std::string& id) {
  size_t i = 0;
  int number = 0;
  while (i < id.size() && std::isdigit(static_cast<unsigned char>(id[i])) && number < 1000)
    number = number * 10 + (id[i++] - '0');
  return i == 0 ? -1 : number;
}

void requireSomethingToDump(const Frame& frame, const std::string& technique) {
  if (frame.intermediates.empty())
    throw InputError("--dump-passes: " + technique +
                     " captured no intermediate buffer, so there is nothing to dump");
}

std::vector<PassDumpImage> planPassDump(const Frame& frame, const std::string& technique) {
  requireSomethingToDump(frame, technique);
  // Pipeline order: by pass number, and within a pass in the order the buffers were made.
  std::vector<size_t> order(frame.intermediates.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return PipelineOrder()(passKeyOf(frame.intermediates[a]), passKeyOf(frame.intermediates[b]));
  });
  std::map<int, size_t> perPass;
  for (const PassImage& p : frame.intermediates) ++perPass[passIdNumber(p.passId)];
  std::map<int, size_t> seen;
  std::set<std::string> used;
  std::vector<PassDumpImage> out;
  for (size_t i : order) {
    const PassImage& p = frame.intermediates[i];
    const int pass = passIdNumber(p.passId);
    std::string stem = passPrefix(pass, seen[pass]++, perPass[pass]);
    stem += '-';
    stem += fileSafe(bufferFileName(p));
    for (int k = 2; used.count(stem); ++k) {
      stem += '-';
      stem += std::to_string(k);
    }
    used.insert(stem);
    const bool alpha = p.image.channels == 2 || p.image.channels == 4;
    PassDumpImage main{
        stem + ".png", pass, p.caption, alpha ? opaque(p.image) : p.image, "", "", "",
        std::nullopt};
    main.passId = passKeyOf(p);
    if (alpha) main.caption += " [shown opaque: alpha ignored; each channel follows in grey]";
    out.push_back(main);
    if (!alpha) continue;
    const std::vector<std::string> names = channelNames(p.image.channels);
    const bool packed = p.centreChannel >= 0 && p.centreChannel < p.image.channels;
    // A packed map's channels share one depth scale: the drawn values, far (1) white.
    const PackedRange range = packed ? drawnRange(p.image) : PackedRange{0.0f, 1.0f};
    for (int c = 0; c < p.image.channels; ++c) {
      const std::string& name = names[size_t(c)];
      const std::string meaning =
          size_t(c) < p.channelMeaning.size() ? ": " + p.channelMeaning[size_t(c)] : "";
      PassDumpImage panel{
          stem + "-ch" + std::to_string(c + 1) + "-" + name + ".png",
          pass,
          p.caption + " [channel " + name + " (" + channelWord(name) + ")" + meaning + " alone]",
          packed ? stretched(p.image, c, range) : channel(p.image, c),
          name,
          main.file,
          "channel",
          packed ? ValueLegend{"grey", range.lo, range.hi, "1 (far: nothing drawn) = white"}
                 : ValueLegend{"grey", 0.0, 1.0, ""}};
      panel.passId = main.passId;
      out.push_back(panel);
    }
    if (!packed) continue;
    const int centre = p.centreChannel;
    for (int c = 0; c < p.image.channels; ++c) {
      if (c == centre) continue;
      const std::string& name = names[size_t(c)];
      const std::string& centreName = names[size_t(centre)];
      float limit = 0.0f;
      Image diverging = minusCentre(p.image, c, centre, limit);
      PassDumpImage view{
          stem + "-ch" + std::to_string(c + 1) + "-" + name + "-minus-" + centreName + ".png",
          pass,
          "channel " + name +
              (size_t(c) < p.channelMeaning.size() ? " (" + p.channelMeaning[size_t(c)] + ")"
                                                   : "") +
              " minus channel " + centreName +
              (size_t(centre) < p.channelMeaning.size()
                   ? " (" + p.channelMeaning[size_t(centre)] + ")"
                   : "") +
              ": white where the neighbour lies at the texel's depth; red / blue "
              "along depth edges where the packed neighbour is one texel away "
              "(Fig. 5)",
          std::move(diverging),
          name,
          main.file,
          "minus centre",
          ValueLegend{"diverging", -double(limit), double(limit),
                      "depth difference; clamped beyond the ends (edges against "
                      "the far plane)"}};
      view.passId = main.passId;
      out.push_back(view);
    }
  }
  return out;
}

nlohmann::json passesJson(const Frame& frame, const PassDumpHeader& header,
                          const std::vector<PassDumpImage>& images) {
  nlohmann::json out;
  out["technique"] = header.technique;
  out["paper"] = header.paper;
  out["scene"] = header.scene;
  out["parameters"] = header.parameters;
  out["frame_ms"] = frame.totalMilliseconds();
  out["counters"] = nlohmann::json::object();
  for (const auto& [key, value] : frame.counters) out["counters"][key] = value;
  // Passes by id: every timed entry, and passes that only have images.
  std::map<std::string, nlohmann::json, PipelineOrder> passes;
  std::map<std::string, std::vector<ReplacedPass>> replaced;  // by pass key
  for (const PassTime& t : frame.passes) {
    nlohmann::json& p = passes[passKeyOf(t)];
    if (!p.contains("name")) {
      p["name"] = nameAfterId(t);
      // Declared by the pass (core/technique/technique.h PassTimer): the paper section, or "ours
      // ...".
      p["section"] = t.section;  // a timed pass declares its own (an empty one is a bug)
      p["source"] = {{"file", t.sourceFile}, {"function", t.sourceFunction}};
      p["state"] = nlohmann::json::array();
      p["key_state"] = t.keyState;
    }
    p["milliseconds"] = p.value("milliseconds", 0.0) + t.milliseconds;
    p["timings"].push_back({{"name", t.name}, {"milliseconds", t.milliseconds}});
    // A pass timed in several parts (the phases of a 4x4 footprint): each part's lines
    // follow a "part" line naming it.
    size_t parts = 0;
    for (const PassTime& u : frame.passes) parts += passKeyOf(u) == passKeyOf(t);
    if (parts > 1) {
      p["state"].push_back({{"group", "part"}, {"text", t.name}});
      // The pass's title is what its parts share: "camera pass", not the first part's
      // "camera pass (upper-left)"; each part keeps its full name on its "part" line.
      const std::string name = p["name"].get<std::string>();
      const std::string part = nameAfterId(t);
      const size_t open = name.rfind(" (");
      if (open != std::string::npos && name != part &&
          part.compare(0, open + 2, name, 0, open + 2) == 0)
        p["name"] = name.substr(0, open);
    }
    for (const GlStateLine& l : t.gl.setup)
      p["state"].push_back({{"group", l.group}, {"text", l.text}, {"before_pass", true}});
    for (const GlStateLine& l : t.gl.state)
      p["state"].push_back({{"group", l.group}, {"text", l.text}});
    if (!p.contains("glsl")) {
      p["glsl"] = nlohmann::json::array();
      p["replaces"] = nlohmann::json::array();
    }
    for (const std::string& id : t.glsl) addShaderPass(p, id, header, replaced[passKeyOf(t)]);
  }
  out["images"] = nlohmann::json::array();
  for (const PassDumpImage& i : images) {
    nlohmann::json& p = passes[i.passId];
    p["files"].push_back(i.file);
    nlohmann::json image = {{"file", i.file},           {"pass", i.pass},
                            {"pass_id", i.passId},      {"pass_name", p.value("name", "")},
                            {"caption", i.caption},     {"width", i.image.width},
                            {"height", i.image.height}, {"channels", i.image.channels}};
    if (!i.channel.empty()) {
      image["channel"] = i.channel;
      image["of"] = i.of;
    }
    if (!i.view.empty()) image["view"] = i.view;
    if (i.legend)
      image["legend"] = {{"kind", i.legend->kind},
                         {"low", i.legend->low},
                         {"high", i.legend->high},
                         {"note", i.legend->note}};
    out["images"].push_back(image);
  }
  out["passes"] = nlohmann::json::array();
  for (auto& [id, p] : passes) {
    // The legacy passes a twin's pass replaces, in the order of the twin's table (the markers
    // list them in the shader's order).
    std::vector<ReplacedPass>& legacy = replaced[id];
    std::stable_sort(
        legacy.begin(), legacy.end(),
        [](const ReplacedPass& a, const ReplacedPass& b) { return a.order < b.order; });
    p["replaces"] = nlohmann::json::array();
    for (const ReplacedPass& r : legacy) p["replaces"].push_back(replacedJson(r));
    p["id"] = id;
    p["number"] = passIdNumber(id);
    if (!p.contains("name")) p["name"] = "";
    if (!p.contains("section")) p["section"] = header.paper;
    if (!p.contains("source")) p["source"] = {{"file", ""}, {"function", ""}};
    if (!p.contains("state")) p["state"] = nlohmann::json::array();
    if (!p.contains("key_state")) p["key_state"] = nlohmann::json::array();
    if (!p.contains("glsl")) p["glsl"] = nlohmann::json::array();
    if (!p.contains("replaces")) p["replaces"] = nlohmann::json::array();
    if (!p.contains("milliseconds")) p["milliseconds"] = nullptr;
    if (!p.contains("timings")) p["timings"] = nlohmann::json::array();
    if (!p.contains("files")) p["files"] = nlohmann::json::array();
    out["passes"].push_back(p);
  }
  return out;
}

std::string indexHtml(const nlohmann::json& passes) {
  std::map<std::string, const nlohmann::json*> images;
  for (const nlohmann::json& i : passes["images"]) images[i["file"].get<std::string>()] = &i;
  const std::string technique = htmlEscape(passes["technique"].get<std::string>());
  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>"
       << technique << " — passes</title>\n<style>\n"
       << "body { font-family: sans-serif; margin: 1.5em; max-width: 1200px; }\n"
       << "h2 { border-top: 1px solid #ccc; padding-top: 0.6em; }\n"
       << ".time { color: #555; font-weight: normal; font-size: 0.8em; }\n"
       << "figure { display: inline-block; vertical-align: top; margin: 0 1em 1em 0; }\n"
       << "figure img { height: auto; max-width: 100%; image-rendering: pixelated; "
          "border: 1px solid #999; }\n"
       << "figcaption { font-size: 0.85em; margin-top: 0.3em; }\n"
       << "table { border-collapse: collapse; font-size: 0.9em; }\n"
       << "td { padding: 0.1em 0.8em 0.1em 0; }\n"
       << ".where { color: #333; margin: 0.2em 0 0.6em 0; }\n"
       << ".state-card { border: 1px solid #bbb; background: #f7f7f2; padding: 0.4em 0.7em; "
          "margin: 0 0 1em 0; max-height: 28em; overflow: auto; }\n"
       << ".state-card td { font-family: monospace; font-size: 0.85em; vertical-align: top; "
          "word-break: break-word; }\n"
       << ".state-card td.group { color: #0a5; white-space: nowrap; }\n"
       << ".state-card tr.before td { color: #777; }\n"
       << ".state-card tr.part td { font-weight: bold; padding-top: 0.5em; }\n"
       << ".legend span { vertical-align: middle; margin-right: 0.3em; }\n"
       << ".legend .bar { display: inline-block; width: 120px; height: 0.8em; "
          "border: 1px solid #999; }\n"
       << ".legend .note { color: #555; }\n"
       << "</style>\n</head>\n<body>\n";
  html << "<h1>" << technique << "</h1>\n<p>" << htmlEscape(passes["paper"].get<std::string>())
       << "<br>scene " << htmlEscape(passes["scene"].get<std::string>()) << ", frame "
       << milliseconds(passes["frame_ms"].get<double>()) << "</p>\n<table>\n";
  for (const auto& [key, value] : passes["parameters"].items()) {
    if (value.is_object()) {
      for (const auto& [k, v] : value.items())
        html << "<tr><td>--param " << htmlEscape(k) << "</td><td>" << htmlEscape(shownValue(v))
             << "</td></tr>\n";
    } else if (!value.is_null()) {
      html << "<tr><td>" << htmlEscape(key) << "</td><td>" << htmlEscape(shownValue(value))
           << "</td></tr>\n";
    }
  }
  for (const auto& [key, value] : passes["counters"].items())
    html << "<tr><td>counter " << htmlEscape(key) << "</td><td>" << htmlEscape(shownValue(value))
         << "</td></tr>\n";
  html << "</table>\n";
  for (const nlohmann::json& p : passes["passes"]) {
    const int number = p["number"].get<int>();
    const std::string id = p.value("id", std::to_string(number));
    html << "<h2>" << (number >= 0 ? "Pass " + id + ": " : std::string())
         << htmlEscape(p["name"].get<std::string>());
    if (p["milliseconds"].is_number())
      html << " <span class=\"time\">" << milliseconds(p["milliseconds"].get<double>())
           << (p["timings"].size() > 1 ? " in " + std::to_string(p["timings"].size()) + " parts"
                                       : std::string())
           << "</span>";
    html << "</h2>\n";
    html << stateCard(p);
    if (!p["glsl"].empty()) {
      html << "<p class=\"glsl\">GLSL: ";
      bool first = true;
      for (const nlohmann::json& g : p["glsl"]) {
        html << (first ? "" : "; ") << "<code>" << htmlEscape(g["file"].get<std::string>())
             << "</code> lines " << g["first_line"].get<int>() << "&ndash;"
             << g["last_line"].get<int>() << " (" << htmlEscape(g["title"].get<std::string>())
             << ")";
        first = false;
      }
      html << "</p>\n";
    }
    if (!p["replaces"].empty()) {
      html << "<p class=\"replaces\">Replaces: ";
      bool first = true;
      for (const nlohmann::json& r : p["replaces"]) {
        html << (first ? "" : "; ") << htmlEscape(replacedPassText(r));
        first = false;
      }
      html << "</p>\n";
    }
    for (const nlohmann::json& f : p["files"]) {
      const nlohmann::json& image = *images.at(f.get<std::string>());
      const int width = image["width"].get<int>();
      const int shown = std::clamp(width, kMinShownWidthPixels, kMaxShownWidthPixels);
      const std::string file = htmlEscape(f.get<std::string>());
      html << "<figure style=\"width: " << shown << "px\"><img src=\"" << file << "\" alt=\""
           << file << "\" style=\"width: " << shown << "px\"><figcaption><b>" << file << "</b> ("
           << width << "x" << image["height"].get<int>() << ")<br>"
           << htmlEscape(image["caption"].get<std::string>());
      if (image.contains("legend")) html << legendHtml(image["legend"]);
      html << "</figcaption></figure>\n";
    }
  }
  html << "</body>\n</html>\n";
  return html.str();
}

void writePassDump(const std::string& directory, const Frame& frame, const PassDumpHeader& header,
                   const Provenance& provenance) {
  const std::vector<PassDumpImage> images = planPassDump(frame, header.technique);
  for (const PassDumpImage& i : images)
    writePng((fs::path(directory) / i.file).string(), i.image, 8, provenance);
  const nlohmann::json passes = passesJson(frame, header, images);
  writeFileAtomically((fs::path(directory) / kDumpIndexFiles[0]).string(), [&](std::ostream& out) {
    out << passes.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) << "\n";
  });
  writeFileAtomically((fs::path(directory) / kDumpIndexFiles[1]).string(),
                      [&](std::ostream& out) { out << indexHtml(passes); });
}

}  // namespace sl
