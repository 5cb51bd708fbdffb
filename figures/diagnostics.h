// figures/diagnostics.h — the figure module's own small renders for what no technique
// outputs: the scene from the light, its depth map, the eye's distance to the light, the map
// projected onto the scene and the shadow-map texel density seen from the eye (Everitt
// Figs. 2, 4 and 6). One core-profile OSMesa context, GLSL written here, no shadows.
#pragma once

#include "core/base/image.h"
#include "core/scene/scene.h"

namespace sl::figures {

struct DiagnosticViews {
  Image lightView;      // RGB, square: the scene shaded from the light (N.L only)
  Image shadowMap;      // 1 channel, texels x texels: linearised light depth, 0 = near
  Image lightDistance;  // 1 channel, eye image: linearised light depth of each eye pixel
  Image projectedMap;   // 1 channel, eye image: the map's value at each pixel's projection
  Image texelDensity;   // RGB, eye image: eye pixels per texel, colour coded (log2)
  Image lightDensity;   // RGB, square: the light's view in texelDensity's colours where the
                        // eye sees the point, dim grey where it does not (Fig. 6 right)
};

// `lightSide` is the side of the square light-view image; `texels` the shadow map's side.
DiagnosticViews renderDiagnostics(const Scene& scene, int width, int height, int texels,
                                  int lightSide);

// The colour code of texelDensity: log2(eye pixels per texel) in [-2, 2] from red (many
// texels per pixel: minified) through green (one to one) to blue (one texel spread over many
// pixels: magnified, blocky). Exposed for the legend and the test.
void densityColor(float pixelsPerTexel, float rgb[3]);

}  // namespace sl::figures
