// interpose/frame_files.cpp — the frame session of run-legacy's grabbers (frame_files.h).
#include "interpose/frame_files.h"

#include <cstdio>
#include <cstdlib>
#include <sstream>

namespace sl::interpose {
namespace {
constexpr unsigned char kEscape = 27;
constexpr int kFrameNameDigits = 3;  // DIR/NNN.png
}  // namespace

FrameSession& FrameSession::get() {
  static FrameSession s = [] {
    FrameSession made;
    if (const char* d = std::getenv("SHADOWLAB_FRAMES_DIR")) made.dir = d;
    if (const char* k = std::getenv("SHADOWLAB_KEYS")) {
      std::istringstream words(k);
      std::string w;
      while (words >> w) {
        if (w == "esc")
          made.keys.push_back(kEscape);
        else if (w == "space")
          made.keys.push_back(' ');
        else
          made.keys.push_back(static_cast<unsigned char>(w[0]));
        made.keyNames.push_back(w);
      }
    }
    return made;
  }();
  return s;
}

bool FrameSession::write(const Image& rgb, const char* source) {
  char name[32];
  std::snprintf(name, sizeof name, "%0*d.png", kFrameNameDigits, frame);
  const std::string event =
      frame == 0 ? std::string("start-up") : "key " + keyNames[size_t(frame - 1)];
  Provenance provenance;
  if (const char* c = std::getenv("SHADOWLAB_FRAMES_COMMAND")) provenance.command = c;
  provenance.parameters = "{\"frame\":" + std::to_string(frame) + ",\"after\":\"" + event +
                          "\",\"buffer\":\"" + source + "\"}";
  bool ok = true;
  try {
    writePng(dir + "/" + name, rgb, 8, provenance);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "shadowlab frames: %s\n", e.what());
    ok = false;
  }
  ++frame;
  awaiting = false;
  if (nextKey >= keys.size()) done = true;
  return ok;
}

int FrameSession::takeKey() {
  if (nextKey >= keys.size()) return -1;
  return int(nextKey++);
}

}  // namespace sl::interpose
