// interpose/frames_preload.cpp — libshadowlab-frames.so: what `shadowlab run-legacy --backend
// glx` preloads beside libshadowlab-imaging.so to see a GLUT program's frames and to press its
// keys. Not part of the drop-in library a user preloads.
//
// It wraps glutDisplayFunc and glutKeyboardFunc (to keep the program's callbacks) and
// glutSwapBuffers. A frame is "displayed" when glutSwapBuffers is called (double-buffered:
// the back buffer is read before the real swap) or when the display callback returns
// (single-buffered: the front buffer after glFinish). The first displayed frame after
// start-up and the first after each key are written as $SHADOWLAB_FRAMES_DIR/NNN.png; keys
// ($SHADOWLAB_KEYS, space-separated: one character, or esc / space) are delivered one at a
// time through the program's keyboard callback from a GLUT timer, each after the previous
// frame was written. After the last frame the main loop is left as when the window is closed
// (glutLeaveMainLoop), so the program ends through its own exit path.
#include <GL/freeglut.h>
#include <GL/gl.h>
#include <dlfcn.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "core/base/image.h"
#include "interpose/frame_files.h"

#define SL_EXPORT extern "C" __attribute__((visibility("default")))

namespace sl::interpose {
namespace {

constexpr float kByteMax = 255.0f;

// freeglut's own function, by its library's handle (RTLD_NEXT would be answered relative to
// libshadowlab-imaging.so, whose dlsym wraps glibc's: see interpose/imaging_preload.cpp).
// The GLUT library is found through a function this library does not wrap (glutGet).
void* glutLibrary() {
  static void* glut = [] {
    Dl_info info{};
    void* handle = nullptr;
    if (dladdr(reinterpret_cast<void*>(&glutGet), &info) != 0 && info.dli_fname != nullptr)
      handle = dlopen(info.dli_fname, RTLD_NOW | RTLD_NOLOAD);
    if (handle == nullptr) {
      std::fprintf(stderr, "libshadowlab-frames: the program's GLUT library is not found\n");
      std::exit(3);
    }
    return handle;
  }();
  return glut;
}

template <class Fn>
Fn nextFn(const char* name) {
  auto fn = reinterpret_cast<Fn>(dlsym(glutLibrary(), name));
  if (fn == nullptr) {
    std::fprintf(stderr, "libshadowlab-frames: GLUT has no %s\n", name);
    std::exit(3);
  }
  return fn;
}

// The driver's GL entry point, from libGL itself: never the imaging library's export (its
// glReadPixels runs the pixel-transfer pipeline; the frame is the framebuffer as shown).
template <class Fn>
Fn driverFn(const char* name) {
  static void* gl = dlopen("libGL.so.1", RTLD_NOW | RTLD_NOLOAD);
  if (gl == nullptr) return nullptr;
  return reinterpret_cast<Fn>(dlsym(gl, name));
}

// The program's callbacks, per GLUT window.
struct Callbacks {
  std::map<int, void (*)()> display;
  std::map<int, void (*)(unsigned char, int, int)> keyboard;
  int mainWindow = 0;
};

Callbacks& callbacks() {
  static Callbacks c;
  return c;
}

bool active() { return FrameSession::get().active(); }

// Reads the window's colour buffer `buffer` (GL_FRONT or GL_BACK) as shown: tight pixel
// storage, no pack buffer; the program's state is restored.
Image readWindow(GLenum buffer, int w, int h) {
  static auto getIntegerv = driverFn<decltype(&::glGetIntegerv)>("glGetIntegerv");
  static auto pixelStorei = driverFn<decltype(&::glPixelStorei)>("glPixelStorei");
  static auto readBuffer = driverFn<decltype(&::glReadBuffer)>("glReadBuffer");
  static auto readPixels = driverFn<decltype(&::glReadPixels)>("glReadPixels");
  static auto finish = driverFn<decltype(&::glFinish)>("glFinish");
  static auto bindBuffer = driverFn<void (*)(GLenum, GLuint)>("glBindBuffer");
  Image image;
  if (!getIntegerv || !pixelStorei || !readBuffer || !readPixels || !finish || w <= 0 || h <= 0)
    return image;
  finish();
  const GLenum packParams[] = {GL_PACK_ALIGNMENT, GL_PACK_ROW_LENGTH, GL_PACK_SKIP_PIXELS,
                               GL_PACK_SKIP_ROWS, GL_PACK_SWAP_BYTES, GL_PACK_LSB_FIRST};
  GLint saved[6] = {};
  for (int i = 0; i < 6; ++i) getIntegerv(packParams[i], &saved[i]);
  GLint savedRead = 0, savedPackBuffer = 0;
  getIntegerv(GL_READ_BUFFER, &savedRead);
  if (bindBuffer) getIntegerv(GL_PIXEL_PACK_BUFFER_BINDING, &savedPackBuffer);
  const GLint tight[6] = {1, 0, 0, 0, GL_FALSE, GL_FALSE};
  for (int i = 0; i < 6; ++i) pixelStorei(packParams[i], tight[i]);
  if (bindBuffer && savedPackBuffer != 0) bindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  readBuffer(buffer);
  std::vector<unsigned char> bytes(size_t(w) * h * 3);
  readPixels(0, 0, w, h, GL_RGB, GL_UNSIGNED_BYTE, bytes.data());
  readBuffer(GLenum(savedRead));
  if (bindBuffer && savedPackBuffer != 0) bindBuffer(GL_PIXEL_PACK_BUFFER, GLuint(savedPackBuffer));
  for (int i = 0; i < 6; ++i) pixelStorei(packParams[i], saved[i]);
  image = Image(w, h, 3);
  for (size_t i = 0; i < bytes.size(); ++i) image.data[i] = float(bytes[i]) / kByteMax;
  return image;
}

void deliverKey(int index);

// A frame was shown on `buffer`: written when one is awaited, then the next key or the end.
void frameShown(GLenum buffer) {
  FrameSession& s = FrameSession::get();
  if (!s.active() || !s.awaiting || s.done) return;
  const int w = glutGet(GLUT_WINDOW_WIDTH), h = glutGet(GLUT_WINDOW_HEIGHT);
  const Image image = readWindow(buffer, w, h);
  if (image.empty()) {
    std::fprintf(stderr, "libshadowlab-frames: cannot read the window (no libGL entry points)\n");
    s.done = true;
    glutLeaveMainLoop();
    return;
  }
  s.write(image, buffer == GL_BACK ? "back" : "front");
  const int key = s.takeKey();
  if (key >= 0)
    glutTimerFunc(0, deliverKey, key);
  else
    glutLeaveMainLoop();  // as when the window is closed
}

void deliverKey(int index) {
  FrameSession& s = FrameSession::get();
  const int window = callbacks().mainWindow;
  auto it = callbacks().keyboard.find(window);
  if (it == callbacks().keyboard.end() || it->second == nullptr) {
    std::fprintf(stderr, "libshadowlab-frames: the program has no keyboard callback for key '%s'\n",
                 s.keyNames[size_t(index)].c_str());
    s.done = true;
    glutLeaveMainLoop();
    return;
  }
  glutSetWindow(window);
  s.awaiting = true;
  it->second(s.keys[size_t(index)], 0, 0);
}

void displayHook() {
  Callbacks& c = callbacks();
  const int window = glutGetWindow();
  auto it = c.display.find(window);
  if (it != c.display.end() && it->second != nullptr) it->second();
  if (window == c.mainWindow && !glutGet(GLUT_WINDOW_DOUBLEBUFFER)) frameShown(GL_FRONT);
}

}  // namespace
}  // namespace sl::interpose

