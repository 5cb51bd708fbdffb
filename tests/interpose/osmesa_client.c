/* tests/interpose/osmesa_client.c — a plain C program on Debian's OSMesa that uses the imaging
 * subset the way an old program does: linked to libOSMesa, no shadowlab header. Built and run
 * by legacy_clients_test.cpp, with libshadowlab-imaging.so preloaded and without.
 * Prints one "ok ..." line per check; exits 1 at the first check that fails. */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

enum { kSize = 16, kDepthBits = 24, kColorTableSizeA = 4, kColorTableSizeB = 8 };

static int fail(const char* what) {
  printf("FAIL %s\n", what);
  exit(1);
}

static OSMesaContext makeContext(GLubyte* buffer) {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         kDepthBits,
                         OSMESA_PROFILE,
                         OSMESA_COMPAT_PROFILE,
                         0};
  OSMesaContext c = OSMesaCreateContextAttribs(attribs, NULL);
  if (c == NULL) fail("OSMesaCreateContextAttribs");
  if (!OSMesaMakeCurrent(c, buffer, GL_UNSIGNED_BYTE, kSize, kSize)) fail("OSMesaMakeCurrent");
  return c;
}

/* A context per thread, each with a colour table of its own width: per-context state. */
struct ThreadCheck {
  int width;
  int seen;
};

static void* threadBody(void* arg) {
  struct ThreadCheck* t = (struct ThreadCheck*)arg;
  GLubyte* buffer = calloc(kSize * kSize, 4);
  OSMesaContext c = makeContext(buffer);
  GLubyte table[kColorTableSizeB * 4];
  memset(table, 128, sizeof table);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, t->width, GL_RGBA, GL_UNSIGNED_BYTE, table);
  GLint w = 0;
  glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, &w);
  t->seen = w;
  OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
  OSMesaDestroyContext(c);
  free(buffer);
  return NULL;
}

int main(void) {
  GLubyte* buffer = calloc(kSize * kSize, 4);
  OSMesaContext c = makeContext(buffer);

  const char* ext = (const char*)glGetString(GL_EXTENSIONS);
  if (ext == NULL || strstr(ext, "GL_ARB_imaging") == NULL)
    fail("no GL_ARB_imaging in GL_EXTENSIONS");
  printf("ok GL_ARB_imaging in glGetString(GL_EXTENSIONS)\n");

  GLint n = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &n);
  const char* last = (const char*)glGetStringi(GL_EXTENSIONS, (GLuint)(n - 1));
  if (last == NULL || strcmp(last, "GL_ARB_imaging") != 0)
    fail("glGetStringi's last is not GL_ARB_imaging");
  printf("ok glGetStringi(GL_EXTENSIONS, %d) = GL_ARB_imaging\n", n - 1);

  if ((void*)OSMesaGetProcAddress("glConvolutionFilter2D") != (void*)&glConvolutionFilter2D)
    fail("OSMesaGetProcAddress(glConvolutionFilter2D) is not the linked symbol");
  printf("ok OSMesaGetProcAddress gives the same glConvolutionFilter2D as the link\n");

  /* Errors of the emulation and of the driver, merged: 2.5 sticky flags. */
  while (glGetError() != GL_NO_ERROR) {}
  GLfloat kernel[9] = {0};
  glConvolutionFilter2D(GL_TEXTURE_2D, GL_LUMINANCE, 3, 3, GL_LUMINANCE, GL_FLOAT, kernel);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 3, GL_RGBA, GL_UNSIGNED_BYTE, kernel); /* not 2^n */
  glBindTexture(GL_TEXTURE_2D, 0);
  glTexParameteri(GL_TEXTURE_2D, 0x7fff, 0); /* the driver's INVALID_ENUM */
  GLenum e1 = glGetError(), e2 = glGetError(), e3 = glGetError();
  if (e1 != GL_INVALID_ENUM || e2 != GL_INVALID_VALUE || e3 != GL_NO_ERROR) {
    printf("errors: 0x%x 0x%x 0x%x\n", e1, e2, e3);
    fail("glGetError does not give INVALID_ENUM then INVALID_VALUE then NO_ERROR");
  }
  printf("ok glGetError: GL_INVALID_ENUM, GL_INVALID_VALUE, GL_NO_ERROR\n");

  /* Imaging state through glEnable / glIsEnabled / glGetIntegerv. */
  glEnable(GL_HISTOGRAM);
  GLint depth = 0;
  glGetIntegerv(GL_MAX_COLOR_MATRIX_STACK_DEPTH, &depth);
  if (!glIsEnabled(GL_HISTOGRAM) || depth < 2 || glGetError() != GL_NO_ERROR)
    fail("imaging enables and limits");
  glDisable(GL_HISTOGRAM);
  printf("ok glIsEnabled(GL_HISTOGRAM), GL_MAX_COLOR_MATRIX_STACK_DEPTH %d\n", depth);

  /* A colour matrix on the pixel path: swap red and blue through glDrawPixels. */
  const GLfloat swap[16] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0, 0, 1};
  glMatrixMode(GL_COLOR);
  glLoadMatrixf(swap);
  glMatrixMode(GL_MODELVIEW);
  glViewport(0, 0, kSize, kSize);
  glRasterPos2f(-1.0f, -1.0f);
  GLubyte red[4] = {255, 0, 0, 255}, got[4] = {0, 0, 0, 0};
  glDrawPixels(1, 1, GL_RGBA, GL_UNSIGNED_BYTE, red);
  glMatrixMode(GL_COLOR);
  glLoadIdentity();
  glMatrixMode(GL_MODELVIEW);
  glReadPixels(0, 0, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, got);
  if (got[0] != 0 || got[2] != 255) {
    printf("pixel %u %u %u %u\n", got[0], got[1], got[2], got[3]);
    fail("the colour matrix did not act on glDrawPixels");
  }
  printf("ok glDrawPixels through the colour matrix: red drawn as blue\n");

  struct ThreadCheck a = {kColorTableSizeA, 0}, b = {kColorTableSizeB, 0};
  pthread_t ta, tb;
  pthread_create(&ta, NULL, threadBody, &a);
  pthread_create(&tb, NULL, threadBody, &b);
  pthread_join(ta, NULL);
  pthread_join(tb, NULL);
  if (a.seen != kColorTableSizeA || b.seen != kColorTableSizeB) fail("per-thread contexts");
  GLint mine = -1;
  glGetColorTableParameteriv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, &mine);
  if (mine != 0) fail("this context's colour table changed with the others'");
  printf("ok contexts on two threads keep their own tables (%d, %d; this one %d)\n", a.seen, b.seen,
         mine);

  OSMesaDestroyContext(c);
  free(buffer);
  return 0;
}
