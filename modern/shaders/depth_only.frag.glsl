// depth_only.frag — light pass: only the depth buffer is written (Everitt §2, Fig. 2).
#version 330 core
void main() {}
