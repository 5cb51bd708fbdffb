/* tests/interpose/bad_input_client.c — a plain C program on Debian's OSMesa that hands the
 * imaging subset wrong enums and sizes, as a careless old program might: each call must raise
 * the error the specification names (glspec121 2.5 and 3.6.3, the "Errors" sections of
 * SGI_color_table, EXT_convolution, HP_convolution_border_modes, EXT_histogram and
 * SGI_color_matrix), read through glGetError, and nothing may crash. Run by
 * legacy_clients_test.cpp with libshadowlab-imaging.so preloaded.
 * Prints "ok NAME" per case, "FAIL NAME ..." for a wrong error; exits 1 when any failed. */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/glext.h>
#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>

enum { kSize = 16, kDepthBits = 24, kBogusEnum = 0x7fff, kMaxFilterSide = 64 };

static int failures = 0;
static float data[kMaxFilterSide * kMaxFilterSide * 4]; /* zeros: big enough for every call */

static void drain(void) {
  while (glGetError() != GL_NO_ERROR) {}
}

/* The error the last call raised must be `want`, and only that one. */
static void expect(const char* name, GLenum want) {
  const GLenum got = glGetError();
  const GLenum after = glGetError();
  if (got != want || after != GL_NO_ERROR) {
    printf("FAIL %s: glGetError 0x%x then 0x%x, want 0x%x then 0\n", name, got, after, want);
    ++failures;
  } else {
    printf("ok %s\n", name);
  }
  drain();
}

