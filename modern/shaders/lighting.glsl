// lighting.glsl — OpenGL fixed-function lighting with one spotlight (glspec121 §2.13.1), split
// into the ambient term and the direct (diffuse + specular) term that the shadow term darkens
// (Everitt et al. 2001, Kilgard's note). Included by the camera passes of modern/.
uniform vec3 uDiffuse;
uniform float uSpecular;
uniform vec3 uLightPosition;
uniform vec3 uLightDirection;
uniform float uSpotCosCutoff;
uniform vec3 uLightColor;
uniform float uAmbient;
uniform vec3 uEyePosition;

vec3 shadeSpotlight(vec3 world, vec3 worldNormal, float visibility) {
  vec3 n = normalize(worldNormal);
  vec3 toLight = normalize(uLightPosition - world);
  if (!gl_FrontFacing) n = -n;
  float spot = dot(-toLight, normalize(uLightDirection)) >= uSpotCosCutoff ? 1.0 : 0.0;
  float diffuse = max(dot(n, toLight), 0.0);
  vec3 toEye = normalize(uEyePosition - world);
  float specular = diffuse > 0.0 ? pow(max(dot(n, normalize(toLight + toEye)), 0.0), 32.0) : 0.0;
  vec3 direct = spot * uLightColor * (uDiffuse * diffuse + vec3(uSpecular) * specular);
  vec3 ambient = uAmbient * uLightColor * uDiffuse;
  return ambient + visibility * direct;
}
