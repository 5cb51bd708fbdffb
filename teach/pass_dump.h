// teach/pass_dump.h — what `shadowlab render --dump-passes DIR` writes:
//
//   DIR/01-light-depth.png, 02-..., 03a-..., 03b-...   every intermediate buffer, in pipeline order
//   DIR/passes.json                                    what each file shows, pass by pass
//   DIR/index.html                                     the same as a page (no network needed)
//
// File names: a technique names its buffers "<pass>-<what>" (core/technique/pass_capture.h); the
// dump writes the pass number with two digits and, when a pass has several images, a letter in the
// order they were made ("05a-mask-after-colour-table", "05b-alpha-after-colour-matrix"), so that
// `ls` lists them in pipeline order. A buffer with alpha (packed maps: four depths in R, G, B,
// A) is written opaque (alpha shown as 1), followed by one grey PNG per channel named
// "<file>-ch1-R.png" ... "-ch4-A.png", each with a value legend. A packed map (PassImage::
// centreChannel, Brabec–Seidel Fig. 5) shows its channels on one depth scale and adds, per other
// channel, that channel minus the centre one on a diverging scale ("<file>-ch1-R-minus-A.png"):
// the one-texel shift between the packed neighbours appears at every depth edge.
//
// passes.json: {"technique", "paper", "scene", "parameters", "frame_ms", "counters",
//   "passes": [{"id", "number", "name", "milliseconds", "timings": [{"name", "milliseconds"}],
//               "section", "source": {"file", "function"},
//               "state": [{"group", "text", "before_pass" (true when set before the timer)}],
//               "key_state": [words of the lines that matter (PassSpec::keyState)],
//               "glsl": [{"file", "first_line", "last_line", "marker", "title"}],
//               "replaces": ["legacy.X pass ID name"], "files": [...]}],
//   "images": [{"file", "pass", "pass_id", "pass_name", "caption", "width", "height", "channels",
//               "channel" and "of" for the grey panel of one channel, "view",
//               "legend": {"kind", "low", "high", "note"}}]}
// "section" and "source" come from the pass's PassTimer (core/technique/technique.h), "state" from
// the GL trace (core/gl/gl_trace.h), "glsl" and "replaces" from the `// @pass` markers of the
// shaders the pass names (core/gl/shaders.h), "replaces" limited to the legacy twin in the header:
// each `// @replaces legacy.X ID` of those markers, named from the twin's pass table
// ("legacy.fast-pcf pass 6a accumulate"), in the order of that table.
// A pass is every Frame::passes entry with one id (core/technique/pass_table.h; the phases of a 4x4
// footprint are several entries); its "milliseconds" is their sum, "timings" lists them. "id" is
// the pass's id in the technique's table, "number" the number it starts with (-1 for "mesh").
// The times are those of this one render (core/technique/technique.h PassTimer), not a median.
#pragma once

#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/base/provenance.h"
#include "core/technique/pass_table.h"
#include "core/technique/technique.h"

namespace sl {

// What made the dump, for passes.json and index.html.
struct PassDumpHeader {
  std::string technique;
  std::string paper;
  std::string scene;
  nlohmann::json parameters;  // the options and --params as they took effect
  std::string twin;           // a modern technique's legacy twin (registry/twins.h), or ""
  // The twin's pass table (its Technique::passes): names the legacy passes a modern pass
  // replaces; null without a twin.
  const PassTable* twinPasses = nullptr;
};

// How a file's values map to grey or colour, for the legend beside it.
struct ValueLegend {
  std::string kind;  // "grey": low black .. high white; "diverging": low blue, 0 white, high red
  double low = 0.0;
  double high = 1.0;
  std::string note;  // "1 (far, nothing drawn) = white", "clamped beyond the ends"
};

// One file of a dump.
struct PassDumpImage {
  std::string file;  // "03b-mask-after-colour-table-rgba.png"
  int pass = -1;     // the pass number of its name, -1 when it has none
  std::string caption;
  Image image;          // as written (alpha forced to 1, or one channel)
  std::string channel;  // "R", "G", "B", "A", "L" for a channel of `of`; empty otherwise
  std::string of;       // the file this is a channel of
  std::string view;     // "channel", "minus centre" (channel minus the centre channel), or ""
  std::optional<ValueLegend> legend;
  std::string passId{};  // the id of its pass in the technique's pass table ("5c")
};

// The number a pass-table id starts with ("3a" -> 3, "12" -> 12), which orders the passes in the
// dump, or -1 for a named id ("mesh").
int passIdNumber(const std::string& id);

// Throws InputError (exit 2) naming the technique when the frame holds no intermediate buffer:
// a dump is never an empty folder. Call before any output is written.
void requireSomethingToDump(const Frame& frame, const std::string& technique);

// The files of a dump, in order (requireSomethingToDump first).
std::vector<PassDumpImage> planPassDump(const Frame& frame, const std::string& technique);

nlohmann::json passesJson(const Frame& frame, const PassDumpHeader& header,
                          const std::vector<PassDumpImage>& images);
// A "replaces" entry of passes.json ({"technique", "pass", "name"}: the id of a legacy twin's
// pass and its name there) as a page shows it: "legacy.fast-pcf pass 6a accumulate".
std::string replacedPassText(const nlohmann::json& replaced);
// A self-contained page: the technique, then each pass with its time and its images at their
// natural aspect ratio (sized by width only), each with its caption.
std::string indexHtml(const nlohmann::json& passes);

// Writes the PNGs, passes.json and index.html into `directory` (which exists; render gives the
// temporary directory of core/base/output_files.h OutputSet). Throws InputError as planPassDump.
void writePassDump(const std::string& directory, const Frame& frame, const PassDumpHeader& header,
                   const Provenance& provenance);

}  // namespace sl
