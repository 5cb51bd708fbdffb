/* interpose/include/glut_wrap.h — the GLUT header of the Mesa demos build: the system's
 * GLUT (Debian: freeglut). Written for shadowlab (scripts/build_legacy_client.sh). */
#ifndef SHADOWLAB_GLUT_WRAP_H
#define SHADOWLAB_GLUT_WRAP_H

#include <GL/glut.h>

#endif
