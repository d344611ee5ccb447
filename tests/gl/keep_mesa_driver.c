// Preloaded into window tests (tests/gl/keep_mesa_driver.sh): keeps Mesa's software driver mapped
// until the process ends. Mesa unloads it at exit (libEGL's atexit, or SDL's eglTerminate) before
// LeakSanitizer looks, and memory that only the driver's own globals still point to then reads as
// leaked from an "<unknown module>": a false report, which a suppression cannot name. With the
// driver mapped, LeakSanitizer scans its globals as it does every other library's.
#define _GNU_SOURCE
#include <dlfcn.h>
#include <stdlib.h>

__attribute__((constructor)) static void keep_mesa_driver(void) {
  const char* path = getenv("KEEP_MESA_DRIVER");
  if (path != NULL && *path != '\0') dlopen(path, RTLD_LAZY | RTLD_NODELETE);
}
