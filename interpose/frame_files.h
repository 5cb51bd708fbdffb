// interpose/frame_files.h — what run-legacy's two frame grabbers share (libshadowlab-frames.so
// on freeglut, libshadowlab-glut.so on OSMesa): the keys to press and the frames to write.
//
// Environment, set by `shadowlab run-legacy`: SHADOWLAB_FRAMES_DIR (where NNN.png go),
// SHADOWLAB_KEYS (space-separated: one character each, or esc / space),
// SHADOWLAB_FRAMES_COMMAND (the command line, for each PNG's provenance).
#pragma once

#include <string>
#include <vector>

#include "core/base/image.h"

namespace sl::interpose {

struct FrameSession {
  std::string dir;                    // empty: no frames asked for
  std::vector<unsigned char> keys;    // the keys, in order
  std::vector<std::string> keyNames;  // as given
  size_t nextKey = 0;                 // the next key to deliver
  int frame = 0;                      // the next frame's number
  bool awaiting = true;               // the next displayed frame is written
  bool done = false;                  // every frame asked for is written

  // The session of this process, from the environment.
  static FrameSession& get();
  bool active() const { return !dir.empty(); }
  // Writes `rgb` (3 channels, rows bottom-up) as DIR/NNN.png with what made it, then moves
  // on: awaiting becomes false, and done is set after the last frame. `source` names the
  // buffer read ("front", "back", "osmesa buffer"). Returns false (message on stderr) when
  // the file cannot be written.
  bool write(const Image& rgb, const char* source);
  // The index of the key to deliver next, or -1 when none is left (then the run is done).
  // Whoever delivers it sets `awaiting` just before the program's callback runs.
  int takeKey();
};

}  // namespace sl::interpose
