// texgen.vert — the fixed-function vertex stage that legacy_gl's Brabec & Seidel passes use,
// as a shader (§2: "using automatic texture coordinate generation ... eye ... coordinates
// (x, y, z, w) as texture coordinates (s, t, r, q)" and "an additional 4x4 texture matrix
// which transforms points from camera to light source space"). EYE_LINEAR texgen with the
// identity planes copies the eye position; the texture matrix then maps it to the ramp
// coordinate (light pass and camera pass, §2 Fig. 1) and to the projective shadow-map
// coordinates of each group (§3, §4 Fig. 6). Like the fixed-function vertex program, the
// transforms are matrix · vector on the model-view and model-view-projection products, and the
// coordinates are interpolated per fragment and divided by q at the lookup, so 'faithful'
// arithmetic sees the same texture coordinates as the legacy pipeline.
#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
uniform mat4 uModel;                 // for lighting (world position and normal)
uniform mat4 uModelView;             // V · M, the legacy modelview
uniform mat4 uModelViewProjection;   // P · (V · M)
uniform mat4 uEyeToRamp;             // texture matrix of the ramp unit
uniform mat4 uEyeToShadowMap[4];     // texture matrix of each group's map
out vec3 vWorldPosition;
out vec3 vWorldNormal;
out vec4 vRampCoord;
out vec4 vShadowCoord[4];
void main() {
  vec4 object = vec4(aPosition, 1.0);
  vec4 eye = uModelView * object;  // EYE_LINEAR texgen, identity planes: (s, t, r, q) = eye
  vRampCoord = uEyeToRamp * eye;
  for (int g = 0; g < 4; ++g) vShadowCoord[g] = uEyeToShadowMap[g] * eye;
  vec4 world = uModel * object;
  vWorldPosition = world.xyz;
  vWorldNormal = mat3(transpose(inverse(uModel))) * aNormal;
  gl_Position = uModelViewProjection * object;
}
