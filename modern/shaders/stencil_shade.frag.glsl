// stencil_shade.frag — Everitt & Kilgard 2002 / Chan 2004 §3.1 step 4: the final shading pass
// of stencil shadow volumes. The stencil test has already chosen the pixels (count == 0: lit;
// count != 0: in shadow), so the visibility arrives as a constant per draw.
#version 330 core
in vec3 vWorldPosition;
in vec3 vWorldNormal;
uniform float uVisibility;        // 1 for the lit draw, 0 for the shadowed draw
uniform bool uReceivesShadow;
uniform vec3 uDiffuse;
uniform float uSpecular;
uniform vec3 uLightPosition;
uniform vec3 uLightDirection;
uniform float uSpotCosCutoff;
uniform vec3 uLightColor;
uniform float uAmbient;
uniform vec3 uEyePosition;
layout(location = 0) out vec4 oColor;
layout(location = 1) out vec4 oVisibility;

// OpenGL fixed-function lighting with one spotlight (glspec121 §2.13.1), as hw_shadow.frag.
void main() {
  float visibility = uReceivesShadow ? uVisibility : 1.0;
  vec3 n = normalize(vWorldNormal);
  vec3 toLight = normalize(uLightPosition - vWorldPosition);
  if (!gl_FrontFacing) n = -n;
  float spot = dot(-toLight, normalize(uLightDirection)) >= uSpotCosCutoff ? 1.0 : 0.0;
  float diffuse = max(dot(n, toLight), 0.0);
  vec3 toEye = normalize(uEyePosition - vWorldPosition);
  float specular = diffuse > 0.0 ? pow(max(dot(n, normalize(toLight + toEye)), 0.0), 32.0) : 0.0;
  vec3 direct = spot * uLightColor * (uDiffuse * diffuse + vec3(uSpecular) * specular);
  vec3 ambient = uAmbient * uLightColor * uDiffuse;
  oColor = vec4(ambient + visibility * direct, 1.0);
  oVisibility = vec4(visibility, visibility, visibility, 1.0);
}
