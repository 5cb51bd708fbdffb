// teach/lesson_why.cpp — the lesson's "why" blocks: pictures rendered at lesson time, numbers
// read from the page's own GL traces, the 4x4 tiling drawn from the pass table
// (teach/lesson.h, teach/lesson_parts.h).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <nlohmann/json.hpp>
#include <regex>
#include <set>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/html.h"
#include "core/base/image.h"
#include "core/gl/shaders.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"
#include "registry/twins.h"
#include "teach/lesson_parts.h"
#include "teach/pass_dump.h"

namespace sl::figures::lesson_detail {

// The part of an image a why picture shows, seen from the top: [x, y from the top, w, h].
// `region` gives it as fractions of the image (the same place at every lesson size), `crop` in
// pixels of this image; neither: the whole image.
struct Rect {
  int x = 0, top = 0, w = 0, h = 0;
};
Rect cropRect(int width, int height, const json& crop, const json& region) {
  Rect r{0, 0, width, height};
  double v[4];
  if (region.is_array() && region.size() == 4) {
    for (size_t i = 0; i < 4; ++i) v[i] = region[i].get<double>() * (i % 2 ? height : width);
  } else if (crop.is_array() && crop.size() == 4) {
    for (size_t i = 0; i < 4; ++i) v[i] = crop[i].get<double>();
  } else {
    return r;
  }
  r.x = std::clamp(int(std::lround(v[0])), 0, width - 1);
  r.top = std::clamp(int(std::lround(v[1])), 0, height - 1);
  r.w = std::clamp(int(std::lround(v[2])), 1, width - r.x);
  r.h = std::clamp(int(std::lround(v[3])), 1, height - r.top);
  return r;
}

// `r` of an image enlarged `zoom` times with nearest-neighbour sampling so that single pixels
// stay visible.
Image croppedAndZoomed(const Image& image, const Rect& r, int zoom) {
  zoom = std::max(zoom, 1);
  Image out(r.w * zoom, r.h * zoom, image.channels);
  const int bottom = image.height - r.top - r.h;  // rows are stored bottom-up
  for (int y = 0; y < out.height; ++y)
    for (int xx = 0; xx < out.width; ++xx)
      for (int c = 0; c < image.channels; ++c)
        out.at(xx, y, c) = image.at(r.x + xx / zoom, bottom + y / zoom, c);
  return out;
}

// The mean of a one-channel image over `r` (the visibility a why picture shows).
double meanOver(const Image& image, const Rect& r) {
  if (image.width == 0 || image.height == 0) return 0.0;
  const int bottom = image.height - r.top - r.h;
  double sum = 0.0;
  for (int y = bottom; y < bottom + r.h; ++y)
    for (int x = r.x; x < r.x + r.w; ++x) sum += image.at(x, y, 0);
  return sum / double(r.w * r.h);
}

// The numbers of a traced line: "GL_S: GL_EYE_PLANE = (0.862, -0.43, ...)" -> {0.862, -0.43, ...}
// (those after the first '(' or '[').
std::vector<double> numbersOf(const std::string& text) {
  static const std::regex kNumber(R"([-+]?[0-9]*\.?[0-9]+(?:[eE][-+]?[0-9]+)?)");
  const size_t open = text.find_first_of("([");
  std::vector<double> out;
  if (open == std::string::npos) return out;
  const std::string tail = text.substr(open);
  for (auto it = std::sregex_iterator(tail.begin(), tail.end(), kNumber);
       it != std::sregex_iterator(); ++it)
    out.push_back(std::stod(it->str()));
  return out;
}

// Everitt Eq. 5 on both twins: the four EYE_LINEAR planes the legacy camera pass gives (unit 0)
// beside the rows of the matrix the shader twin loads (uWorldToShadowMap), as traced on this
// page's cards, with their largest difference. Empty when the page has no such pair of lines.
std::string planesTable(const std::vector<Side>& sides) {
  std::vector<std::vector<double>> planes(4), rows;
  std::string legacyName, modernName;
  const char* coords[] = {"GL_S", "GL_T", "GL_R", "GL_Q"};
  for (const Side& side : sides) {
    if (!side.tag.empty()) continue;
    for (const json& pass : side.passes["passes"])
      for (const json& line : pass.value("state", json::array())) {
        const std::string text = line.value("text", "");
        for (int i = 0; i < 4; ++i)
          if (text.rfind(std::string(coords[i]) + ": GL_EYE_PLANE = (", 0) == 0 &&
              text.find("(unit 0;") != std::string::npos && planes[size_t(i)].empty()) {
            planes[size_t(i)] = numbersOf(text);
            legacyName = side.technique->name;
          }
        if (text.rfind("uWorldToShadowMap = mat4 [", 0) == 0 && rows.empty()) {
          const std::vector<double> m = numbersOf(text);
          for (size_t r = 0; r + 1 < 5 && m.size() == 16; ++r)
            rows.emplace_back(m.begin() + long(4 * r), m.begin() + long(4 * r + 4));
          modernName = side.technique->name;
        }
      }
  }
  if (rows.size() != 4 ||
      std::any_of(planes.begin(), planes.end(), [](const auto& p) { return p.size() < 4; }))
    return "";
  std::ostringstream html;
  double largest = 0.0;
  html << "<table class=\"numbers\"><tr><th>row</th><th>" << htmlEscape(legacyName)
       << ": glTexGenfv(…, GL_EYE_PLANE) (pass card)</th><th>" << htmlEscape(modernName)
       << ": uWorldToShadowMap row (pass card)</th><th>largest |difference|</th></tr>\n";
  for (int i = 0; i < 4; ++i) {
    double d = 0.0;
    std::string a, b;
    for (int k = 0; k < 4; ++k) {
      d = std::max(d, std::fabs(planes[size_t(i)][size_t(k)] - rows[size_t(i)][size_t(k)]));
      const char* separator = k ? ", " : "";
      a.append(separator).append(fmt(planes[size_t(i)][size_t(k)], "%.6g"));
      b.append(separator).append(fmt(rows[size_t(i)][size_t(k)], "%.6g"));
    }
    largest = std::max(largest, d);
    html << "<tr><td>" << coords[i] << "</td><td><code>(" << a << ")</code></td><td><code>(" << b
         << ")</code></td><td>" << fmt(d, "%.2g") << "</td></tr>\n";
  }
  html << "</table>\n<p class=\"measured\">Largest difference over the sixteen numbers: "
       << fmt(largest, "%.2g")
       << " (both printed with 6 significant digits; the two programs compute the same product "
          "in float).</p>\n";
  return html.str();
}

// The parts of a pass repeated per phase or group (the 4x4 footprint), with the traced lines
// of each part that hold one of `match` (the kernels of the packing copy, the texture matrix
// of the projective pass): a table of what changes from part to part.
std::string partsTable(const std::vector<Side>& sides, const json& block) {
  const std::string tag = footprintTag(kLargeFootprint);
  std::ostringstream html;
  for (const Side& side : sides) {
    if (side.tag != tag || side.role != "legacy") continue;
    for (const json& id : block.value("passes", json::array()))
      for (const json& pass : side.passes["passes"]) {
        if (pass.value("id", "") != id.get<std::string>()) continue;
        html << "<table class=\"numbers parts\"><tr><th colspan=2>"
             << htmlEscape(side.technique->name) << " at 4x4, pass "
             << htmlEscape(pass.value("id", "")) << " (" << htmlEscape(pass.value("name", ""))
             << "), as traced</th></tr>\n";
        std::string part;
        for (const json& line : pass.value("state", json::array())) {
          const std::string text = line.value("text", "");
          if (line.value("group", "") == "part") {
            const size_t open = text.rfind(" (");
            part = open == std::string::npos ? text : text.substr(open + 1);
            continue;
          }
          for (const json& m : block.value("match", json::array()))
            if (text.find(m.get<std::string>()) != std::string::npos &&
                text.find("load [1 0 0 0; 0 1 0 0; 0 0 1 0; 0 0 0 1]") == std::string::npos) {
              html << "<tr><td>" << htmlEscape(part) << "</td><td>" << code(text) << "</td></tr>\n";
              break;
            }
        }
        html << "</table>\n";
      }
  }
  return html.str();
}

// Brabec & Seidel §4's 4x4 footprint as four 2x2 phases: the 16 texels around the lookup point
// (the texel corner nearest to it, the dot), each phase's block in its colour with the channel
// that holds each texel (the packing's channel meaning, PassBuffer::channelMeaning: R lower left,
// G lower right, B upper left, A upper right). Drawn as SVG from the legacy 4x4 pass table.
std::string tilingFigure(const std::vector<Side>& sides) {
  constexpr int kCell = 44;  // pixels per texel in the drawing
  constexpr int kMargin = 10;
  const char* colours[] = {"#fbb", "#bdf", "#bfb", "#fe9"};
  const char* phases[] = {"upper-left", "upper-right", "lower-left", "lower-right"};
  const char* letters[2][2] = {{"B", "A"}, {"R", "G"}};  // [row from the top][column]
  const PassSpec* packing = nullptr;
  for (const Side& side : sides)
    if (side.tag == footprintTag(kLargeFootprint) && side.role == "legacy")
      for (const PassSpec& spec : side.technique->passes)
        for (const PassBuffer& b : spec.writes)
          if (b.centreChannel >= 0 && b.channelMeaning.size() == 4) packing = &spec;
  if (packing == nullptr) return "";
  const int size = 4 * kCell + 2 * kMargin;
  std::ostringstream svg;
  svg << "<svg class=\"tiling\" width=\"" << size << "\" height=\"" << size << "\" viewBox=\"0 0 "
      << size << " " << size << "\" font-family=\"sans-serif\" font-size=\"13\">\n";
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) {
      const int phase = (row / 2) * 2 + col / 2;
      const int x = kMargin + col * kCell, y = kMargin + row * kCell;
      svg << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << kCell << "\" height=\""
          << kCell << "\" fill=\"" << colours[phase] << "\" stroke=\"#888\"/>"
          << "<text x=\"" << x + kCell / 2 << "\" y=\"" << y + kCell / 2 + 5
          << "\" text-anchor=\"middle\">" << letters[row % 2][col % 2] << "</text>\n";
    }
  for (int phase = 0; phase < 4; ++phase) {
    const int x = kMargin + (phase % 2) * 2 * kCell, y = kMargin + (phase / 2) * 2 * kCell;
    svg << "<rect x=\"" << x << "\" y=\"" << y << "\" width=\"" << 2 * kCell << "\" height=\""
        << 2 * kCell << "\" fill=\"none\" stroke=\"#000\" stroke-width=\"2\"><title>"
        << phases[phase] << " phase</title></rect>\n";
  }
  svg << "<circle cx=\"" << kMargin + 2 * kCell << "\" cy=\"" << kMargin + 2 * kCell
      << "\" r=\"5\" fill=\"#000\"/>\n</svg>";
  std::ostringstream html;
  html << "<figure class=\"picture\">" << svg.str()
       << "<figcaption>The 4x4 footprint of one lookup as four 2x2 phases, one packed map each "
          "(pass "
       << htmlEscape(packing->id)
       << "; upper-left red, "
          "upper-right blue, lower-left green, lower-right yellow); the letter in each texel is "
          "the channel of that phase's packed map that holds it ("
       << htmlEscape(packing->writes.front().channelMeaning[0]) << " R, "
       << htmlEscape(packing->writes.front().channelMeaning[1]) << " G, "
       << htmlEscape(packing->writes.front().channelMeaning[2])
       << " B, upper right A); the dot "
          "is the texel corner nearest to the point.</figcaption></figure>\n";
  return html.str();
}

