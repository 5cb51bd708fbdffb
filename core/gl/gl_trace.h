// core/gl/gl_trace.h — a tracing layer on the GL dispatch table (core/gl/gl.h) for --dump-passes:
// the GL state behind every pass, as readable lines a student can follow.
//
// While a GlTrace lives, the current thread's GL calls go through a second GlDispatch whose
// entries record the call and forward to the table that was current when the trace began (the
// context's own table, with imaging/'s emulated entries where it installed them: the trace sees
// the calls the technique makes, not the emulation's own). When no trace lives, nothing
// changes: the context's table is current and every call goes straight to the driver, so
// tracing costs nothing when it is off (tools/legacy_bench --trace-overhead measures both).
//
// What is recorded: every call that changes state or draws, with its arguments, summarised
// for reading — texgen planes, matrices with their matrix mode (4x4, rows), colour tables
// (entry count and runs: "256 entries: 0..63 -> 0, 64..255 -> 1"), convolution kernels (as a
// grid), blend, depth/alpha/stencil tests, polygon offset, accumulation, pixel copies,
// texture parameters, programs (with their .glsl files), uniforms by name, render targets and
// draws (immediate-mode glBegin/glEnd batches counted, not listed). Queries (glGet*, glIs*),
// name generation and shader compilation are not state of a pass and are left out.
//
// Lines are grouped per pass: core/technique/technique.h PassTimer calls beginTracedPass() and
// endTracedPass(); calls made between two passes (setting up textures, programs) are kept as
// the next pass's setup. Readbacks made only for the dump run under a GlTracePause.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/gl/gl.h"

namespace sl {

// One readable line of a pass's GL state: `group` names what it is about ("texgen", "matrix",
// "colour matrix", "colour table", "convolution", "blend", "depth", "alpha", "stencil",
// "polygon offset", "accum", "pixels", "texture", "program", "uniforms", "target", "draw",
// "clear", "lighting", "raster", "enable", "vertex arrays", "attrib stack").
struct GlStateLine {
  std::string group;
  std::string text;
};

// The lines of one pass: `setup` were recorded since the previous pass ended (outside any
// PassTimer), `state` inside it, both in call order.
struct TracedPass {
  std::vector<GlStateLine> setup;
  std::vector<GlStateLine> state;
};

// While alive, GL calls made on this thread are recorded (see above). Not nestable: a second
// GlTrace on the same thread throws GlError. Requires a current context.
class GlTrace {
 public:
  GlTrace();
  ~GlTrace();
  GlTrace(const GlTrace&) = delete;
  GlTrace& operator=(const GlTrace&) = delete;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// True while a GlTrace lives on this thread.
bool glTraceActive();

// Pass boundaries (PassTimer). beginTracedPass: the lines recorded since the last pass become
// this pass's setup. endTracedPass: the pass's lines. Passes may nest (a pass inside a pass
// keeps its own lines). Both do nothing / return nothing without a GlTrace.
void beginTracedPass();
TracedPass endTracedPass();

// Names the .glsl files of a program, for "program" lines (core/gl/shaders.cpp calls it).
void noteTracedProgram(GLuint program, const std::vector<std::string>& files);

// While alive, calls are not recorded (state is still followed): readbacks made for the dump
// only (core/technique/pass_capture.h and the techniques' capture helpers).
class GlTracePause {
 public:
  GlTracePause();
  ~GlTracePause();
  GlTracePause(const GlTracePause&) = delete;
  GlTracePause& operator=(const GlTracePause&) = delete;
};

// The name of a GL enum the sources use ("GL_EYE_LINEAR"), or its value in hexadecimal.
std::string glEnumName(GLenum value);

}  // namespace sl
