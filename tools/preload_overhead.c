/* tools/preload_overhead.c — the drop-in imaging library's cost on a program that draws a lot
 * and uses no imaging: an OSMesa program of many small transformed objects (per object: matrix
 * push, translate, rotate, enable/disable, a short glBegin/glEnd run, pop), timed over frames.
 * scripts/preload_overhead.sh runs it with and without LD_PRELOAD and prints the ratio.
 * Usage: preload_overhead FRAMES OBJECTS
 * Prints: "ms_per_frame WALL cpu_ms_per_frame CPU" (CPU: the process's CPU time, all threads;
 * on a shared machine it counts the work, where wall time also counts the wait for a core). */
#define GL_GLEXT_PROTOTYPES 1
#include <GL/gl.h>
#include <GL/osmesa.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>

enum { kSize = 256, kDepthBits = 24, kTrianglesPerObject = 8 };

static double clock_ms(clockid_t clock) {
  struct timespec t;
  clock_gettime(clock, &t);
  return (double)t.tv_sec * 1e3 + (double)t.tv_nsec / 1e6;
}

static void draw_frame(int objects) {
  int i, k;
  glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  for (i = 0; i < objects; ++i) {
    const float x = (float)(i % 40) / 20.0f - 1.0f, y = (float)(i / 40 % 40) / 20.0f - 1.0f;
    glPushMatrix();
    glTranslatef(x, y, 0.0f);
    glRotatef((float)(i * 7 % 360), 0.0f, 0.0f, 1.0f);
    if (i % 2)
      glEnable(GL_BLEND);
    else
      glDisable(GL_BLEND);
    glBegin(GL_TRIANGLES);
    for (k = 0; k < kTrianglesPerObject; ++k) {
      glColor3f((float)k / kTrianglesPerObject, 0.5f, 1.0f - (float)k / kTrianglesPerObject);
      glVertex3f(0.0f, 0.0f, 0.0f);
      glVertex3f(0.03f, (float)k * 0.004f, 0.0f);
      glVertex3f(0.0f, 0.03f, 0.0f);
    }
    glEnd();
    glPopMatrix();
  }
  glFinish();
}

/* The timed frames, in a function of their own so that an instruction count can be limited
 * to them (valgrind --tool=callgrind --toggle-collect=timed_frames, scripts/preload_overhead.sh
 * COUNT=instructions). */
__attribute__((noinline)) void timed_frames(int frames, int objects) {
  for (int f = 0; f < frames; ++f) draw_frame(objects);
}

int main(int argc, char** argv) {
  if (argc != 3 || atoi(argv[1]) <= 0 || atoi(argv[2]) <= 0) {
    fprintf(stderr, "usage: preload_overhead FRAMES OBJECTS\n");
    return 2;
  }
  const int frames = atoi(argv[1]), objects = atoi(argv[2]);
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
    fprintf(stderr, "preload_overhead: no OSMesa context\n");
    return 3;
  }
  glEnable(GL_DEPTH_TEST);
  draw_frame(objects); /* warm-up: shaders compiled, buffers allocated */
  const double start = clock_ms(CLOCK_MONOTONIC), cpu_start = clock_ms(CLOCK_PROCESS_CPUTIME_ID);
  timed_frames(frames, objects);
  const double cpu = clock_ms(CLOCK_PROCESS_CPUTIME_ID) - cpu_start;
  printf("ms_per_frame %.4f cpu_ms_per_frame %.4f\n", (clock_ms(CLOCK_MONOTONIC) - start) / frames,
         cpu / frames);
  OSMesaDestroyContext(c);
  free(buffer);
  return 0;
}