SL_EXPORT void glutDisplayFunc(void (*callback)()) {
  static auto real = sl::interpose::nextFn<decltype(&::glutDisplayFunc)>("glutDisplayFunc");
  auto& s = sl::interpose::callbacks();
  if (!sl::interpose::active()) return real(callback);
  const int window = glutGetWindow();
  if (s.mainWindow == 0) s.mainWindow = window;
  s.display[window] = callback;
  real(callback != nullptr ? sl::interpose::displayHook : nullptr);
}

SL_EXPORT void glutKeyboardFunc(void (*callback)(unsigned char, int, int)) {
  static auto real = sl::interpose::nextFn<decltype(&::glutKeyboardFunc)>("glutKeyboardFunc");
  if (sl::interpose::active()) sl::interpose::callbacks().keyboard[glutGetWindow()] = callback;
  real(callback);
}

SL_EXPORT void glutSwapBuffers() {
  static auto real = sl::interpose::nextFn<decltype(&::glutSwapBuffers)>("glutSwapBuffers");
  auto& s = sl::interpose::callbacks();
  if (sl::interpose::active() && glutGetWindow() == s.mainWindow &&
      glutGet(GLUT_WINDOW_DOUBLEBUFFER))
    sl::interpose::frameShown(GL_BACK);
  real();
}
