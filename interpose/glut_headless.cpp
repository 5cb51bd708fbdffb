// interpose/glut_headless.cpp — libshadowlab-glut.so: the GLUT 3.x surface the Red Book's
// programs use, on an OSMesa context and no window system, for `shadowlab run-legacy
// --backend osmesa|reference`. Preloaded before the program's freeglut, so its glut* calls
// land here; the GL (Debian's OSMesa with libshadowlab-imaging.so, or the reference Mesa
// 7.8.2) is preloaded after it and found at run time (dlsym RTLD_DEFAULT).
//
// The main loop is deterministic: a redisplay runs first, then a pending key, then the
// earliest timer (the clock jumps to it: GLUT_ELAPSED_TIME is virtual), then the idle
// callback. One window, single-buffered (OSMesa has one colour buffer: glutSwapBuffers shows
// it). Frames and keys as in frame_files.h; after the last frame the program exits 0, as
// freeglut does when its window is closed. Written from the GLUT 3 specification's
// description of each call (Kilgard 1996), not from any GLUT's source. The shapes
// (glutSolid*/glutWire*) are in glut_shapes.cpp.
#include "interpose/glut_headless.h"

#include <GL/freeglut_std.h>
#include <GL/gl.h>
#include <GL/osmesa.h>
#include <dlfcn.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "interpose/frame_files.h"

#define SL_EXPORT extern "C" __attribute__((visibility("default")))

namespace sl::interpose {

void fatal(const std::string& message) {
  std::fprintf(stderr, "libshadowlab-glut: %s\n", message.c_str());
  std::exit(kExitGlFailure);
}

namespace {

constexpr int kDefaultWindowSide = 300;  // GLUT 3 spec, glutInitWindowSize: 300 x 300
constexpr int kScreenWidth = 1280;       // the screen GLUT_SCREEN_WIDTH/HEIGHT report
constexpr int kScreenHeight = 1024;
constexpr int kDepthBits = 24;  // what the Red Book programs ask with GLUT_DEPTH
constexpr int kStencilBits = 8;
constexpr int kAccumBits = 16;                // GLUT_ACCUM
constexpr int kMaxIdleWithoutFrame = 100000;  // idle calls that show nothing: a stalled program
constexpr float kByteMax = 255.0f;

struct Timer {
  long due;  // ms of the virtual clock
  long order;
  void (*fn)(int);
  int value;
};

struct Glut {
  unsigned displayMode = GLUT_RGBA | GLUT_SINGLE;
  int initWidth = kDefaultWindowSide, initHeight = kDefaultWindowSide;
  int initX = -1, initY = -1;
  int window = 0;  // 1 once created (one window)
  int width = 0, height = 0;
  OSMesaContext context = nullptr;
  std::vector<uint8_t> buffer;
  void (*display)() = nullptr;
  void (*reshape)(int, int) = nullptr;
  void (*keyboard)(unsigned char, int, int) = nullptr;
  void (*idle)() = nullptr;
  bool redisplay = false;
  bool reshapePending = false;
  long clock = 0;  // ms
  long timerOrder = 0;
  std::vector<Timer> timers;
  int nextMenu = 1;
};

Glut& glut() {
  static Glut g;
  return g;
}

void makeWindowCurrent() {
  Glut& g = glut();
  static const auto makeCurrent = gl<decltype(&::OSMesaMakeCurrent)>("OSMesaMakeCurrent");
  g.buffer.assign(size_t(g.width) * g.height * 4, 0);
  if (!makeCurrent(g.context, g.buffer.data(), GL_UNSIGNED_BYTE, g.width, g.height))
    fatal("OSMesaMakeCurrent failed");
}

// The window as shown: the OSMesa buffer (rows bottom-up, RGBA) after glFinish.
void frameShown() {
  FrameSession& s = FrameSession::get();
  if (!s.active() || !s.awaiting || s.done) return;
  SL_GL(glFinish);
  glFinish();
  Glut& g = glut();
  Image rgb(g.width, g.height, 3);
  for (size_t p = 0; p < size_t(g.width) * g.height; ++p)
    for (int c = 0; c < 3; ++c) rgb.data[p * 3 + c] = float(g.buffer[p * 4 + c]) / kByteMax;
  s.write(rgb, "osmesa buffer");
}

void callDisplay() {
  Glut& g = glut();
  g.redisplay = false;
  if (g.display == nullptr) fatal("the program set no display callback");
  g.display();
  frameShown();  // single-buffered, or double-buffered without a swap: the buffer as left
}

void callReshape() {
  Glut& g = glut();
  g.reshapePending = false;
  if (g.reshape != nullptr) {
    g.reshape(g.width, g.height);
  } else {  // GLUT 3 spec 7.2: the default reshape sets the viewport to the window
    SL_GL(glViewport);
    glViewport(0, 0, g.width, g.height);
  }
}

bool deliverKey() {
  FrameSession& s = FrameSession::get();
  if (!s.active() || s.awaiting || s.done) return false;
  const int key = s.takeKey();
  if (key < 0) return false;
  Glut& g = glut();
  if (g.keyboard == nullptr)
    fatal("the program has no keyboard callback for key '" + s.keyNames[size_t(key)] + "'");
  s.awaiting = true;
  g.keyboard(s.keys[size_t(key)], g.width / 2, g.height / 2);
  return true;
}

}  // namespace
}  // namespace sl::interpose

