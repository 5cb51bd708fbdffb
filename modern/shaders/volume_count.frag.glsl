// volume_count.frag — Chan 2004 §3.3.2, Figures 3-9a and 3-10: every rasterised shadow-volume
// fragment adds 1 (additive blending into a float buffer), so the buffer holds the overdraw
// per pixel and its sum the number of shadow-polygon pixels.
#version 330 core
layout(location = 0) out vec4 oCount;
void main() { oCount = vec4(1.0, 0.0, 0.0, 1.0); }
