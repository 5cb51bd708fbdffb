// legacy_gl/fixed_function.h — scene drawing and lighting in OpenGL 1.x, shared by every
// legacy technique (module-internal header).
#pragma once

#include <glm/glm.hpp>
#include <string>
#include <vector>

#include "core/gl/gl.h"
#include "core/gl/gl_objects.h"
#include "core/scene/scene.h"
#include "core/technique/technique.h"

namespace sl::legacy {

enum class Draw { kAll, kCasters, kReceivers, kNonReceivers };
// kBlack draws colour and alpha 0 (passes that encode values in colour, Brabec–Seidel §2).
enum class Colors { kMaterial, kWhite, kBlack };

// glMatrixMode(mode); glLoadMatrixf(m).
void loadMatrix(unsigned mode, const glm::mat4& m);

// Draws the objects selected by `which` with client-side vertex arrays (GL 1.1), each under
// glPushMatrix/glMultMatrixf(model). Sets glColor and the diffuse material from the object.
// With Colors::kWhite every object is drawn white (visibility and depth passes).
void drawScene(const Scene& scene, Draw which, Colors colors = Colors::kMaterial);

// Which terms of OpenGL lighting a pass wants (Everitt §4, Kilgard's note: the shadow term
// darkens diffuse and specular and keeps the ambient).
enum class LightTerms { kAmbientOnly, kDiffuseSpecularOnly, kAll };
// Enables GL_LIGHTING with GL_LIGHT0 at the scene's spotlight, without GL_SPOT_CUTOFF: the cone
// is the projected texture of legacy_gl/projected_spotlight.h, which every pass adding direct
// light enables beside it. Must be called while the modelview matrix holds the camera's view
// matrix (the light position is specified in world coordinates and transformed by it,
// glspec121 §2.13.1).
void enableSpotlight(const Scene& scene, LightTerms terms);
void disableLighting();

// The camera's matrices for a window of the given size (viewport set too).
void setCameraMatrices(const Scene& scene, int width, int height);

// A framebuffer object standing in for the window when a light pass does not fit in it.
// DEVIATION (Brabec–Seidel §2, Everitt §2): the 2001 code rendered the light view into the
// window; a map larger than our window would be clipped, so we render it off-screen.
inline const std::string kOffscreenLightPassDeviation =
    "DEVIATION (Brabec–Seidel §2, Everitt §2): the 2001 code rendered the light view into the "
    "window; a map larger than our window would be clipped, so we render it off-screen.";
class LightTarget {
 public:
  // colorFormat: the colour attachment's internal format (the precision of the light pass).
  LightTarget(int texels, bool windowFits, bool needColor, unsigned colorFormat = GL_RGBA8);
  LightTarget(const LightTarget&) = delete;
  LightTarget& operator=(const LightTarget&) = delete;
  void bind();    // binds the FBO (or the window) and sets the viewport to texels^2
  void unbind();  // back to the window
  bool offscreen() const { return fbo_.id() != 0; }

 private:
  int texels_;
  Framebuffer fbo_;  // none when the window fits
  Texture depth_;
  Texture color_;  // none without needColor
};

// Everything a legacy frame may change in its context, given back when the frame ends, also
// when it throws (the lab and the benchmarks render frame after frame in one context;
// tests/legacy_gl/state_scope_test.cpp renders every legacy technique after every other):
//   - every server attribute group, glPushAttrib(GL_ALL_ATTRIB_BITS) (glspec121 §6.1.12 and the
//     attribute column of tables 6.5-6.21): the enables, texgen modes and planes, texture
//     environments, bindings and enables of every unit, blending, depth, stencil, lighting,
//     pixel transfer, viewport, clear values, matrix mode, active unit, current colour and
//     raster position. Where imaging/ emulates ARB_imaging, its enables (colour tables,
//     convolutions, histogram, minmax) and pixel-mode parameters (scales, biases, border modes)
//     go with the same push, as the tables' "pixel" and "pixel/enable" rows assign them
//     (imaging/internal.h AttribSnapshot);
//   - the client groups, glPushClientAttrib(GL_CLIENT_ALL_ATTRIB_BITS): pixel store and vertex
//     arrays;
//   - what no group holds (the tables' "-" rows; "matrix stacks are never pushed or popped",
//     appendix F): the projection and modelview matrices, the texture matrix of every texture
//     unit and the colour matrix, read now and loaded back at the end (the frame keeps the
//     stacks' full depth); and the framebuffer binding (framebuffer objects came after 1.2.1).
// Not given back: the contents of objects and tables (textures, colour tables, convolution
// filters, the accumulation buffer), which every pass loads or clears before it reads them.
// The scope's own calls are in no pass's GL trace (--dump-passes).
class ScopedLegacyState {
 public:
  ScopedLegacyState();
  ~ScopedLegacyState();
  ScopedLegacyState(const ScopedLegacyState&) = delete;
  ScopedLegacyState& operator=(const ScopedLegacyState&) = delete;

 private:
  glm::mat4 projection_{1.0f}, modelview_{1.0f}, color_{1.0f};
  std::vector<glm::mat4> texture_;  // one per texture unit (GL_MAX_TEXTURE_UNITS)
  GLint framebuffer_ = 0;
};

// `render` inside a ScopedLegacyState: the render function of every technique legacy_gl lists
// (legacy_gl/techniques.cpp).
RenderFunction withScopedLegacyState(RenderFunction render);

// Reads the window's red channel as a one-channel image (visibility masks).
Image readRedChannel(int width, int height);
// Reads the window as RGB.
Image readRgb(int width, int height);

}  // namespace sl::legacy