using sl::interpose::glut;

// ---- initialisation and the window ----
SL_EXPORT void glutInit(int*, char**) {}
SL_EXPORT void glutInitDisplayMode(unsigned int mode) { glut().displayMode = mode; }
SL_EXPORT void glutInitDisplayString(const char*) {}
SL_EXPORT void glutInitWindowSize(int w, int h) {
  if (w > 0 && h > 0) {
    glut().initWidth = w;
    glut().initHeight = h;
  }
}
SL_EXPORT void glutInitWindowPosition(int x, int y) {
  glut().initX = x;
  glut().initY = y;
}

SL_EXPORT int glutCreateWindow(const char*) {
  auto& g = glut();
  if (g.window != 0) sl::interpose::fatal("one window only (the program made a second)");
  static const auto create =
      sl::interpose::gl<decltype(&::OSMesaCreateContextExt)>("OSMesaCreateContextExt");
  const bool depth = (g.displayMode & GLUT_DEPTH) != 0,
             stencil = (g.displayMode & GLUT_STENCIL) != 0,
             accum = (g.displayMode & GLUT_ACCUM) != 0;
  g.context = create(OSMESA_RGBA, depth ? sl::interpose::kDepthBits : 0,
                     stencil ? sl::interpose::kStencilBits : 0,
                     accum ? sl::interpose::kAccumBits : 0, nullptr);
  if (g.context == nullptr) sl::interpose::fatal("OSMesaCreateContextExt failed");
  g.width = g.initWidth;
  g.height = g.initHeight;
  sl::interpose::makeWindowCurrent();
  g.window = 1;
  g.reshapePending = true;
  g.redisplay = true;
  return g.window;
}
SL_EXPORT int glutCreateSubWindow(int, int, int, int, int) {
  sl::interpose::fatal("sub-windows are not provided");
}
SL_EXPORT void glutDestroyWindow(int) {}
SL_EXPORT void glutSetWindow(int) {}
SL_EXPORT int glutGetWindow() { return glut().window; }
SL_EXPORT void glutSetWindowTitle(const char*) {}
SL_EXPORT void glutSetIconTitle(const char*) {}
SL_EXPORT void glutPositionWindow(int, int) {}
SL_EXPORT void glutShowWindow() {}
SL_EXPORT void glutHideWindow() {}
SL_EXPORT void glutIconifyWindow() {}
SL_EXPORT void glutFullScreen() {}
SL_EXPORT void glutSetCursor(int) {}
SL_EXPORT void glutWarpPointer(int, int) {}
SL_EXPORT void glutIgnoreKeyRepeat(int) {}
SL_EXPORT void glutSetKeyRepeat(int) {}
SL_EXPORT void glutReshapeWindow(int w, int h) {
  auto& g = glut();
  if (w <= 0 || h <= 0 || (w == g.width && h == g.height)) return;
  g.width = w;
  g.height = h;
  sl::interpose::makeWindowCurrent();
  g.reshapePending = true;
  g.redisplay = true;
}
SL_EXPORT void glutPostRedisplay() { glut().redisplay = true; }
SL_EXPORT void glutPostWindowRedisplay(int) { glut().redisplay = true; }
SL_EXPORT void glutSwapBuffers() { sl::interpose::frameShown(); }

// ---- callbacks ----
SL_EXPORT void glutDisplayFunc(void (*f)()) { glut().display = f; }
SL_EXPORT void glutReshapeFunc(void (*f)(int, int)) { glut().reshape = f; }
SL_EXPORT void glutKeyboardFunc(void (*f)(unsigned char, int, int)) { glut().keyboard = f; }
SL_EXPORT void glutIdleFunc(void (*f)()) { glut().idle = f; }
SL_EXPORT void glutTimerFunc(unsigned int ms, void (*f)(int), int value) {
  auto& g = glut();
  g.timers.push_back({g.clock + long(ms), g.timerOrder++, f, value});
}
// Input this GLUT never produces (run-legacy drives the keyboard only): kept, never called.
SL_EXPORT void glutKeyboardUpFunc(void (*)(unsigned char, int, int)) {}
SL_EXPORT void glutSpecialFunc(void (*)(int, int, int)) {}
SL_EXPORT void glutSpecialUpFunc(void (*)(int, int, int)) {}
SL_EXPORT void glutMouseFunc(void (*)(int, int, int, int)) {}
SL_EXPORT void glutMotionFunc(void (*)(int, int)) {}
SL_EXPORT void glutPassiveMotionFunc(void (*)(int, int)) {}
SL_EXPORT void glutEntryFunc(void (*)(int)) {}
SL_EXPORT void glutVisibilityFunc(void (*)(int)) {}
SL_EXPORT void glutMenuStatusFunc(void (*)(int, int, int)) {}
SL_EXPORT int glutCreateMenu(void (*)(int)) { return glut().nextMenu++; }
SL_EXPORT void glutAddMenuEntry(const char*, int) {}
SL_EXPORT void glutAddSubMenu(const char*, int) {}
SL_EXPORT void glutAttachMenu(int) {}
SL_EXPORT void glutSetMenu(int) {}