// The "why" blocks of the lesson text: [{"title", "text": [...], "renders": [{"technique",
// "params", "filter", "scene", "shadow-map", "caption", "region" | "crop", "zoom"}], "table":
// "planes" | "parts", "passes", "match", "figure": "tiling"}]; each render is made here, at the
// lesson's size, on the lesson's scene and shadow map unless the render names its own (a
// failure case that needs another configuration: the fence of Annen et al. Fig. 9, a coarse map).
std::vector<WhyBlock> whyBlocks(const LessonText& text, const std::vector<Side>& sides,
                                const LessonSettings& s, const Scene& scene) {
  std::vector<WhyBlock> out;
  const json blocks = text.entry.value("why", json::array());
  try {
    for (size_t b = 0; b < blocks.size(); ++b) {
      const json& block = blocks[b];
      WhyBlock w;
      w.title = block.at("title").get<std::string>();
      w.text = block.value("text", json::array()).get<std::vector<std::string>>();
      const json renders = block.value("renders", json::array());
      for (size_t r = 0; r < renders.size(); ++r) {
        const json& render = renders[r];
        const Technique& t = findTechnique(render.at("technique").get<std::string>());
        LessonSettings own = s;
        own.scene = render.value("scene", s.scene);
        own.shadowMapTexels = render.value("shadow-map", s.shadowMapTexels);
        RenderParams p = paramsForSettings(own);
        p.filter = render.value("filter", p.filter);
        const json params = render.value("params", json::object());
        for (const auto& [k, v] : params.items()) p.extra[k] = v.get<std::string>();
        const Frame frame =
            renderTechnique(t, own.scene == s.scene ? scene : loadScene(own.scene), p);
        WhyPicture pic;
        pic.file = "why-" + std::to_string(b + 1) + "-" + std::to_string(r + 1) + ".png";
        pic.caption = render.at("caption").get<std::string>();
        long long shadowed = 0;  // visibility below one half
        for (float v : frame.visibility.data) shadowed += v < 0.5f;
        const double share = frame.visibility.data.empty()
                                 ? 0.0
                                 : double(shadowed) / double(frame.visibility.data.size());
        pic.measured = fmt(100.0 * share, "%.1f") + "% of the image in shadow (visibility < 1/2)";
        const Rect rect = cropRect(frame.color.width, frame.color.height,
                                   render.value("crop", json()), render.value("region", json()));
        const bool sameSize = frame.visibility.width == frame.color.width &&
                              frame.visibility.height == frame.color.height;
        if (sameSize && (rect.w != frame.color.width || rect.h != frame.color.height))
          pic.measured += "; mean visibility in the part shown: " +
                          fmt(meanOver(frame.visibility, rect), "%.3f");
        pic.command = renderCommandFor(t, p, own, pic.file.substr(0, pic.file.size() - 4), false);
        pic.image = croppedAndZoomed(frame.color, rect, render.value("zoom", 1));
        w.pictures.push_back(std::move(pic));
      }
      const std::string table = block.value("table", "");
      if (table == "planes") w.tableHtml = planesTable(sides);
      if (table == "parts") w.tableHtml = partsTable(sides, block);
      if (block.value("figure", "") == "tiling") w.figureHtml = tilingFigure(sides);
      out.push_back(std::move(w));
    }
  } catch (const json::exception& e) {
    throw InputError("lesson text " + text.file + ": why: " + e.what());
  }
  return out;
}

}  // namespace sl::figures::lesson_detail
