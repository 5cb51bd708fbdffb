/* interpose/include/glad/gl.h — the loader header the Mesa demos build gives the Red Book
 * programs, reduced to what they use: the system's GL header (every OpenGL 1.2 entry point,
 * the imaging subset included, is a libGL symbol) and gladLoaderLoadGL / gladLoaderUnloadGL.
 * Nothing is loaded: the program links libGL, and LD_PRELOAD can come before it.
 * Written for shadowlab (scripts/build_legacy_client.sh). */
#ifndef SHADOWLAB_GLAD_GL_H
#define SHADOWLAB_GLAD_GL_H

#include <GL/gl.h>
#include <stdio.h>

/* The context's version as glad reports it: major * 10000 + minor, 0 without a context. */
static inline int gladLoaderLoadGL(void) {
  const char* version = (const char*)glGetString(GL_VERSION);
  int major = 0, minor = 0;
  if (version == NULL || sscanf(version, "%d.%d", &major, &minor) != 2) return 0;
  return major * 10000 + minor;
}

static inline void gladLoaderUnloadGL(void) {}

#endif
