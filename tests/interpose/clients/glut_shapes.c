/* tests/interpose/clients/glut_shapes.c — every GLUT shape, solid and wire, once, for
 * tests/interpose/glut_capture_preload.c to write down what the GLUT sends the GL. Written for
 * shadowlab's tests. Before each shape: glPassThrough(N) (the capture's "mark N") and a line
 * "N call" on stdout naming the call. The arguments include the Red Book's (accanti.c's torus,
 * cube, sphere) and edge cases: a cube of side 1 (freeglut's unscaled path), the fewest
 * stacks a sphere has, the teapot at a second size (its vertices are made again, its normals
 * kept). The program exits after the first display. */
#include <stdio.h>
#include <stdlib.h>

#include "glut_wrap.h"

static int shape = 0;

static void mark(const char* call) {
  ++shape;
  printf("%d %s\n", shape, call);
  glPassThrough((GLfloat)shape);
}

#define SHAPE(call) \
  mark(#call);      \
  call

static void display(void) {
  SHAPE(glutSolidSphere(1.0, 16, 16));
  SHAPE(glutWireSphere(0.75, 7, 5));
  SHAPE(glutSolidSphere(0.5, 3, 2));
  SHAPE(glutSolidCube(1.5));
  SHAPE(glutSolidCube(1.0));
  SHAPE(glutWireCube(1.0));
  SHAPE(glutWireCube(2.5));
  SHAPE(glutSolidCone(1.0, 2.0, 8, 3));
  SHAPE(glutWireCone(0.6, 1.3, 5, 4));
  SHAPE(glutSolidTorus(0.275, 0.85, 16, 16));
  SHAPE(glutWireTorus(0.3, 1.0, 5, 7));
  SHAPE(glutSolidTeapot(1.0));
  SHAPE(glutSolidTeapot(0.5));
  SHAPE(glutWireTeapot(0.75));
  SHAPE(glutSolidDodecahedron());
  SHAPE(glutWireDodecahedron());
  SHAPE(glutSolidOctahedron());
  SHAPE(glutWireOctahedron());
  SHAPE(glutSolidTetrahedron());
  SHAPE(glutWireTetrahedron());
  SHAPE(glutSolidIcosahedron());
  SHAPE(glutWireIcosahedron());
  mark("end");
  glFinish();
  fflush(stdout);
  exit(0);
}

int main(int argc, char** argv) {
  glutInit(&argc, argv);
  glutInitDisplayMode(GLUT_SINGLE | GLUT_RGB | GLUT_DEPTH);
  glutInitWindowSize(64, 64);
  glutCreateWindow(argv[0]);
  glutDisplayFunc(display);
  glutMainLoop();
  return 0;
}