// ---- state ----
SL_EXPORT int glutGet(GLenum what) {
  const auto& g = glut();
  switch (what) {
    case GLUT_WINDOW_WIDTH: return g.width;
    case GLUT_WINDOW_HEIGHT: return g.height;
    case GLUT_WINDOW_X: return g.initX < 0 ? 0 : g.initX;
    case GLUT_WINDOW_Y: return g.initY < 0 ? 0 : g.initY;
    case GLUT_WINDOW_DOUBLEBUFFER: return 0;  // one OSMesa buffer
    case GLUT_WINDOW_RGBA: return 1;
    case GLUT_WINDOW_DEPTH_SIZE:
      return (g.displayMode & GLUT_DEPTH) ? sl::interpose::kDepthBits : 0;
    case GLUT_WINDOW_STENCIL_SIZE:
      return (g.displayMode & GLUT_STENCIL) ? sl::interpose::kStencilBits : 0;
    case GLUT_SCREEN_WIDTH: return sl::interpose::kScreenWidth;
    case GLUT_SCREEN_HEIGHT: return sl::interpose::kScreenHeight;
    case GLUT_INIT_WINDOW_WIDTH: return g.initWidth;
    case GLUT_INIT_WINDOW_HEIGHT: return g.initHeight;
    case GLUT_INIT_WINDOW_X: return g.initX;
    case GLUT_INIT_WINDOW_Y: return g.initY;
    case GLUT_INIT_DISPLAY_MODE: return int(g.displayMode);
    case GLUT_ELAPSED_TIME: return int(g.clock);
    case GLUT_DISPLAY_MODE_POSSIBLE: return 1;
    case GLUT_WINDOW_PARENT: return 0;
    case GLUT_WINDOW_NUM_CHILDREN: return 0;
    default: return 0;
  }
}
SL_EXPORT int glutGetModifiers() { return 0; }
SL_EXPORT int glutDeviceGet(GLenum) { return 0; }
SL_EXPORT int glutLayerGet(GLenum) { return 0; }

// GLUT 3 spec 12.1: true when `name` is a whole word of GL_EXTENSIONS.
SL_EXPORT int glutExtensionSupported(const char* name) {
  SL_GL(glGetString);
  const char* all = reinterpret_cast<const char*>(glGetString(GL_EXTENSIONS));
  if (all == nullptr || name == nullptr || *name == 0 || std::strchr(name, ' ') != nullptr)
    return 0;
  std::istringstream words(all);
  for (std::string w; words >> w;)
    if (w == name) return 1;
  return 0;
}

// ---- the main loop ----
SL_EXPORT void glutLeaveMainLoop() { std::exit(0); }

SL_EXPORT void glutMainLoop() {
  auto& g = glut();
  auto& s = sl::interpose::FrameSession::get();
  if (g.window == 0) sl::interpose::fatal("glutMainLoop before glutCreateWindow");
  int idleWithoutFrame = 0;
  for (;;) {
    if (s.active() && s.done) std::exit(0);  // as freeglut does when the window is closed
    if (g.reshapePending) sl::interpose::callReshape();
    if (g.redisplay) {
      idleWithoutFrame = 0;
      sl::interpose::callDisplay();
      continue;
    }
    if (sl::interpose::deliverKey()) continue;
    if (!g.timers.empty()) {
      auto first = g.timers.begin();
      for (auto it = g.timers.begin(); it != g.timers.end(); ++it)
        if (it->due < first->due || (it->due == first->due && it->order < first->order)) first = it;
      const sl::interpose::Timer t = *first;
      g.timers.erase(first);
      if (t.due > g.clock) g.clock = t.due;
      t.fn(t.value);
      continue;
    }
    if (g.idle != nullptr && ++idleWithoutFrame < sl::interpose::kMaxIdleWithoutFrame) {
      g.idle();
      continue;
    }
    if (!s.active()) std::exit(0);  // nothing will ever happen again
    sl::interpose::fatal(s.frame == 0 ? std::string("the program showed no frame")
                                      : "the program showed no frame after key '" +
                                            s.keyNames[size_t(s.frame - 1)] + "'");
  }
}

// ---- fonts ----
// Fonts whose data this GLUT does not carry: stop with a message rather than draw nothing.
SL_EXPORT void glutBitmapCharacter(void*, int) {
  sl::interpose::fatal("GLUT bitmap fonts are not provided");
}
SL_EXPORT void glutStrokeCharacter(void*, int) {
  sl::interpose::fatal("GLUT stroke fonts are not provided");
}
