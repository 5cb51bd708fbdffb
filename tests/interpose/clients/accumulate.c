/* tests/interpose/clients/accumulate.c — a GLUT program in the style of the OpenGL
 * Programming Guide's accumulation and imaging chapters, written for shadowlab's tests from
 * the book's description of the techniques (no code of the book's): a lit torus and sphere
 * antialiased by jittering the projection by sub-pixel offsets and averaging the passes in the
 * accumulation buffer (glAccum GL_ACCUM / GL_RETURN), then optionally turned to grey by
 * copying the window onto itself through a colour matrix (glCopyPixels with
 * glMatrixMode(GL_COLOR)). Keys: 'a' toggles 1 and 8 passes, 'g' toggles the grey matrix.
 * Built like the Red Book programs (scripts/build_legacy_client.sh) and run by run-legacy. */
#include <stdio.h>
#include <stdlib.h>

#include "glad/gl.h"
#include "glut_wrap.h"

enum { kWidth = 160, kHeight = 120, kManyPasses = 8 };

/* Sub-pixel offsets of the passes, in pixels: a regular 8-sample pattern in [-0.5, 0.5). */
static const float kJitter[kManyPasses][2] = {
    {-0.375f, -0.125f}, {-0.125f, 0.375f},  {0.125f, -0.375f}, {0.375f, 0.125f},
    {-0.375f, 0.375f},  {-0.125f, -0.375f}, {0.125f, 0.125f},  {0.375f, -0.125f}};

/* Luminance weights (ITU-R BT.601) in every row: R' = G' = B' = 0.299 R + 0.587 G + 0.114 B. */
static const GLfloat kGrey[16] = {0.299f, 0.299f, 0.299f, 0.0f, 0.587f, 0.587f, 0.587f, 0.0f,
                                  0.114f, 0.114f, 0.114f, 0.0f, 0.0f,   0.0f,   0.0f,   1.0f};

static int passes = 1;
static int grey = 0;
static int width = kWidth, height = kHeight;

static void init(void) {
  const GLfloat light[4] = {1.0f, 1.0f, 1.0f, 0.0f};
  if (!glutExtensionSupported("GL_ARB_imaging")) {
    fprintf(stderr, "accumulate: needs GL_ARB_imaging\n");
    exit(1);
  }
  glEnable(GL_LIGHTING);
  glEnable(GL_LIGHT0);
  glLightfv(GL_LIGHT0, GL_POSITION, light);
  glEnable(GL_DEPTH_TEST);
  glEnable(GL_COLOR_MATERIAL);
  glClearColor(0.1f, 0.1f, 0.2f, 0.0f);
  glClearAccum(0.0f, 0.0f, 0.0f, 0.0f);
}

/* The projection shifted by (dx, dy) pixels: a translation in clip space of 2 d / size. */
static void project(float dx, float dy) {
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glTranslatef(2.0f * dx / (float)width, 2.0f * dy / (float)height, 0.0f);
  glFrustum(-1.0, 1.0, -0.75, 0.75, 2.0, 10.0);
  glMatrixMode(GL_MODELVIEW);
}

static void scene(void) {
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  glLoadIdentity();
  glTranslatef(0.0f, 0.0f, -5.0f);
  glRotatef(30.0f, 1.0f, 0.0f, 0.0f);
  glColor3f(0.9f, 0.5f, 0.1f);
  glutSolidTorus(0.3, 1.0, 16, 32);
  glColor3f(0.2f, 0.6f, 0.9f);
  glutSolidSphere(0.6, 24, 16);
}

static void display(void) {
  int i;
  glClear(GL_ACCUM_BUFFER_BIT);
  for (i = 0; i < passes; ++i) {
    project(passes == 1 ? 0.0f : kJitter[i][0], passes == 1 ? 0.0f : kJitter[i][1]);
    scene();
    glAccum(GL_ACCUM, 1.0f / (float)passes);
  }
  glAccum(GL_RETURN, 1.0f);
  if (grey) {
    /* The window onto itself through the colour matrix, in a pixel-exact projection. */
    glDisable(GL_LIGHTING);
    glDisable(GL_DEPTH_TEST);
    glMatrixMode(GL_PROJECTION);
    glLoadIdentity();
    glOrtho(0, width, 0, height, -1, 1);
    glMatrixMode(GL_MODELVIEW);
    glLoadIdentity();
    glMatrixMode(GL_COLOR);
    glLoadMatrixf(kGrey);
    glMatrixMode(GL_MODELVIEW);
    glRasterPos2i(0, 0);
    glCopyPixels(0, 0, width, height, GL_COLOR);
    glMatrixMode(GL_COLOR);
    glLoadIdentity();
    glMatrixMode(GL_MODELVIEW);
    glEnable(GL_LIGHTING);
    glEnable(GL_DEPTH_TEST);
  }
  glFlush();
}

static void reshape(int w, int h) {
  width = w;
  height = h;
  glViewport(0, 0, w, h);
}

static void keyboard(unsigned char key, int x, int y) {
  (void)x;
  (void)y;
  switch (key) {
    case 'a': passes = passes == 1 ? kManyPasses : 1; break;
    case 'g': grey = !grey; break;
    case 27: exit(0);
  }
  glutPostRedisplay();
}

int main(int argc, char** argv) {
  glutInit(&argc, argv);
  glutInitDisplayMode(GLUT_SINGLE | GLUT_RGB | GLUT_ACCUM | GLUT_DEPTH);
  glutInitWindowSize(kWidth, kHeight);
  glutCreateWindow(argv[0]);
  gladLoaderLoadGL();
  init();
  glutReshapeFunc(reshape);
  glutKeyboardFunc(keyboard);
  glutDisplayFunc(display);
  glutMainLoop();
  gladLoaderUnloadGL();
  return 0;
}
