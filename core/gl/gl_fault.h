// core/gl/gl_fault.h — fault injection on the GL dispatch table (core/gl/gl.h): a GL error or a
// missing entry point at a chosen pass or GL call, so that tests can prove every failure path
// (GlError -> exit 3 with no output file, HTTP 500 in the lab) without a broken driver.
//
// A fault is armed by the environment variable SHADOWLAB_INJECT_GL_FAULT, read once at the
// first GlContext::makeCurrent of the process, or by injectGlFault() (tests). Its spelling is
// KIND@TRIGGER (docs/fault-injection.md):
//
//   KIND     error    the next glGetError reports GL_INVALID_OPERATION (after a call trigger:
//                     the call is made, then reports the error, as a failed call would)
//            missing  the next GL call finds its entry point absent: the dispatch's own check
//                     throws GlError "the current GL implementation has no entry point glX"
//   TRIGGER  pass=ID  when the pass with pass-table id ID begins (core/technique/passes.h;
//                     "3", "5b", "mesh"); hand-timed passes (PassTimer) have no id
//            pass#N   when the Nth pass (Passes::run or PassTimer) begins, counted from 1
//                     since arming
//            call#N   at the Nth GL call made through the dispatch table since arming
//
// A fault fires once, on the first thread that meets its trigger, and is then disarmed: the
// next render (the live lab's next request) runs clean. The error it causes says so: the
// GlError's message ends "(injected GL fault KIND@TRIGGER, in pass 'NAME')".
//
// How: while a fault is armed, GlContext::makeCurrent makes current a thin table whose entries
// count the call and forward to the context's own table (which the imaging layer may still
// edit; the fault table reads it through a pointer). A GlTrace started later wraps the fault
// table like any other. Unarmed, makeCurrent makes the context's table current as before, no
// GL call passes through this layer, and PassTimer's hooks test one flag: zero cost when off.
#pragma once

#include <string>

#include "core/gl/gl.h"

namespace sl {

inline constexpr const char* kGlFaultVariable = "SHADOWLAB_INJECT_GL_FAULT";

struct GlFault {
  enum class Kind { kError, kMissingEntryPoint };
  enum class Trigger { kPassId, kPassNumber, kCallNumber };
  Kind kind = Kind::kError;
  Trigger trigger = Trigger::kPassNumber;
  std::string passId;    // kPassId: a pass-table id (core/technique/pass_table.h PassSpec::id)
  long long number = 0;  // kPassNumber, kCallNumber: 1 = the first
  std::string spelling;  // as SHADOWLAB_INJECT_GL_FAULT spells it: "error@pass=3"
};

// Reads KIND@TRIGGER (above); throws InputError naming the variable and what is wrong.
GlFault parseGlFault(const std::string& text);

// The test hook: arms `fault` for the whole process (replacing an armed one; pass and call
// counts start again). It takes effect from the next GlContext::makeCurrent on any thread.
void injectGlFault(const GlFault& fault);
// The pass id a pass=ID fault waits for, while one is armed; empty otherwise. A command that
// knows its technique checks it against the technique's pass tables (an id no pass has is an
// input error there, not a fault that silently never fires).
std::string armedGlFaultPassId();
// Disarms without firing (a test's cleanup). A fired fault is disarmed already.
void clearGlFault();
// How many faults have fired in this process (a test checks that its fault was met).
int glFaultsFired();

// --- Hooks of core/ (gl.cpp, errors.cpp, technique.cpp); nothing else calls them.

// True while a fault is armed (reads the variable at its first call).
bool glFaultArmed();
// The table to make current for a context's `table`: the fault table while armed.
const GlDispatch* glFaultLayer(const GlDispatch* table);
// A pass begins / ends on this thread: its pass-table id (empty for a hand-timed PassTimer)
// meets a pass=ID trigger, its display name goes into the fault's note. Cheap unless the fault
// table is current.
void glFaultPassBegin(const std::string& id, const std::string& name);
void glFaultPassEnd();
// The " (injected GL fault ..., in pass '...')" note of the fault that just fired on this
// thread, once; empty when none. checkGl and the missing-entry-point error append it.
std::string takeGlFaultNote();

}  // namespace sl
