/* tests/interpose/clients/glut_shapes.c — every GLUT shape, solid and wire, once, each in a
 * cell of a 6 x 4 grid, lit and flat-shaded as the Red Book's accanti.c draws its shapes (the
 * flat colour is the provoking vertex's: the order of vertices shows). Written for shadowlab's
 * tests. Before each shape: glPassThrough(N) (the "mark N" of
 * tests/interpose/glut_capture_preload.c, which writes down what the GLUT sends the GL) and a
 * line "N call" on stdout naming the call. The arguments include accanti.c's (torus, cube,
 * sphere, octahedron) and edge cases: a cube of side 1 (freeglut's unscaled path), the fewest
 * stacks a sphere has, the teapot at a second size (its vertices are made again, its normals
 * kept). With $SHADOWLAB_GLUT_CAPTURE set the program exits after the first display; else it
 * shows one frame (run by `shadowlab run-legacy`, which ends it). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "glut_wrap.h"

enum { kColumns = 6, kRows = 4, kCellPixels = 64 };
static const GLfloat kShapeScale = 0.28f; /* the largest shape (the teapot) fits its cell */

static int shape = 0;

/* The next shape's marker, and its cell: row by row from the top left, turned to show three
 * sides. Wire shapes are drawn without the depth test: their faces' loops draw each edge twice
 * at the same depth, and which of the two stays would turn on the depth buffer's format. */
static void mark(const char* call) {
  ++shape;
  printf("%d %s\n", shape, call);
  glPassThrough((GLfloat)shape);
  if (strstr(call, "Wire") != NULL)
    glDisable(GL_DEPTH_TEST);
  else
    glEnable(GL_DEPTH_TEST);
  glLoadIdentity();
  glTranslatef(-0.5f * kColumns + 0.5f + (float)((shape - 1) % kColumns),
               0.5f * kRows - 0.5f - (float)((shape - 1) / kColumns), 0.0f);
  glRotatef(30.0f, 1.0f, 0.0f, 0.0f);
  glRotatef(-35.0f, 0.0f, 1.0f, 0.0f);
  glScalef(kShapeScale, kShapeScale, kShapeScale);
}

static void init(void) {
  const GLfloat light[4] = {1.0f, 2.0f, 3.0f, 0.0f};
  const GLfloat diffuse[4] = {0.3f, 0.5f, 0.7f, 1.0f};
  const GLfloat specular[4] = {0.4f, 0.4f, 0.4f, 1.0f};
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glLightfv(GL_LIGHT0, GL_POSITION, light);
  glMaterialfv(GL_FRONT, GL_DIFFUSE, diffuse);
  glMaterialfv(GL_FRONT, GL_SPECULAR, specular);
  glMaterialf(GL_FRONT, GL_SHININESS, 50.0f);
  glEnable(GL_DEPTH_TEST);
  glShadeModel(GL_FLAT);
  glEnable(GL_NORMALIZE); /* the cells scale the shapes, and with them their normals */
  glClearColor(0.0f, 0.0f, 0.0f, 0.0f);
}

static void reshape(int w, int h) {
  glViewport(0, 0, w, h);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(-0.5 * kColumns, 0.5 * kColumns, -0.5 * kRows, 0.5 * kRows, -10.0, 10.0);
  glMatrixMode(GL_MODELVIEW);
}

#define SHAPE(call) \
  mark(#call);      \
  call

static void display(void) {
  shape = 0;
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  SHAPE(glutSolidSphere(1.0, 16, 16));
  SHAPE(glutWireSphere(0.75, 7, 5));
  SHAPE(glutSolidSphere(0.5, 3, 2));
  SHAPE(glutSolidCube(1.5));
  SHAPE(glutSolidCube(1.0));
  SHAPE(glutWireCube(1.0));
  SHAPE(glutWireCube(2.0));
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
  if (getenv("SHADOWLAB_GLUT_CAPTURE") != NULL) exit(0);
}

int main(int argc, char** argv) {
  glutInit(&argc, argv);
  glutInitDisplayMode(GLUT_SINGLE | GLUT_RGB | GLUT_DEPTH);
  glutInitWindowSize(kColumns * kCellPixels, kRows * kCellPixels);
  glutCreateWindow(argv[0]);
  init();
  glutReshapeFunc(reshape);
  glutDisplayFunc(display);
  glutMainLoop();
  return 0;
}
