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
// --param bias=normal-offset (modern.pcf, modern.fast-pcf camera pass; ours, after Holbert
// 2011): the eye position moves along the surface normal before texgen, so the ramp and map
// coordinates are those of the moved point; uNormalOffsetPerDistance is 0 in every other use.
#version 330 core
layout(location = 0) in vec3 aPosition;
layout(location = 1) in vec3 aNormal;
uniform mat4 uModel;                 // for lighting (world position and normal)
uniform mat4 uModelView;             // V · M, the legacy modelview
uniform mat4 uModelViewProjection;   // P · (V · M)
uniform mat4 uEyeToRamp;             // texture matrix of the ramp unit
uniform mat4 uEyeToShadowMap[4];     // texture matrix of each group's map
uniform vec3 uLightPosition;         // world (lighting.glsl's)
uniform float uNormalOffsetPerDistance;  // normal-offset-texels x footprint / distance; 0: none
uniform bool uNormalOffsetByAngle;   // times 1 - N.L
out vec3 vWorldPosition;
out vec3 vShadowWorldPosition;       // the world position the shadow test projects
out vec3 vWorldNormal;
out vec4 vRampCoord;
out vec4 vShadowCoord[4];
void main() {
  vec4 object = vec4(aPosition, 1.0);
  vec4 eye = uModelView * object;  // EYE_LINEAR texgen, identity planes: (s, t, r, q) = eye
  vShadowWorldPosition = (uModel * object).xyz;
  vec3 normal = mat3(transpose(inverse(uModel))) * aNormal;
  // @pass vertex-normal-offset-bias: the eye position moved along the surface normal by texel footprints before texgen (ours, after Holbert 2011)
  // DEVIATION (Brabec & Seidel §2-§4 bias the depth by a constant only): with --param
  // bias=normal-offset (ours, after Holbert 2011) the camera pass's point moves along its
  // surface normal by normal-offset-texels texel footprints at its distance from the light
  // before texgen, so the ramp and map coordinates are those of the moved point.
  // uNormalOffsetPerDistance is that many footprints per unit of distance; a zero normal does
  // not move the point.
  if (uNormalOffsetPerDistance > 0.0 && dot(normal, normal) > 0.0) {
    vec3 n = normalize(normal);
    vec3 toLight = uLightPosition - vShadowWorldPosition;
    float toLightDistance = length(toLight);
    float nDotL = clamp(dot(n, toLight / toLightDistance), 0.0, 1.0);
    float scale = uNormalOffsetByAngle ? 1.0 - nDotL : 1.0;
    vec3 offset = n * (uNormalOffsetPerDistance * toLightDistance * scale);
    vShadowWorldPosition += offset;
    eye += uModelView * vec4(inverse(mat3(uModel)) * offset, 0.0);
  }
  // @end vertex-normal-offset-bias
  vRampCoord = uEyeToRamp * eye;
  for (int g = 0; g < 4; ++g) vShadowCoord[g] = uEyeToShadowMap[g] * eye;
  vec4 world = uModel * object;
  vWorldPosition = world.xyz;
  vWorldNormal = mat3(transpose(inverse(uModel))) * aNormal;
  gl_Position = uModelViewProjection * object;
}