int main(void) {
  const int attribs[] = {OSMESA_FORMAT,
                         OSMESA_RGBA,
                         OSMESA_DEPTH_BITS,
                         kDepthBits,
                         OSMESA_PROFILE,
                         OSMESA_COMPAT_PROFILE,
                         0};
  OSMesaContext c = OSMesaCreateContextAttribs(attribs, NULL);
  GLubyte* buffer = calloc(kSize * kSize, 4);
  if (c == NULL || buffer == NULL ||
      !OSMesaMakeCurrent(c, buffer, GL_UNSIGNED_BYTE, kSize, kSize)) {
    printf("FAIL no OSMesa context\n");
    return 1;
  }
  drain();

  /* Colour tables (SGI_color_table "Errors"; 3.6.3). */
  glColorTable(GL_HISTOGRAM, GL_RGBA, 4, GL_RGBA, GL_FLOAT, data);
  expect("glColorTable target GL_HISTOGRAM", GL_INVALID_ENUM);
  glColorTable(GL_COLOR_TABLE, kBogusEnum, 4, GL_RGBA, GL_FLOAT, data);
  expect("glColorTable internal format bogus", GL_INVALID_ENUM);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 4, GL_DEPTH_COMPONENT, GL_FLOAT, data);
  expect("glColorTable format GL_DEPTH_COMPONENT", GL_INVALID_ENUM);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 4, GL_RGBA, kBogusEnum, data);
  expect("glColorTable type bogus", GL_INVALID_ENUM);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 4, GL_RGBA, GL_UNSIGNED_SHORT_5_6_5, data);
  expect("glColorTable packed type GL_UNSIGNED_SHORT_5_6_5 with GL_RGBA", GL_INVALID_OPERATION);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 3, GL_RGBA, GL_FLOAT, data);
  expect("glColorTable width 3 (not a power of two)", GL_INVALID_VALUE);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, -2, GL_RGBA, GL_FLOAT, data);
  expect("glColorTable width -2", GL_INVALID_VALUE);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 1 << 30, GL_RGBA, GL_FLOAT, data);
  expect("glColorTable width 2^30 (too large, nothing read)", GL_TABLE_TOO_LARGE);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 8, GL_RGBA, GL_FLOAT, data);
  glColorSubTable(GL_COLOR_TABLE, 6, 4, GL_RGBA, GL_FLOAT, data);
  expect("glColorSubTable past the end", GL_INVALID_VALUE);
  glColorSubTable(GL_COLOR_TABLE, -1, 2, GL_RGBA, GL_FLOAT, data);
  expect("glColorSubTable start -1", GL_INVALID_VALUE);
  glCopyColorTable(GL_COLOR_TABLE, GL_RGBA, 0, 0, 5);
  expect("glCopyColorTable width 5", GL_INVALID_VALUE);
  glColorTableParameterfv(GL_COLOR_TABLE, GL_COLOR_TABLE_WIDTH, data);
  expect("glColorTableParameterfv pname GL_COLOR_TABLE_WIDTH", GL_INVALID_ENUM);
  glGetColorTable(GL_PROXY_COLOR_TABLE, GL_RGBA, GL_FLOAT, data);
  expect("glGetColorTable of a proxy", GL_INVALID_ENUM);
  {
    GLint v = 0;
    glGetColorTableParameteriv(GL_COLOR_TABLE, kBogusEnum, &v);
    expect("glGetColorTableParameteriv pname bogus", GL_INVALID_ENUM);
  }

  /* Convolution (EXT_convolution, HP_convolution_border_modes "Errors"). */
  glConvolutionFilter2D(GL_CONVOLUTION_1D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, data);
  expect("glConvolutionFilter2D target GL_CONVOLUTION_1D", GL_INVALID_ENUM);
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, kMaxFilterSide, 3, GL_RGBA, GL_FLOAT, data);
  expect("glConvolutionFilter2D width 64 (over the maximum)", GL_INVALID_VALUE);
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, -1, GL_RGBA, GL_FLOAT, data);
  expect("glConvolutionFilter2D height -1", GL_INVALID_VALUE);
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_INTENSITY, GL_FLOAT, data);
  expect("glConvolutionFilter2D format GL_INTENSITY (not a pixel format)", GL_INVALID_ENUM);
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_UNSIGNED_BYTE_3_3_2, data);
  expect("glConvolutionFilter2D packed type GL_UNSIGNED_BYTE_3_3_2 with GL_RGBA",
         GL_INVALID_OPERATION);
  glConvolutionFilter1D(GL_CONVOLUTION_1D, GL_RGBA, -3, GL_RGBA, GL_FLOAT, data);
  expect("glConvolutionFilter1D width -3", GL_INVALID_VALUE);
  glSeparableFilter2D(GL_SEPARABLE_2D, GL_RGBA, kMaxFilterSide, 3, GL_RGBA, GL_FLOAT, data, data);
  expect("glSeparableFilter2D width 64", GL_INVALID_VALUE);
  glCopyConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 0, 0, kMaxFilterSide, 3);
  expect("glCopyConvolutionFilter2D width 64", GL_INVALID_VALUE);
  glConvolutionParameteri(GL_CONVOLUTION_2D, GL_CONVOLUTION_BORDER_MODE, GL_REPEAT);
  expect("glConvolutionParameteri border mode GL_REPEAT", GL_INVALID_ENUM);
  glConvolutionParameteri(GL_HISTOGRAM, GL_CONVOLUTION_BORDER_MODE, GL_REDUCE);
  expect("glConvolutionParameteri target GL_HISTOGRAM", GL_INVALID_ENUM);
  {
    GLint v = 0;
    glGetConvolutionParameteriv(GL_CONVOLUTION_1D, GL_CONVOLUTION_HEIGHT, &v);
    expect("glGetConvolutionParameteriv 1D height", GL_INVALID_ENUM);
  }

  /* Histogram and minmax (EXT_histogram "Errors"). */
  glHistogram(GL_HISTOGRAM, 3, GL_RGBA, GL_FALSE);
  expect("glHistogram width 3", GL_INVALID_VALUE);
  glHistogram(GL_HISTOGRAM, -4, GL_RGBA, GL_FALSE);
  expect("glHistogram width -4", GL_INVALID_VALUE);
  glHistogram(GL_HISTOGRAM, 1 << 30, GL_RGBA, GL_FALSE);
  expect("glHistogram width 2^30 (too large, nothing allocated)", GL_TABLE_TOO_LARGE);
  glHistogram(GL_HISTOGRAM, 16, GL_DEPTH_COMPONENT, GL_FALSE);
  expect("glHistogram internal format GL_DEPTH_COMPONENT", GL_INVALID_ENUM);
  glHistogram(GL_COLOR_TABLE, 16, GL_RGBA, GL_FALSE);
  expect("glHistogram target GL_COLOR_TABLE", GL_INVALID_ENUM);
  glMinmax(GL_HISTOGRAM, GL_RGBA, GL_FALSE);
  expect("glMinmax target GL_HISTOGRAM", GL_INVALID_ENUM);
  glResetHistogram(GL_MINMAX);
  expect("glResetHistogram target GL_MINMAX", GL_INVALID_ENUM);
  glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_DEPTH_COMPONENT, GL_FLOAT, data);
  expect("glGetHistogram format GL_DEPTH_COMPONENT", GL_INVALID_ENUM);
  glGetHistogram(GL_HISTOGRAM, GL_FALSE, GL_RGB, GL_UNSIGNED_INT_8_8_8_8, data);
  expect("glGetHistogram packed type GL_UNSIGNED_INT_8_8_8_8 with GL_RGB", GL_INVALID_OPERATION);
  glGetMinmax(GL_MINMAX, GL_FALSE, GL_RGBA, kBogusEnum, data);
  expect("glGetMinmax type bogus", GL_INVALID_ENUM);
  {
    GLint v = 0;
    glGetMinmaxParameteriv(GL_MINMAX, GL_HISTOGRAM_WIDTH, &v);
    expect("glGetMinmaxParameteriv pname GL_HISTOGRAM_WIDTH", GL_INVALID_ENUM);
  }

  /* The colour matrix stack (2.10.2 stack errors in glMatrixMode(GL_COLOR)). */
  glMatrixMode(GL_COLOR);
  glPopMatrix();
  expect("glPopMatrix on an empty colour matrix stack", GL_STACK_UNDERFLOW);
  {
    GLint depth = 0, i;
    glGetIntegerv(GL_MAX_COLOR_MATRIX_STACK_DEPTH, &depth);
    for (i = 1; i < depth; ++i) glPushMatrix();
    drain();
    glPushMatrix();
    expect("glPushMatrix past GL_MAX_COLOR_MATRIX_STACK_DEPTH", GL_STACK_OVERFLOW);
    for (i = 1; i < depth; ++i) glPopMatrix();
  }
  glMatrixMode(GL_MODELVIEW);

  /* The pixel paths with a stage of the pipeline on: bad arguments still fail first. */
  glConvolutionFilter2D(GL_CONVOLUTION_2D, GL_RGBA, 3, 3, GL_RGBA, GL_FLOAT, data);
  glEnable(GL_CONVOLUTION_2D);
  drain();
  glCopyPixels(0, 0, kSize, kSize, kBogusEnum);
  expect("glCopyPixels type bogus under convolution", GL_INVALID_ENUM);
  glReadPixels(0, 0, -1, kSize, GL_RGBA, GL_UNSIGNED_BYTE, data);
  expect("glReadPixels width -1 under convolution", GL_INVALID_VALUE);
  glDrawPixels(kSize, kSize, GL_RGBA, kBogusEnum, data);
  expect("glDrawPixels type bogus under convolution", GL_INVALID_ENUM);
  glDisable(GL_CONVOLUTION_2D);
  glEnable(kBogusEnum);
  expect("glEnable bogus (the driver's error)", GL_INVALID_ENUM);

  /* Between glBegin and glEnd, every imaging command is GL_INVALID_OPERATION (2.6.3). */
  glBegin(GL_POINTS);
  glColorTable(GL_COLOR_TABLE, GL_RGBA, 4, GL_RGBA, GL_FLOAT, data);
  glEnd();
  expect("glColorTable between glBegin and glEnd", GL_INVALID_OPERATION);

  /* Two errors in a row: both come back, in order (2.5), then GL_NO_ERROR. */
  glHistogram(GL_HISTOGRAM, 3, GL_RGBA, GL_FALSE);
  glEnable(kBogusEnum);
  {
    const GLenum e1 = glGetError(), e2 = glGetError(), e3 = glGetError();
    if (e1 == GL_INVALID_VALUE && e2 == GL_INVALID_ENUM && e3 == GL_NO_ERROR) {
      printf("ok two errors in order: emulation's then driver's\n");
    } else {
      printf("FAIL two errors in order: 0x%x 0x%x 0x%x\n", e1, e2, e3);
      ++failures;
    }
  }

  OSMesaMakeCurrent(NULL, NULL, 0, 0, 0);
  OSMesaDestroyContext(c);
  free(buffer);
  printf("%d failed\n", failures);
  return failures == 0 ? 0 : 1;
}
