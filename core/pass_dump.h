// core/pass_dump.h — what `shadowlab render --dump-passes DIR` writes (issue 18 item 1):
//
//   DIR/01-light-depth.png, 02-..., 03a-..., 03b-...   every intermediate buffer, in pipeline order
//   DIR/passes.json                                    what each file shows, pass by pass
//   DIR/index.html                                     the same as a page (no network needed)
//
// File names: a technique names its buffers "<pass>-<what>" (core/pass_capture.h); the dump
// writes the pass number with two digits and, when a pass has several images, a letter in the
// order they were made ("05a-mask-after-colour-table", "05b-alpha-after-colour-matrix"), so that
// `ls` lists them in pipeline order. A buffer with alpha (packed maps: four depths in R, G, B,
// A) is written opaque (alpha shown as 1), followed by one grey PNG per channel named
// "<file>-ch1-R.png" ... "-ch4-A.png".
//
// passes.json: {"technique", "paper", "scene", "parameters", "frame_ms", "counters",
//   "passes": [{"number", "name", "milliseconds", "timings": [{"name", "milliseconds"}],
//               "files": [...]}],
//   "images": [{"file", "pass", "pass_name", "caption", "width", "height", "channels",
//               "channel" and "of" for the grey panel of one channel}]}
// A pass is every Frame::passes entry with one number (the phases of a 4x4 footprint are
// several entries); its "milliseconds" is their sum, "timings" lists them.
// The times are those of this one render (core/technique.h PassTimer), not a median.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "core/provenance.h"
#include "core/technique.h"

namespace sl {

// What made the dump, for passes.json and index.html.
struct PassDumpHeader {
  std::string technique;
  std::string paper;
  std::string scene;
  nlohmann::json parameters;  // the options and --params as they took effect
};

// One file of a dump.
struct PassDumpImage {
  std::string file;  // "03b-mask-after-colour-table-rgba.png"
  int pass = -1;     // the pass number of its name, -1 when it has none
  std::string caption;
  Image image;          // as written (alpha forced to 1, or one channel)
  std::string channel;  // "R", "G", "B", "A", "L" for a channel of `of`; empty otherwise
  std::string of;       // the file this is a channel of
};

// The pass number a buffer or pass name starts with ("3a-projected..." -> 3, "1 depth" -> 1),
// or -1.
int passNumberOf(const std::string& name);

// Throws InputError (exit 2) naming the technique when the frame holds no intermediate buffer:
// a dump is never an empty folder. Call before any output is written.
void requireSomethingToDump(const Frame& frame, const std::string& technique);

// The files of a dump, in order (requireSomethingToDump first).
std::vector<PassDumpImage> planPassDump(const Frame& frame, const std::string& technique);

nlohmann::json passesJson(const Frame& frame, const PassDumpHeader& header,
                          const std::vector<PassDumpImage>& images);
// A self-contained page: the technique, then each pass with its time and its images at their
// natural aspect ratio (sized by width only), each with its caption.
std::string indexHtml(const nlohmann::json& passes);

// Writes the PNGs, passes.json and index.html into `directory` (which exists; render gives the
// temporary directory of core/output_files.h OutputSet). Throws InputError as planPassDump.
void writePassDump(const std::string& directory, const Frame& frame, const PassDumpHeader& header,
                   const Provenance& provenance);

}  // namespace sl
