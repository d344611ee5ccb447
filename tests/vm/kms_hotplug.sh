#!/usr/bin/env bash
# Runs inside the test VM (tools/vm/run), as root, on vkms: the player starts with its display
# switched off, waits for one, plays when it comes, stops presenting when it goes (keeping the
# playlist clock), and sets the mode again when it comes back. vkms on 6.1 has no configfs, so a
# hotplug is the connector's status forced through sysfs and a uevent written to the card's.
#
#   kms_hotplug.sh PLAYER OUT_DIR
set -euo pipefail
# Mesa's shader cache on the guest's tmpfs (9p cannot hold it): the first player process compiles
# the SSAO variants, about 20 s under TCG; later ones in this guest find them there.
export MESA_SHADER_CACHE_DIR=${TMPDIR:-/run}/mesa-shader-cache
player=$1 out=$2
mkdir -p "$out"
fail() {
  echo "FAIL: $*"
  [ -f "$out/hotplug.out" ] && cat "$out/hotplug.out"
  exit 1
}
connector=$(ls -d /sys/class/drm/card0-Virtual-* | head -1)
hotplug() {
  echo "$1" >"$connector/status"
  echo "change $(cat /proc/sys/kernel/random/uuid) HOTPLUG=1" >/sys/class/drm/card0/uevent
}
# Waits up to $2 seconds for a line matching $1 in the player's output.
wait_for() {
  for _ in $(seq 1 $(($2 * 10))); do
    grep -q "$1" "$out/hotplug.out" && return 0
    kill -0 "$pid" 2>/dev/null || fail "the player exited while waiting for '$1'"
    sleep 0.1
  done
  fail "no '$1' within $2 s"
}

echo off >"$connector/status"
"$player" play builtin:demo --platform kms --drm-mode 640x480 --ao off --frames 30 --status "$out/status.json" \
  --log "$out/hotplug.log" >"$out/hotplug.out" 2>&1 &
pid=$!
wait_for "^display: no display connected; waiting for one" 120
sleep 2
grep -q '"state": *"no display"' "$out/status.json" || fail "the status file does not say 'no display' while waiting"
[ -s "$out/hotplug.log" ] && fail "frames were logged with no display connected"

hotplug on
wait_for "^display: DRM/KMS on /dev/dri/card0 .*Virtual-1 640x480" 30
wait_for "^first frame presented" 60
wait_for "^display: showing frames again" 30
sleep 3
frames_before=$(wc -l <"$out/hotplug.log")
[ "$frames_before" -gt 0 ] || fail "no frame after the display came"

hotplug off
wait_for "^display: no display connected at" 30
sleep 1
frames_off=$(wc -l <"$out/hotplug.log")
sleep 2
[ "$(wc -l <"$out/hotplug.log")" -eq "$frames_off" ] || fail "frames were presented with the display off"
t_off=$(tail -1 "$out/hotplug.log" | sed -n 's/.* t=\([0-9.]*\) .*/\1/p')

hotplug on
wait_for "showing frames again.*" 30
# The rest of the 30 frames, bounded: a player stuck after the return (a flip that never completes)
# fails here with its output and log, not at ctest's timeout with nothing to read. Beside the ASan gl
# tests a frame of this guest took 6 s (2.5 s alone), so 30 frames, with room for that.
for _ in $(seq 1 3000); do
  kill -0 "$pid" 2>/dev/null || break
  sleep 0.1
done
if kill -0 "$pid" 2>/dev/null; then
  kill -ABRT "$pid" 2>/dev/null || true
  sleep 2
  echo "last frames logged:"
  tail -5 "$out/hotplug.log"
  fail "the player did not finish its 30 frames within 300 s of the display's return"
fi
wait "$pid" || fail "the player exited with $?"
cat "$out/hotplug.out"
[ "$(grep -c '^display: showing frames again' "$out/hotplug.out")" -eq 2 ] || fail "expected two returns of the display"
grep -q "^played 30 frames, 0 error(s)" "$out/hotplug.out" || fail "expected 30 frames and no error"
# The playlist clock ran on while nothing was shown: the first frame after the return is later than
# the last before it by at least the time the display was off.
t_back=$(awk -v off="$t_off" '{ sub(/.* t=/, ""); sub(/ .*/, ""); if ($0 + 0 > off + 0) { print; exit } }' "$out/hotplug.log")
awk -v a="$t_off" -v b="$t_back" 'BEGIN { exit !(b - a >= 2.0) }' || fail "the clock did not run on while the display was off ($t_off -> $t_back)"
back_ms=$(sed -n 's/^display: showing frames again \([0-9.]*\) ms.*/\1/p' "$out/hotplug.out" | tail -1)
echo "kms figures: hotplug-on to the first frame again ${back_ms} ms"
echo "PASS"
