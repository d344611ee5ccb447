#!/usr/bin/env bash
# Runs COMMAND with Mesa's software driver kept mapped to the end (keep_mesa_driver.c says why).
#   keep_mesa_driver.sh SHIM COMMAND...
set -euo pipefail
shim=$1
shift
driver=$(ls /usr/lib/*/dri/swrast_dri.so /usr/lib/dri/swrast_dri.so 2>/dev/null | head -1 || true)
[ -n "$driver" ] || { echo "keep_mesa_driver.sh: no swrast_dri.so under /usr/lib/*/dri (libgl1-mesa-dri)" >&2; exit 2; }
# The shim loads before the sanitizer runtime the command brings, which ASan checks by default.
export KEEP_MESA_DRIVER=$driver LD_PRELOAD=$shim${LD_PRELOAD:+:$LD_PRELOAD}
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"
exec "$@"
