/* tests/interpose/glut_capture_preload.c — a test shim, preloaded ahead of the GL, that writes
 * down what a GLUT sends the GL to draw, the same way whichever GLUT it is (freeglut on GLX or
 * libshadowlab-glut.so on OSMesa) and however it draws (glBegin/glEnd or vertex arrays):
 *
 *   mark N                       glPassThrough(N) (the client's marker before each shape)
 *   prim MODE COUNT              a glBegin ... glEnd, or a glDrawArrays / glDrawElements
 *   x y z nx ny nz [s t]         COUNT lines: each vertex in the order the GL receives it, its
 *                                normal, and its texture coordinate when an array gives one
 *
 * Numbers are C99 hexadecimal floats (%a): exact. Vertex arrays are read where the GL would
 * read them (its pointers, sizes, types and strides, asked of the GL at the draw); a draw from
 * a buffer object, or of a type this shim does not read, is written as "unread" (the test
 * fails on it). Into the file $SHADOWLAB_GLUT_CAPTURE. The real functions are the next
 * definitions after this library (dlsym RTLD_NEXT). */
#define _GNU_SOURCE
#include <GL/gl.h>
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

#define EXPORT __attribute__((visibility("default")))
#define REAL(type, name)   \
  static type real_##name; \
  if (!real_##name) real_##name = (type)next(#name)

static FILE* out;

static void* next(const char* name) {
  void* p = dlsym(RTLD_NEXT, name);
  if (p == NULL) {
    fprintf(stderr, "glut_capture_preload: no %s after this library\n", name);
    exit(3);
  }
  return p;
}

static FILE* capture(void) {
  if (out == NULL) {
    const char* path = getenv("SHADOWLAB_GLUT_CAPTURE");
    out = fopen(path != NULL ? path : "/dev/null", "w");
    if (out == NULL) {
      fprintf(stderr, "glut_capture_preload: cannot write %s\n", path);
      exit(3);
    }
  }
  return out;
}

/* ---- immediate mode: the current normal is kept here, a vertex written as it comes ---- */
static GLfloat normal[3] = {0.0f, 0.0f, 1.0f}; /* GL's initial current normal */
static GLenum mode;
static long count;
static char* block;
static size_t blockSize;
static FILE* blockFile;

typedef void (*BeginFn)(GLenum);
typedef void (*EndFn)(void);
typedef void (*Normal3fFn)(GLfloat, GLfloat, GLfloat);
typedef void (*Normal3dFn)(GLdouble, GLdouble, GLdouble);
typedef void (*Normal3fvFn)(const GLfloat*);
typedef void (*Normal3dvFn)(const GLdouble*);
typedef void (*Vertex3fFn)(GLfloat, GLfloat, GLfloat);
typedef void (*Vertex3dFn)(GLdouble, GLdouble, GLdouble);
typedef void (*Vertex3fvFn)(const GLfloat*);
typedef void (*Vertex3dvFn)(const GLdouble*);

EXPORT void glBegin(GLenum m) {
  REAL(BeginFn, glBegin);
  mode = m;
  count = 0;
  blockFile = open_memstream(&block, &blockSize);
  real_glBegin(m);
}
EXPORT void glEnd(void) {
  REAL(EndFn, glEnd);
  real_glEnd();
  if (blockFile == NULL) return;
  fclose(blockFile);
  blockFile = NULL;
  fprintf(capture(), "prim %#x %ld\n%s", (unsigned)mode, count, block);
  free(block);
  block = NULL;
}
static void vertex(GLfloat x, GLfloat y, GLfloat z) {
  if (blockFile == NULL) return;
  fprintf(blockFile, "%a %a %a %a %a %a\n", x, y, z, normal[0], normal[1], normal[2]);
  ++count;
}
static void setNormal(GLfloat x, GLfloat y, GLfloat z) {
  normal[0] = x;
  normal[1] = y;
  normal[2] = z;
}
/* The GL keeps vertices and normals in single precision: doubles are rounded as it rounds. */
EXPORT void glNormal3f(GLfloat x, GLfloat y, GLfloat z) {
  REAL(Normal3fFn, glNormal3f);
  setNormal(x, y, z);
  real_glNormal3f(x, y, z);
}
EXPORT void glNormal3d(GLdouble x, GLdouble y, GLdouble z) {
  REAL(Normal3dFn, glNormal3d);
  setNormal((GLfloat)x, (GLfloat)y, (GLfloat)z);
  real_glNormal3d(x, y, z);
}
EXPORT void glNormal3fv(const GLfloat* v) {
  REAL(Normal3fvFn, glNormal3fv);
  setNormal(v[0], v[1], v[2]);
  real_glNormal3fv(v);
}
EXPORT void glNormal3dv(const GLdouble* v) {
  REAL(Normal3dvFn, glNormal3dv);
  setNormal((GLfloat)v[0], (GLfloat)v[1], (GLfloat)v[2]);
  real_glNormal3dv(v);
}
EXPORT void glVertex3f(GLfloat x, GLfloat y, GLfloat z) {
  REAL(Vertex3fFn, glVertex3f);
  vertex(x, y, z);
  real_glVertex3f(x, y, z);
}
EXPORT void glVertex3d(GLdouble x, GLdouble y, GLdouble z) {
  REAL(Vertex3dFn, glVertex3d);
  vertex((GLfloat)x, (GLfloat)y, (GLfloat)z);
  real_glVertex3d(x, y, z);
}
EXPORT void glVertex3fv(const GLfloat* v) {
  REAL(Vertex3fvFn, glVertex3fv);
  vertex(v[0], v[1], v[2]);
  real_glVertex3fv(v);
}
EXPORT void glVertex3dv(const GLdouble* v) {
  REAL(Vertex3dvFn, glVertex3dv);
  vertex((GLfloat)v[0], (GLfloat)v[1], (GLfloat)v[2]);
  real_glVertex3dv(v);
}

/* ---- vertex arrays: read as the GL's state says ---- */
typedef GLboolean (*IsEnabledFn)(GLenum);
typedef void (*GetIntegervFn)(GLenum, GLint*);
typedef void (*GetPointervFn)(GLenum, void**);
typedef void (*GetFloatvFn)(GLenum, GLfloat*);
typedef void (*DrawArraysFn)(GLenum, GLint, GLsizei);
typedef void (*DrawElementsFn)(GLenum, GLsizei, GLenum, const void*);
typedef void (*PassThroughFn)(GLfloat);

struct Array {
  int enabled, size, unread;
  GLenum type;
  GLint stride;
  const char* base;
};

static struct Array array(GLenum enable, GLenum pointer, GLenum size, GLenum type, GLenum stride,
                          int fixedSize) {
  REAL(IsEnabledFn, glIsEnabled);
  REAL(GetIntegervFn, glGetIntegerv);
  REAL(GetPointervFn, glGetPointerv);
  struct Array a = {0, 0, 0, GL_FLOAT, 0, NULL};
  GLint v = 0;
  a.enabled = real_glIsEnabled(enable);
  if (!a.enabled) return a;
  void* p = NULL;
  real_glGetPointerv(pointer, &p);
  a.base = (const char*)p;
  if (fixedSize > 0) {
    a.size = fixedSize;
  } else {
    real_glGetIntegerv(size, &v);
    a.size = v;
  }
  real_glGetIntegerv(type, &v);
  a.type = (GLenum)v;
  real_glGetIntegerv(stride, &v);
  a.stride = v;
  a.unread = a.type != GL_FLOAT && a.type != GL_DOUBLE;
  return a;
}

static float element(const struct Array* a, long i, int c) {
  const size_t bytes = a->type == GL_DOUBLE ? sizeof(GLdouble) : sizeof(GLfloat);
  const size_t step = a->stride != 0 ? (size_t)a->stride : bytes * (size_t)a->size;
  const char* p = a->base + step * (size_t)i + bytes * (size_t)c;
  return a->type == GL_DOUBLE ? (float)*(const GLdouble*)p : *(const GLfloat*)p;
}

/* One draw, its vertices given by `index(k)`. */
static void drawn(GLenum m, long n, const void* indices, GLenum indexType, GLint first) {
  REAL(GetIntegervFn, glGetIntegerv);
  REAL(GetFloatvFn, glGetFloatv);
  FILE* f = capture();
  GLint buffer = 0, elementBuffer = 0;
  real_glGetIntegerv(GL_ARRAY_BUFFER_BINDING, &buffer);
  real_glGetIntegerv(GL_ELEMENT_ARRAY_BUFFER_BINDING, &elementBuffer);
  const struct Array v = array(GL_VERTEX_ARRAY, GL_VERTEX_ARRAY_POINTER, GL_VERTEX_ARRAY_SIZE,
                               GL_VERTEX_ARRAY_TYPE, GL_VERTEX_ARRAY_STRIDE, 0);
  const struct Array nr = array(GL_NORMAL_ARRAY, GL_NORMAL_ARRAY_POINTER, 0, GL_NORMAL_ARRAY_TYPE,
                                GL_NORMAL_ARRAY_STRIDE, 3);
  const struct Array t =
      array(GL_TEXTURE_COORD_ARRAY, GL_TEXTURE_COORD_ARRAY_POINTER, GL_TEXTURE_COORD_ARRAY_SIZE,
            GL_TEXTURE_COORD_ARRAY_TYPE, GL_TEXTURE_COORD_ARRAY_STRIDE, 0);
  const int indexUnread = indices != NULL && indexType != GL_UNSIGNED_SHORT &&
                          indexType != GL_UNSIGNED_INT && indexType != GL_UNSIGNED_BYTE;
  if (buffer != 0 || elementBuffer != 0 || !v.enabled || v.unread || nr.unread || t.unread ||
      indexUnread) {
    fprintf(f, "unread %#x %ld\n", (unsigned)m, n);
    return;
  }
  GLfloat current[3];
  real_glGetFloatv(GL_CURRENT_NORMAL, current);
  fprintf(f, "prim %#x %ld\n", (unsigned)m, n);
  for (long k = 0; k < n; ++k) {
    long i = first + k;
    if (indices != NULL)
      i = indexType == GL_UNSIGNED_SHORT ? ((const GLushort*)indices)[k]
          : indexType == GL_UNSIGNED_INT ? (long)((const GLuint*)indices)[k]
                                         : ((const GLubyte*)indices)[k];
    fprintf(f, "%a %a %a", element(&v, i, 0), element(&v, i, 1),
            v.size > 2 ? element(&v, i, 2) : 0.0f);
    for (int c = 0; c < 3; ++c) fprintf(f, " %a", nr.enabled ? element(&nr, i, c) : current[c]);
    if (t.enabled) fprintf(f, " %a %a", element(&t, i, 0), element(&t, i, 1));
    fprintf(f, "\n");
  }
}

EXPORT void glDrawArrays(GLenum m, GLint first, GLsizei n) {
  REAL(DrawArraysFn, glDrawArrays);
  drawn(m, n, NULL, 0, first);
  real_glDrawArrays(m, first, n);
}
EXPORT void glDrawElements(GLenum m, GLsizei n, GLenum type, const void* indices) {
  REAL(DrawElementsFn, glDrawElements);
  drawn(m, n, indices, type, 0);
  real_glDrawElements(m, n, type, indices);
}
EXPORT void glPassThrough(GLfloat token) {
  REAL(PassThroughFn, glPassThrough);
  fprintf(capture(), "mark %g\n", token);
  fflush(capture());
  real_glPassThrough(token);
}
