// core/technique/pass_table.h — a technique's passes, declared once.
//
// Every technique declares its passes as it declares its --params (core/technique/technique.h): a
// table of PassSpec, one per pass, with a stable id ("1", "5c"), its name, the paper's section,
// equation or figure it follows (or "ours: ..."), the buffers it writes (what --dump-passes shows,
// with the meaning of each channel), its floor class for the legacy roofline, the GLSL it runs, the
// legacy passes a modern twin's pass replaces and its departures from the paper. The table feeds
// timing, GL tracing, the dump (teach/pass_dump.h), the roofline (measure/roofline.h) and the
// lessons; nothing finds a pass by its display name.
//
// render() runs each pass through the framework by id (core/technique/passes.h).
#pragma once

#include <string>
#include <vector>

namespace sl {

// Which floor the legacy roofline (measure/roofline.h) measures a pass against: the least
// work the renderer needs for what the pass draws or copies. kNone: no floor (shader passes,
// whose work has no fixed-function equivalent); kCpuOnly: no GL work at all.
enum class PassFloor {
  kNone,
  kCpuOnly,
  kLightDepth,           // one ramp-textured light pass (Brabec & Seidel §2, §4)
  kLightDepthAndCopy,    // the same and its copy into the map texture (§2)
  kJitteredLightGroup,   // up to four jittered light passes and one copy (§3, Fig. 3)
  kCopyToTexture,        // a framebuffer copy into the map texture (§4, Eq. (1))
  kCameraDepth,          // the camera pass drawing ramp depth (§2, §3)
  kProjectiveSubtract,   // the projected map subtracted by blending (§2, Fig. 6)
  kCopyPixels,           // glCopyPixels through colour table and matrix (§3, Fig. 4)
  kAccumulate,           // one accumulation-buffer step (§3)
  kAccumulationReturn,   // the accumulation buffer returned to colour (§3)
  kLighting,             // lighting x shadow term x cone texture, direct then ambient (§5)
  kCopyWindowToTexture,  // the window copied into a texture (fast PCF 4x4 saves its camera pass)
  kTexturedWindowQuad,   // one textured full-window quad (PCF 3x3/4x4, fast PCF 4x4 restore it)
  kStateOnly,            // GL state set, nothing drawn or copied (Everitt's texgen planes)
  kDepthFromLight,       // a depth-only light pass with polygon offset, copied to a depth texture
  kAmbientCamera,        // the camera pass lit by the ambient term, depth written (Everitt)
  kShadowedDirectLight,  // direct light x shadow comparison x cone, added (Everitt Figs. 4-5)
  kVisibilityMask,       // the comparison alone on white surfaces, read back (legacy.hw --mask)
};
const char* passFloorName(PassFloor floor);

// The job a pass does in its pipeline, declared by its table: two techniques' passes with the
// same role do the same job (Brabec & Seidel §2-§4 name them alike), so a figure pairs them
// when it sets one frame's passes beside another's (figures/measured.cpp). kOther: a pass no
// other pipeline pairs with (state only, a reference's rays, a shader technique's own step).
enum class PassRole {
  kOther,
  kMesh,                // the scene's triangles prepared for the pipeline
  kLight,               // a pass from the light that makes (part of) the shadow map
  kCopyToTexture,       // the framebuffer copied into a texture
  kCamera,              // a pass from the camera drawing light depth (or restoring it)
  kProjective,          // the map projected onto the scene and compared
  kCopy,                // glCopyPixels through the imaging subset
  kAccumulate,          // one accumulation-buffer step
  kAccumulationReturn,  // the accumulation buffer returned to colour
  kLighting,            // lighting times the shadow term
};

// One buffer a pass writes, as --dump-passes shows it.
struct PassBuffer {
  // The file name after the pass id: "packed-shadow-map{part}-rgba". "{part}" is replaced by
  // the part's file tag ("-upper-left"; empty for a pass run once).
  std::string name{};
  // Under the picture; "{key}" is replaced by the words given to Passes::capture.
  std::string caption{};
  // A packed map (several depth samples per texel, Brabec–Seidel §4 Fig. 5): the channel that
  // holds the texel's own sample, and what each channel holds.
  int centreChannel = -1;
  std::vector<std::string> channelMeaning{};
};

// Every member has a default, so that a table names only the members a pass has (designated
// initializers leave the others at their defaults).
struct PassSpec {
  std::string id{};         // stable: "1", "5c", "mesh"
  std::string name{};       // "light pass: depth ramp in RGBA"
  std::string reference{};  // "Brabec & Seidel 2001 §4, Eq. (1), Fig. 5", or "ours: ..."
  std::vector<PassBuffer> writes{};
  PassFloor floor = PassFloor::kNone;
  PassRole role = PassRole::kOther;
  // The `// @pass ID` markers of the GLSL this pass runs (core/gl/shaders.h).
  std::vector<std::string> shaders{};
  // A modern twin's pass: the ids of the legacy twin's passes it does ("3", "4", "5").
  std::vector<std::string> replaces{};
  // Its departures from the paper: "DEVIATION (source, section): why", as in the code.
  std::vector<std::string> deviations{};
  // The GL state that matters for this pass, as the technique declares it: words of the traced
  // lines (core/gl/gl_trace.h) that the lesson's state card highlights ("GL_POLYGON_OFFSET_FILL",
  // "colour matrix", "GL_EYE_PLANE"); a line holding any of them is a key line.
  std::vector<std::string> keyState{};
};

using PassTable = std::vector<PassSpec>;

// The pass `id` of `table`; throws std::logic_error (a programming error, not input) naming
// the id when the table has no such pass.
const PassSpec& findPassSpec(const PassTable& table, const std::string& id);
// Checks a table: ids unique and non-empty, names non-empty, buffer names unique within a
// pass. Returns the problems, one line each (empty = none).
std::vector<std::string> passTableProblems(const PassTable& table);

// One run of a pass that a render repeats (the phases of a 4x4 footprint, the groups of a
// PCF): what its name gets ("(upper-left)"), its file tag ("-upper-left") and its index.
struct PassPart {
  std::string label;    // appended to the pass's name after a space: "(group 2)"
  std::string fileTag;  // "{part}" of its buffers' names
  int index = 0;        // 0-based; the roofline reads it (which samples a PCF group holds)
};

}  // namespace sl
