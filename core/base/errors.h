// core/base/errors.h — the two kinds of failure shadowlab reports.
//   InputError: the user's input is wrong (unknown name, malformed file, impossible number).
//               The CLI prints its one-line message and exits with status 2.
//   GlError:    the GL implementation refused or failed (with the pass that was running).
#pragma once

#include <stdexcept>
#include <string>

namespace sl {

struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct GlError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Throws GlError("<pass>: GL error GL_INVALID_OPERATION ...") if glGetError reports anything;
// drains every queued error so the next pass starts clean. A GL failure noted earlier on this
// thread (noteGlError) is thrown first.
void checkGl(const char* pass);

// Drains glGetError without throwing: "GL_INVALID_OPERATION, GL_OUT_OF_MEMORY", or empty when
// no error is queued. An injected fault (core/gl/gl_fault.h) adds its note.
std::string drainGlErrors();

// A GL failure met where throwing is not allowed (PassTimer's destructor, at the end of a pass):
// kept on this thread, the first one noted, until throwNotedGlError() throws it as GlError. The
// next pass, checkGl and the end of Technique::render call it, so the failure still ends the
// render with the pass's name, as if the pass had thrown.
void noteGlError(const std::string& message);
void throwNotedGlError();
bool glErrorNoted();

// A number for a message: shortest form that reads back (0.5, 1e+09, 8e-07), no trailing zeros.
std::string formatNumber(double value);

// Name of a GL error enum, e.g. "GL_INVALID_ENUM".
const char* glErrorName(unsigned error);

// Exit statuses of every shadowlab program (docs/design.md, "Command-line contract").
constexpr int kExitOther = 1;
constexpr int kExitInputError = 2;
constexpr int kExitGlError = 3;

// A program's main(): records the command line for provenance, runs `body`, and turns an
// escaping error into one line on stderr ("<program>: message") and its exit status.
int runProgram(const char* program, int argc, char** argv, int (*body)(int, char**));

}  // namespace sl
