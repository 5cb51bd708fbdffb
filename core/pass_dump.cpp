// core/pass_dump.cpp — see pass_dump.h.
#include "core/pass_dump.h"

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "core/errors.h"
#include "core/html.h"
#include "core/image.h"
#include "core/output_files.h"

namespace sl {
namespace {
namespace fs = std::filesystem;

constexpr int kPassNumberDigits = 2;  // "01" .. "99": techniques have fewer than 100 passes
constexpr int kLettersInAlphabet = 26;
// index.html: small maps (128^2) are shown enlarged, wide strips scaled down; height follows.
constexpr int kMinShownWidthPixels = 256;
constexpr int kMaxShownWidthPixels = 1100;

// The text after the pass number of a buffer name: "3a-projected-map" -> "projected-map".
std::string afterPassNumber(const std::string& name) {
  size_t i = 0;
  while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i]))) ++i;
  if (i == 0) return name;
  if (i < name.size() && std::islower(static_cast<unsigned char>(name[i])) && i + 1 < name.size() &&
      name[i + 1] == '-')
    ++i;  // a letter the technique gave itself ("3a-")
  if (i < name.size() && (name[i] == '-' || name[i] == ' ')) ++i;
  return name.substr(i);
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

}  // namespace

int passNumberOf(const std::string& name) {
  size_t i = 0;
  int number = 0;
  while (i < name.size() && std::isdigit(static_cast<unsigned char>(name[i])) && number < 1000)
    number = number * 10 + (name[i++] - '0');
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
    return passNumberOf(frame.intermediates[a].name) < passNumberOf(frame.intermediates[b].name);
  });
  std::map<int, size_t> perPass;
  for (const PassImage& p : frame.intermediates) ++perPass[passNumberOf(p.name)];
  std::map<int, size_t> seen;
  std::set<std::string> used;
  std::vector<PassDumpImage> out;
  for (size_t i : order) {
    const PassImage& p = frame.intermediates[i];
    const int pass = passNumberOf(p.name);
    std::string stem =
        passPrefix(pass, seen[pass]++, perPass[pass]) + "-" + fileSafe(afterPassNumber(p.name));
    for (int k = 2; used.count(stem); ++k) stem += "-" + std::to_string(k);
    used.insert(stem);
    const bool alpha = p.image.channels == 2 || p.image.channels == 4;
    PassDumpImage main{stem + ".png", pass, p.caption, alpha ? opaque(p.image) : p.image, "", ""};
    if (alpha) main.caption += " [shown opaque: alpha ignored; each channel follows in grey]";
    out.push_back(main);
    if (!alpha) continue;
    const std::vector<std::string> names = channelNames(p.image.channels);
    for (int c = 0; c < p.image.channels; ++c) {
      const std::string& name = names[size_t(c)];
      out.push_back({stem + "-ch" + std::to_string(c + 1) + "-" + name + ".png", pass,
                     p.caption + " [channel " + name + " (" + channelWord(name) +
                         ") alone: 0 black .. 1 white]",
                     channel(p.image, c), name, main.file});
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
  // Passes by number: every timed entry, and passes that only have images.
  std::map<int, nlohmann::json> passes;
  for (const PassTime& t : frame.passes) {
    nlohmann::json& p = passes[passNumberOf(t.name)];
    if (!p.contains("name")) p["name"] = afterPassNumber(t.name);
    p["milliseconds"] = p.value("milliseconds", 0.0) + t.milliseconds;
    p["timings"].push_back({{"name", t.name}, {"milliseconds", t.milliseconds}});
  }
  out["images"] = nlohmann::json::array();
  for (const PassDumpImage& i : images) {
    nlohmann::json& p = passes[i.pass];
    p["files"].push_back(i.file);
    nlohmann::json image = {{"file", i.file},
                            {"pass", i.pass},
                            {"pass_name", p.value("name", "")},
                            {"caption", i.caption},
                            {"width", i.image.width},
                            {"height", i.image.height},
                            {"channels", i.image.channels}};
    if (!i.channel.empty()) {
      image["channel"] = i.channel;
      image["of"] = i.of;
    }
    out["images"].push_back(image);
  }
  out["passes"] = nlohmann::json::array();
  for (auto& [number, p] : passes) {
    p["number"] = number;
    if (!p.contains("name")) p["name"] = "";
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
       << "td { padding: 0.1em 0.8em 0.1em 0; }\n</style>\n</head>\n<body>\n";
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
    html << "<h2>" << (number >= 0 ? "Pass " + std::to_string(number) + ": " : std::string())
         << htmlEscape(p["name"].get<std::string>());
    if (p["milliseconds"].is_number())
      html << " <span class=\"time\">" << milliseconds(p["milliseconds"].get<double>())
           << (p["timings"].size() > 1 ? " in " + std::to_string(p["timings"].size()) + " parts"
                                       : std::string())
           << "</span>";
    html << "</h2>\n";
    for (const nlohmann::json& f : p["files"]) {
      const nlohmann::json& image = *images.at(f.get<std::string>());
      const int width = image["width"].get<int>();
      const int shown = std::clamp(width, kMinShownWidthPixels, kMaxShownWidthPixels);
      const std::string file = htmlEscape(f.get<std::string>());
      html << "<figure style=\"width: " << shown << "px\"><img src=\"" << file << "\" alt=\""
           << file << "\" style=\"width: " << shown << "px\"><figcaption><b>" << file << "</b> ("
           << width << "x" << image["height"].get<int>() << ")<br>"
           << htmlEscape(image["caption"].get<std::string>()) << "</figcaption></figure>\n";
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
