#include "figures/gallery.h"

#include <cmath>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/base/errors.h"
#include "core/base/html.h"
#include "core/base/image.h"
#include "core/base/output_files.h"
#include "core/base/provenance.h"
#include "core/scene/scene_library.h"
#include "registry/registry.h"

namespace sl::figures {
namespace fs = std::filesystem;
using json = nlohmann::json;

namespace {
constexpr int kCloseupFrame = 2;  // pixels: the red frame around the close-up's window
}  // namespace

// Every entry's parameters were chosen by looking at the pictures and their close-ups at
// 400x300 (the size every entry uses); tests/figures/gallery_test.cpp checks that the two
// pictures differ inside the close-up window.
const std::vector<GalleryEntry>& galleryEntries() {
  static const std::vector<GalleryEntry> kEntries = {
      {"acne",
       "Shadow acne",
       "Without polygon offset every lit surface compares its own depth against the depth stored "
       "for it, rounded to the map's texels and depth steps: half the samples fall behind and "
       "shadow themselves, in moire stripes across the ground and the objects (Everitt et al., "
       "'polygon offset'; Chan 2004 Fig. 2-4a).",
       "polygon offset of the light pass: offset-factor and offset-units (0, 0)",
       "the technique's tuned offset (factor 2, units 4) pushes the stored depths just behind "
       "the lit surfaces",
       "brabec",
       400,
       300,
       {},
       "legacy.hw",
       "legacy.hw",
       {{"param", "offset-factor=0"}, {"param", "offset-units=0"}},
       {},
       {140, 200, 100, 75, 4}},
      {"peter-panning",
       "Peter-panning: light leaks under the caster",
       "Too much offset pushes the stored depths so far behind the casters that the floor next "
       "to the box's base tests as lit: the shadow comes loose from the box and a lit gap opens "
       "at the contact (Chan 2004 Fig. 2-4b).",
       "offset-units of the light pass (1000000 depth steps)",
       "the tuned offset (units 4) keeps the shadow attached to the box",
       "contact",
       400,
       300,
       {},
       "legacy.hw",
       "legacy.hw",
       {{"param", "offset-units=1000000"}},
       {},
       {95, 150, 120, 70, 3}},
      {"perspective-aliasing",
       "Perspective aliasing: stair steps near the eye",
       "With the light facing the camera (dueling frusta), one shadow-map texel covers many "
       "pixels near the eye: with one nearest comparison per pixel the shadow edges become "
       "large stair steps (Everitt et al. Fig. 6; Chan 2004 Fig. 2-5).",
       "shadow-map resolution (128 x 128) with compare=nearest",
       "a 2048 x 2048 map shrinks the steps below a pixel here",
       "dueling",
       400,
       300,
       {{"param", "compare=nearest"}},
       "legacy.hw",
       "legacy.hw",
       {{"shadow-map", "128"}},
       {{"shadow-map", "2048"}},
       {170, 170, 100, 75, 3}},
      {"projective-aliasing",
       "Projective aliasing at grazing light",
       "With the light low over the scene, the ground is almost parallel to the light's rays: "
       "one map texel's footprint is stretched over many pixels along the ground, and the "
       "edges of the shadows cast on it (the yellow ball's, magnified) become long, uneven "
       "steps. GPU Gems §11.1: a higher resolution \"does not work when the light is traveling "
       "nearly parallel to the shadowed surface, because the magnification approaches "
       "infinity\".",
       "shadow-map resolution (128 x 128) under a grazing light (light-position -7,1.6,3)",
       "a 2048 x 2048 map under the same light",
       "brabec",
       400,
       300,
       {{"light-position", "-7,1.6,3"}, {"param", "compare=nearest"}},
       "legacy.hw",
       "legacy.hw",
       {{"shadow-map", "128"}},
       {{"shadow-map", "2048"}},
       {200, 90, 120, 60, 4}},
      {"ramp-banding",
       "8-bit depth banding in the ramp shadow map",
       "Brabec & Seidel §2 store depth as an 8-bit colour from a 1D ramp: 256 steps over the "
       "light's range. Without the depth bias a lit surface meets its own stored depth, rounded "
       "in the light's pass and again in the camera's: where the camera's rounding lands a step "
       "behind the map's, the subtraction shadows the lit ground, in dark streaks along the "
       "contours of the 8-bit depth.",
       "depth-bias (0 steps) at 8-bit precision",
       "our default bias of 2 steps (the paper names no bias)",
       "brabec",
       400,
       300,
       {{"precision", "8"}},
       "legacy.ramp",
       "legacy.ramp",
       {{"param", "depth-bias=0"}},
       {},
       {120, 200, 100, 75, 4}},
      {"vsm-light-bleeding",
       "VSM light bleeding",
       "A variance shadow map keeps the mean and variance of the depths under its filter. Where "
       "the fence near the light and the low plank overlap in one kernel, the variance is large "
       "and Chebyshev's upper bound lets light into the plank's shadow: the fence's stripes "
       "show through it (Annen et al. 2007 Fig. 9).",
       "the Chebyshev bound itself (bleed-reduction 0)",
       "bleed-reduction=0.5 counts a bound below 0.5 as shadow",
       "bleeding",
       400,
       300,
       {},
       "modern.vsm",
       "modern.vsm",
       {},
       {{"param", "bleed-reduction=0.5"}},
       {150, 135, 120, 60, 3}},
      {"csm-low-order",
       "CSM: a low-order shadow test fades at contacts",
       "Convolution shadow maps expand the step of the shadow test in M Fourier terms. With "
       "M = 2 the reconstructed step is so smooth that a receiver close behind its caster is "
       "lit: the slanted square's shadow fades to white towards its contact with the plane "
       "(Annen et al. 2007 Fig. 6; series not attenuated, alpha = 0).",
       "order M (2 Fourier terms)",
       "M = 16 keeps the shadow dark up to the contact",
       "squares",
       400,
       300,
       {{"param", "alpha=0"}, {"param", "offset-rule=through-1"}},
       "modern.csm",
       "modern.csm",
       {{"param", "order=2"}},
       {{"param", "order=16"}},
       {235, 75, 90, 75, 3}},
      {"csm-ringing",
       "CSM ringing",
       "The truncated Fourier series of the shadow test's step oscillates about it (Gibbs). "
       "Without attenuation (alpha = 0) the darkness of a shadow rises and falls with the "
       "receiver's distance behind the caster: a lighter band runs across the tilted square's "
       "shadow, darker again beyond it (M = 4, unblurred float basis, so that nothing else "
       "smooths it; Annen et al. 2007 §3.2.1 and Fig. 3(b)).",
       "alpha = 0: no attenuation of the high Fourier terms",
       "alpha = 1 (the technique's default) damps them: the shadow darkens steadily away from the "
       "contact, softer next to it, the price §3.2.1 names",
       "squares",
       400,
       300,
       {{"param", "order=4"},
        {"param", "offset-rule=through-1"},
        {"param", "storage=float"},
        {"param", "blur=0"}},
       "modern.csm",
       "modern.csm",
       {{"param", "alpha=0"}},
       {{"param", "alpha=1"}},
       {245, 95, 70, 50, 5}},
      {"hybrid-missed-silhouette",
       "Hybrid: a shadow the silhouette band missed",
       "Chan's hybrid runs shadow volumes only at the silhouette pixels its shadow map finds. A "
       "bar thinner than a texel of a 64 x 64 map is missing from the map, so no silhouette "
       "pixel is found along its shadow and the volumes never run there: most of the bar's "
       "shadow is gone.",
       "shadow-map resolution of the classification (64 x 64)",
       "a 1024 x 1024 map sees the bar; the volumes draw its whole shadow",
       "dragon",
       400,
       300,
       {},
       "modern.hybrid",
       "modern.hybrid",
       {{"shadow-map", "64"}},
       {{"shadow-map", "1024"}},
       {290, 150, 100, 50, 4}},
      {"smoothies-contact",
       "Smoothies: the contact error",
       "Smoothies add a fixed-width soft edge (width t in the light's image) outside every "
       "silhouette. Without remapping, that edge darkens the lit floor in front of the box where "
       "box and floor meet: a shadow that does not come from the box (Chan 2004 Fig. 4-4b).",
       "remap=off: smoothie alpha not remapped by the depth ratio (width t = 0.06)",
       "remap=on (Chan Eq. 4.1) shrinks the penumbra to nothing at the contact",
       "contact",
       400,
       300,
       {{"param", "width=0.06"}},
       "modern.smoothies",
       "modern.smoothies",
       {{"param", "remap=off"}},
       {},
       {88, 144, 144, 90, 3}},
      {"pcss-few-taps",
       "PCSS with few filter taps",
       "Percentage-closer soft shadows (ours, after Fernando 2005) filter each pixel over a "
       "region as wide as its estimated penumbra. With a light of radius 0.5 that region spans "
       "many texels, and 4 taps at fixed offsets show it: the penumbra is a few shifted copies of "
       "the hard shadow, not a ramp.",
       "filter-taps=4: four shadow-map comparisons per pixel over the penumbra (light radius 0.5)",
       "the default 36 taps: a smoother ramp with the same width",
       "brabec",
       400,
       300,
       {{"param", "light-radius=0.5"}},
       "modern.pcss",
       "modern.pcss",
       {{"param", "filter-taps=4"}},
       {},
       {80, 95, 260, 125, 2}},
      {"woo-thin-caster",
       "Woo's midpoint fails on a thin caster",
       "Woo's map stores the midpoint between the nearest and the second-nearest surface, "
       "which replaces the polygon offset where objects are thick. The squares are boxes 0.02 "
       "thick: the midpoint lies 0.01 under the lit top, less than the depth one 128 x 128 "
       "texel spans across the tilted square, so the tilted square shadows itself in stripes "
       "as if there were no offset (the flat squares, facing the light, stay clean).",
       "the technique: legacy.woo (midpoint map, no polygon offset) on a 128 x 128 map",
       "legacy.hw with its polygon offset on the same map",
       "squares",
       400,
       300,
       {{"shadow-map", "128"}},
       "legacy.woo",
       "legacy.hw",
       {},
       {},
       {240, 85, 80, 60, 4}},
      {"gems-dither",
       "Dithered PCF: the 4-sample pattern",
       "GPU Gems §11.4 takes 4 of the 16 lookups per pixel, chosen by the pixel's screen "
       "position: the penumbra becomes a regular 2 x 2 dither pattern instead of a smooth "
       "ramp (GPU Gems Figs. 11-7 and 11-8).",
       "samples=4 (dithered)",
       "samples=16 filters every pixel with the whole 4 x 4 footprint",
       "cylinder",
       400,
       300,
       {{"shadow-map", "256"}},
       "modern.gems16",
       "modern.gems16",
       {{"param", "samples=4"}},
       {},
       {180, 165, 110, 70, 4}},
  };
  return kEntries;
}

std::vector<std::string> galleryRenderArguments(const GalleryEntry& e, bool wrongSide) {
  std::vector<std::string> a = {
      "--scene",     e.scene,
      "--technique", wrongSide ? e.wrongTechnique : e.rightTechnique,
      "--size",      std::to_string(e.width) + "x" + std::to_string(e.height)};
  for (const auto& [k, v] : e.common) a.insert(a.end(), {"--" + k, v});
  for (const auto& [k, v] : wrongSide ? e.wrong : e.right) a.insert(a.end(), {"--" + k, v});
  return a;
}

namespace {

std::string pictureName(const GalleryEntry& e, bool wrongSide, bool closeup) {
  return e.id + (wrongSide ? "-wrong" : "-right") + (closeup ? "-closeup" : "") + ".png";
}

// Percent-encodes a query value, leaving the characters a reader wants to see: letters, digits,
// "-._~" and the "=", "," and ":" of "offset-factor=0" and "-7,1.6,3" (RFC 3986 allows them in
// a query).
std::string queryValue(const std::string& text) {
  static const char* kHex = "0123456789ABCDEF";
  std::string out;
  for (unsigned char c : text) {
    if (std::isalnum(c) || std::string("-._~=,:").find(char(c)) != std::string::npos) {
      out += char(c);
    } else {
      out += '%';
      out += kHex[c >> 4];
      out += kHex[c & 15];
    }
  }
  return out;
}

// Options the lab keeps per side (a-shadow-map, b-param, ...) and those it keeps once.
bool perSide(const std::string& key) {
  return key == "shadow-map" || key == "filter" || key == "precision" || key == "param";
}

// A fraction with at most 4 decimals, as lab/web/lab.js writes the centre back.
std::string centreText(double v) {
  constexpr double kDecimals = 1e4;
  std::ostringstream s;
  s << std::round(v * kDecimals) / kDecimals;
  return s.str();
}

// The scene, technique and options of one picture, parsed as `shadowlab render` parses them.
struct Picture {
  cli::Args args;
  std::string command;
};

Picture parsePicture(const GalleryEntry& e, bool wrongSide) {
  std::vector<std::string> argv = {"shadowlab", "render"};
  for (const std::string& a : galleryRenderArguments(e, wrongSide)) argv.push_back(a);
  argv.insert(argv.end(), {"--out", pictureName(e, wrongSide, false)});
  std::vector<char*> pointers;
  for (std::string& a : argv) pointers.push_back(a.data());
  Picture p;
  p.args = cli::parse(int(pointers.size()), pointers.data());
  p.command = shellJoin(argv);
  return p;
}

Image renderPicture(const Picture& p) {
  Scene scene = loadScene(p.args.value("scene").value_or(kDefaultScene));
  cli::viewScene(p.args, scene);
  const Technique& t = findTechnique(p.args.required("technique"));
  RenderParams params = cli::renderParams(p.args);
  rejectIgnoredOptions(t, cli::givenCommonOptions(p.args));
  const Frame frame = renderTechnique(t, scene, params);
  if (frame.color.empty() || !allFinite(frame.color))
    throw GlError(t.name + ": no finite image to show in the gallery");
  return frame.color;
}

// The close-up window in the bottom-left-origin coordinates of core/base/image.h crop.
Image closeupOf(const Image& image, const GalleryWindow& w) {
  return magnifyNearest(toRgb(crop(image, w.x, image.height - w.y - w.height, w.width, w.height)),
                        w.magnify);
}

Image framedPicture(const Image& image, const GalleryWindow& w) {
  Image rgb = toRgb(image);
  drawFrame(rgb, w.x, image.height - w.y - w.height, w.width, w.height, kCloseupFrame);
  return rgb;
}

std::string optionsText(const std::vector<RenderOption>& options) {
  std::string out;
  for (const auto& [k, v] : options) {
    if (!out.empty()) out += ' ';
    out += "--" + k + " " + v;
  }
  return out.empty() ? "(the technique's defaults)" : out;
}

json entryJson(const GalleryEntry& e, const std::string& labUrl) {
  const auto side = [&](bool wrongSide) {
    json options = json::array();
    for (const std::string& a : galleryRenderArguments(e, wrongSide)) options.push_back(a);
    return json{{"technique", wrongSide ? e.wrongTechnique : e.rightTechnique},
                {"arguments", options},
                {"command", galleryRenderCommand(e, wrongSide)},
                {"image", pictureName(e, wrongSide, false)},
                {"closeup", pictureName(e, wrongSide, true)}};
  };
  return {{"id", e.id},
          {"title", e.title},
          {"parameter", e.parameter},
          {"lab_query", galleryLabQuery(e)},
          {"lab", labUrl + "?" + galleryLabQuery(e)},
          {"closeup",
           {{"x", e.closeup.x},
            {"y", e.closeup.y},
            {"width", e.closeup.width},
            {"height", e.closeup.height},
            {"magnify", e.closeup.magnify}}},
          {"wrong", side(true)},
          {"right", side(false)}};
}

std::string pageHtml(const std::vector<GalleryEntry>& entries, const std::string& labUrl,
                     const std::string& command) {
  std::ostringstream h;
  h << "<!doctype html>\n<html lang=en>\n<head>\n<meta charset=utf-8>\n"
       "<title>shadowlab — artefact gallery</title>\n<style>\n"
       "body{font:15px/1.45 system-ui,sans-serif;max-width:1100px;margin:1em auto;padding:0 1em;"
       "color:#222}\n"
       "section.artefact{border-top:1px solid #ccc;padding:.6em 0 1em}\n"
       ".pair{display:flex;flex-wrap:wrap;gap:1em}\n"
       ".pair figure{margin:0;flex:1 1 420px}\n"
       ".pair img{max-width:100%;image-rendering:pixelated;border:1px solid #999}\n"
       "figcaption{font-size:.9em;color:#444}\n"
       "code{font-size:.85em;background:#f2f2ec;padding:.1em .25em;word-break:break-all}\n"
       ".wrong h4{color:#b00}.right h4{color:#070}h4{margin:.2em 0;min-height:2.9em}\n"
       // Print: one artefact a page at most, its four pictures small enough to share it.
       "@page{margin:1.2cm}\n"
       "@media print{body{max-width:none;font-size:9pt;line-height:1.25}"
       "section.artefact{break-inside:avoid;padding:.3em 0}.pair{flex-wrap:nowrap}"
       ".pair figure{flex:1 1 50%}.pair img{max-height:4cm;width:auto}h4{min-height:0}"
       "p{margin:.3em 0}a{color:inherit;text-decoration:none}}\n"
       "</style>\n</head>\n<body>\n<h1>Shadow-mapping artefacts</h1>\n"
       "<p>Each artefact as a pair of pictures rendered by shadowlab (OSMesa): the wrong one, "
       "and the same frame with the one parameter that causes it changed. The red frame marks "
       "the close-up below each picture. Each picture names the <code>shadowlab render</code> "
       "command that re-makes it; <em>open in the lab</em> opens the live lab "
       "(<code>shadowlab serve</code>, at "
    << htmlEscape(labUrl)
    << ") with the wrong picture as A, the right one as B and the close-up zoomed; drag the "
       "A/B wipe to compare, and move the parameter's slider to watch the artefact come and "
       "go.</p>\n<ol>\n";
  for (const GalleryEntry& e : entries)
    h << "<li><a href=\"#" << htmlEscape(e.id) << "\">" << htmlEscape(e.title) << "</a></li>\n";
  h << "</ol>\n";
  for (const GalleryEntry& e : entries) {
    h << "<section class=artefact id=\"" << htmlEscape(e.id) << "\">\n<h2>" << htmlEscape(e.title)
      << "</h2>\n<p>" << htmlEscape(e.shows) << "</p>\n<p><b>Cause:</b> " << htmlEscape(e.parameter)
      << ". <b>Right:</b> " << htmlEscape(e.fix) << ". <a class=lab href=\""
      << htmlEscape(labUrl + "?" + galleryLabQuery(e)) << "\">open in the lab</a></p>\n"
      << "<div class=pair>\n";
    for (bool wrongSide : {true, false}) {
      const std::string technique = wrongSide ? e.wrongTechnique : e.rightTechnique;
      h << "<figure class=" << (wrongSide ? "wrong" : "right") << "><h4>"
        << (wrongSide ? "wrong: " : "right: ") << htmlEscape(technique) << " "
        << htmlEscape(optionsText(wrongSide ? e.wrong : e.right)) << "</h4>\n<img src=\""
        << pictureName(e, wrongSide, false) << "\" width=" << e.width << " height=" << e.height
        << " alt=\"" << htmlEscape(e.title + (wrongSide ? ", wrong" : ", right"))
        << "\">\n<img src=\"" << pictureName(e, wrongSide, true)
        << "\" width=" << e.closeup.width * e.closeup.magnify
        << " height=" << e.closeup.height * e.closeup.magnify << " alt=\"close-up, "
        << e.closeup.magnify << "x\">\n<figcaption>close-up magnified " << e.closeup.magnify
        << "x. <code>" << htmlEscape(galleryRenderCommand(e, wrongSide))
        << "</code></figcaption></figure>\n";
    }
    h << "</div>\n</section>\n";
  }
  json data = json::array();
  for (const GalleryEntry& e : entries) data.push_back(entryJson(e, labUrl));
  // Inside <script> only "</" could end the element early: written "<\\/" (the same JSON).
  std::string text;
  for (char c : data.dump(1)) {
    if (c == '/' && !text.empty() && text.back() == '<') text += '\\';
    text += c;
  }
  h << "<p>Made by <code>" << htmlEscape(command) << "</code>, shadowlab "
    << htmlEscape(buildCommit()) << ".</p>\n<script type=\"application/json\" id=gallery-data>\n"
    << text << "\n</script>\n</body>\n</html>\n";
  return h.str();
}

}  // namespace

std::string galleryRenderCommand(const GalleryEntry& e, bool wrongSide) {
  std::vector<std::string> argv = {"shadowlab", "render"};
  for (const std::string& a : galleryRenderArguments(e, wrongSide)) argv.push_back(a);
  argv.insert(argv.end(), {"--out", pictureName(e, wrongSide, false)});
  return shellJoin(argv);
}

std::string galleryLabQuery(const GalleryEntry& e) {
  std::vector<std::pair<std::string, std::string>> q = {
      {"scene", e.scene},
      {"size", std::to_string(e.width) + "x" + std::to_string(e.height)},
      {"a", e.wrongTechnique},
      {"b", e.rightTechnique}};
  for (const auto& [k, v] : e.common) {
    if (perSide(k)) {
      q.emplace_back("a-" + k, v);
      q.emplace_back("b-" + k, v);
    } else {
      q.emplace_back(k, v);
    }
  }
  for (bool wrongSide : {true, false})
    for (const auto& [k, v] : wrongSide ? e.wrong : e.right) {
      if (!perSide(k)) throw InputError("gallery entry " + e.id + ": --" + k + " is not per side");
      q.emplace_back(std::string(wrongSide ? "a-" : "b-") + k, v);
    }
  const GalleryWindow& w = e.closeup;
  q.emplace_back("zoom", std::to_string(w.magnify));
  q.emplace_back("center", centreText((w.x + w.width / 2.0) / e.width) + "," +
                               centreText((w.y + w.height / 2.0) / e.height));
  std::string out;
  for (const auto& [k, v] : q) out += (out.empty() ? "" : "&") + k + "=" + queryValue(v);
  return out;
}

Image renderGalleryPicture(const GalleryEntry& e, bool wrongSide) {
  return renderPicture(parsePicture(e, wrongSide));
}

int writeGallery(const std::string& dir, const std::string& labUrl) {
  const std::vector<GalleryEntry>& entries = galleryEntries();
  OutputSet outputs;
  const std::string target = (fs::path(dir) / "gallery").string();
  const std::string temporary = outputs.addDirectory("--out", target);
  struct Rendered {
    std::string file;
    Image image;
    Provenance provenance;
  };
  std::vector<Rendered> files;
  for (const GalleryEntry& e : entries)
    for (bool wrongSide : {true, false}) {
      const Picture p = parsePicture(e, wrongSide);
      const Image image = renderPicture(p);
      json parameters = json::object();
      for (const auto& [key, values] : p.args.options) parameters[key] = values;
      const Provenance provenance{p.command, parameters.dump()};
      files.push_back(
          {pictureName(e, wrongSide, false), framedPicture(image, e.closeup), provenance});
      files.push_back({pictureName(e, wrongSide, true), closeupOf(image, e.closeup), provenance});
    }
  const std::string html = pageHtml(entries, labUrl, commandLine());
  outputs.beginWriting();
  for (const Rendered& r : files)
    writePng((fs::path(temporary) / r.file).string(), r.image, 8, r.provenance);
  writeFileAtomically((fs::path(temporary) / "index.html").string(),
                      [&](std::ostream& out) { out << html; });
  outputs.commit();
  return int(entries.size());
}

int runGalleryCommand(const cli::Args& args) {
  const std::string out = args.required("out");
  const std::string lab = args.value("lab").value_or(kDefaultLabUrl);
  if (lab.rfind("http://", 0) != 0 && lab.rfind("https://", 0) != 0)
    throw InputError("--lab must be an http:// or https:// address, got '" + lab + "'");
  const int n = writeGallery(out, lab);
  std::cout << "wrote " << (fs::path(out) / "gallery" / "index.html").string() << " (" << n
            << " artefacts, " << 4 * n << " pictures)" << std::endl;
  return 0;
}

}  // namespace sl::figures
