// figures/gallery.h — the artefact gallery: each classic shadow-mapping artefact as a wrong/right
// picture pair rendered by the real renderer, the one parameter that causes it, the
// `shadowlab render` command of each picture, and a link that opens the live lab
// (`shadowlab serve`, lab/web/) in exactly that state: A = the wrong picture, B = the right one,
// zoomed onto the close-up.
//
// The entries are declared once (galleryEntries(), figures/gallery.cpp). writeGallery() writes
//   DIR/gallery/index.html        the gallery (offline; every link but the lab's relative), with
//                                 the entries as JSON in <script id=gallery-data> (the browser
//                                 test opens every lab link from it)
//   DIR/gallery/<id>-wrong.png    the pictures, and <id>-wrong-closeup.png, <id>-right*.png
// `shadowlab gallery --out DIR` calls it.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "core/base/image.h"
#include "registry/cli.h"

namespace sl::figures {

// One option of a `shadowlab render` command as the CLI spells it: {"shadow-map", "128"},
// {"param", "offset-factor=0"}, {"light-position", "-7,1.6,3"}.
using RenderOption = std::pair<std::string, std::string>;

// A window of the picture, in pixels from its top-left corner (as an image viewer counts).
struct GalleryWindow {
  int x = 0, y = 0, width = 0, height = 0;
  int magnify = 3;
};

struct GalleryEntry {
  std::string id;         // file names and anchors: "acne"
  std::string title;      // "Shadow acne"
  std::string shows;      // what the wrong picture shows, and why
  std::string parameter;  // the one parameter that causes it: "polygon offset (offset-factor,
                          // offset-units)"
  std::string fix;        // what the right picture changes
  std::string scene;
  int width = 400, height = 300;
  std::vector<RenderOption> common;  // options both pictures share (lab: both sides, or global)
  std::string wrongTechnique, rightTechnique;
  std::vector<RenderOption> wrong, right;  // the options that differ
  GalleryWindow closeup;                   // where the artefact is
};

const std::vector<GalleryEntry>& galleryEntries();

// The arguments of `shadowlab render` for one picture, without --out: "--scene", S, "--technique",
// T, "--size", WxH, then the common options, then the side's.
std::vector<std::string> galleryRenderArguments(const GalleryEntry& e, bool wrongSide);
// The whole command, with --out <id>-wrong.png or <id>-right.png.
std::string galleryRenderCommand(const GalleryEntry& e, bool wrongSide);
// The lab page's query for the entry (lab/web/lab.js readState: scene, size, a, b, a-/b-
// shadow-map, filter, precision and param, light-position, orbit, zoom, center), without "?".
std::string galleryLabQuery(const GalleryEntry& e);

// One picture, rendered as `shadowlab render` with galleryRenderArguments renders it (the
// arguments parsed by the CLI's own parser). The colour image, bottom-left origin.
Image renderGalleryPicture(const GalleryEntry& e, bool wrongSide);

// The address of `shadowlab serve` with its defaults.
constexpr const char* kDefaultLabUrl = "http://127.0.0.1:8080/";

// Renders every entry and writes DIR/gallery/ as a whole (core/base/output_files.h). Throws
// InputError for bad input, GlError for a GL failure. Returns the number of entries.
int writeGallery(const std::string& dir, const std::string& labUrl = kDefaultLabUrl);

// `shadowlab gallery --out DIR [--lab URL]`.
int runGalleryCommand(const cli::Args& args);

}  // namespace sl::figures
