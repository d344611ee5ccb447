// Stands in for a driver that tells of GPU resets, which no software rasteriser ever has: preloaded
// (LD_PRELOAD) into `player play --platform egl`, it answers the context's reset query with
// GL_GUILTY_CONTEXT_RESET on the GPU_RESET_AT'th call (counted over the whole process), or on every
// call from then on with GPU_RESET_REPEAT=1. Everything else goes to the real EGL and GL.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>
#include <string.h>

typedef void (*Function)(void);
typedef Function (*GetProcAddress)(const char*);

static unsigned long calls;

static unsigned fake_reset_status(void) {
  const char* at_text = getenv("GPU_RESET_AT");
  const char* repeat = getenv("GPU_RESET_REPEAT");
  const unsigned long at = at_text != NULL ? strtoul(at_text, NULL, 10) : 10;
  ++calls;
  const int reset = calls == at || (repeat != NULL && strcmp(repeat, "1") == 0 && calls >= at);
  return reset ? 0x8253u : 0u;  // GL_GUILTY_CONTEXT_RESET_KHR, GL_NO_ERROR
}

Function eglGetProcAddress(const char* name) {
  static GetProcAddress real;
  if (real == NULL) real = (GetProcAddress)dlsym(RTLD_NEXT, "eglGetProcAddress");
  if (strncmp(name, "glGetGraphicsResetStatus", 24) == 0) return (Function)fake_reset_status;
  return real(name);
}
