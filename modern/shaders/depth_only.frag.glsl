// depth_only.frag — light pass: only the depth buffer is written (Everitt §2, Fig. 2).
// Which faces reach the depth buffer (front faces with polygon offset for modern.hw, back faces
// for modern.second-depth) is GL state set by the C++ pass, not this shader's.
#version 330 core
// @pass depth-only: no colour output, only depth (and stencil) written; which fragments are kept is the GL state of the pass (depth test, culling, polygon offset, stencil)
// @replaces legacy.hw 1
// @replaces legacy.woo 1
// @replaces legacy.second-depth 1
void main() {}
// @end depth-only
