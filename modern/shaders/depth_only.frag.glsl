// depth_only.frag — light pass: only the depth buffer is written (Everitt §2, Fig. 2).
// Which faces reach the depth buffer (front faces with polygon offset for modern.hw, back faces
// for modern.second-depth) is GL state set by the C++ pass, not this shader's.
#version 330 core
// @pass depth-only: no colour output, only depth (and stencil) written; which fragments are kept is the GL state of the pass (depth test, culling, polygon offset, stencil)
// @replaces legacy.hw pass 1 depth from light
// @replaces legacy.woo pass 1 first depth layer
// @replaces legacy.second-depth pass 1 back faces from light
void main() {}
// @end depth-only
