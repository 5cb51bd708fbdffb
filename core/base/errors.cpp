#include "core/base/errors.h"

#include <iostream>
#include <optional>
#include <sstream>
#include <string>

#include "core/base/provenance.h"
#include "core/gl/gl.h"
#include "core/gl/gl_fault.h"

namespace sl {
using namespace sl::gl;

std::string formatNumber(double value) {
  std::ostringstream s;
  s.precision(6);
  s << value;
  return s.str();
}

const char* glErrorName(unsigned error) {
  switch (error) {
    case GL_NO_ERROR: return "GL_NO_ERROR";
    case GL_INVALID_ENUM: return "GL_INVALID_ENUM";
    case GL_INVALID_VALUE: return "GL_INVALID_VALUE";
    case GL_INVALID_OPERATION: return "GL_INVALID_OPERATION";
    case GL_STACK_OVERFLOW: return "GL_STACK_OVERFLOW";
    case GL_STACK_UNDERFLOW: return "GL_STACK_UNDERFLOW";
    case GL_OUT_OF_MEMORY: return "GL_OUT_OF_MEMORY";
    case GL_TABLE_TOO_LARGE: return "GL_TABLE_TOO_LARGE";
    case GL_INVALID_FRAMEBUFFER_OPERATION: return "GL_INVALID_FRAMEBUFFER_OPERATION";
    default: return "unknown GL error";
  }
}

std::string drainGlErrors() {
  std::string message;
  constexpr int kMaxQueuedErrors = 16;  // GL keeps one flag per error kind; bound the drain
  for (int i = 0; i < kMaxQueuedErrors; ++i) {
    GLenum e = glGetError();
    if (e == GL_NO_ERROR) break;
    if (!message.empty()) message += ", ";
    message += glErrorName(e);
  }
  if (!message.empty()) message += takeGlFaultNote();
  return message;
}

namespace {
// This thread's noted GL failure (noteGlError), like GL's own error flag: per thread.
thread_local std::optional<std::string> tNotedGlError;
}  // namespace

void noteGlError(const std::string& message) {
  if (!tNotedGlError) tNotedGlError = message;
}

bool glErrorNoted() { return tNotedGlError.has_value(); }

void throwNotedGlError() {
  if (!tNotedGlError) return;
  std::string message = std::move(*tNotedGlError);
  tNotedGlError.reset();
  throw GlError(message);
}

void checkGl(const char* pass) {
  throwNotedGlError();
  const std::string message = drainGlErrors();
  if (!message.empty()) throw GlError(std::string(pass) + ": " + message);
}

int runProgram(const char* program, int argc, char** argv, int (*body)(int, char**)) {
  recordCommandLine(argc, argv);  // PNG text chunks and JSON name the command
  try {
    return body(argc, argv);
  } catch (const InputError& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return kExitInputError;
  } catch (const GlError& e) {
    std::cerr << program << ": GL: " << e.what() << "\n";
    return kExitGlError;
  } catch (const std::exception& e) {
    std::cerr << program << ": " << e.what() << "\n";
    return kExitOther;
  }
}

}  // namespace sl
