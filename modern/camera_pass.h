// modern/camera_pass.h — what every modern technique's final pass shares: the camera target
// (colour + visibility attachments), the spotlight uniforms of shading.glsl-style shaders, and
// read-back into a Frame (module-internal header).
#pragma once

#include "core/technique/technique.h"
#include "modern/gl_objects.h"

namespace sl::modern {

// Colour attachment 0 = shaded RGBA8, attachment 1 = visibility (RGBA8 in 'faithful'
// arithmetic, so that it quantises like the legacy colour buffer; R32F in 'float').
RenderTarget makeCameraTarget(const RenderParams& params, bool floatVisibility);
// Clears colour to black, visibility to 1 (no geometry = lit) and depth to 1.
void clearCameraTarget(const RenderTarget& target);
// Sets uLightPosition, uLightDirection, uSpotCosCutoff, uLightColor, uAmbient, uEyePosition
// (the same spotlight as legacy_gl/fixed_function.cpp).
void setLightingUniforms(const Program& program, const Scene& scene);
// Per-object uniforms: uModel, uDiffuse, uSpecular, uReceivesShadow.
void setObjectUniforms(const Program& program, const Object& object);
// Reads attachment 0 into frame.color (RGB) and attachment 1 channel 0 into frame.visibility.
void readCameraTarget(const RenderTarget& target, Frame& frame);
// The camera's view-projection for the window.
glm::mat4 cameraViewProjection(const Scene& scene, const RenderParams& params);
// Reads a colour attachment of a target as float RGBA.
Image readAttachment(const RenderTarget& target, int attachment);

}  // namespace sl::modern
