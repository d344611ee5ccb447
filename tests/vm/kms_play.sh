#!/usr/bin/env bash
# Runs inside the test VM (tools/vm/run), as root, on vkms: the player's kms platform against the
# kernel's virtual display. Plays with atomic modesetting, then legacy, and checks that the page flips
# complete, that nothing is reported as an error, and that what the display scanned out (read back
# through vkms' writeback connector) is the frame the GPU drew.
#
#   kms_play.sh PLAYER IMAGE_CHECK OUT_DIR [FRAMES]
#
# Prints the benchmark's figures too: time from process start to the first flip, and the frame
# interval (paced by the flips) against the mode's refresh.
set -euo pipefail
player=$1 image_check=$2 out=$3 frames=${4:-45}
# The shader cache on the guest's tmpfs (9p cannot hold it), empty at first: the first player process
# compiles every program (Mesa's cache and the player's program binaries are both filled), the warm
# start below and later runs load them.
unset MESA_SHADER_CACHE_DIR MESA_SHADER_CACHE_DISABLE
cache=${TMPDIR:-/run}/shader-cache
rm -rf "$cache"
mkdir -p "$out"
fail() { echo "FAIL: $*"; exit 1; }

# bounded SECONDS OUTPUT COMMAND...: runs COMMAND with its output in OUTPUT; its exit status. A player
# stuck past SECONDS fails here with where it waits (its kernel stack: a commit the driver never
# completes shows there) and the kernel's last messages, not at the guest's timeout with nothing to read.
bounded() {
  local limit=$1 output=$2 pid
  shift 2
  "$@" >"$output" 2>&1 &
  pid=$!
  for _ in $(seq 1 $((limit * 10))); do
    kill -0 "$pid" 2>/dev/null || break
    sleep 0.1
  done
  if kill -0 "$pid" 2>/dev/null; then
    echo "the player (pid $pid) is still running after $limit s; it waits in $(cat "/proc/$pid/wchan" 2>/dev/null):"
    for task in /proc/"$pid"/task/*; do
      echo "-- thread ${task##*/} ($(cat "$task/comm" 2>/dev/null))"
      cat "$task/stack" 2>/dev/null || true
    done
    echo "-- the kernel's last messages"
    dmesg | tail -30
    kill -ABRT "$pid" 2>/dev/null || true
    sleep 2
    kill -KILL "$pid" 2>/dev/null || true
    cat "$output"
    fail "the player did not finish within $limit s: $*"
  fi
  wait "$pid"
}

[ -e /dev/dri/card0 ] || fail "no /dev/dri/card0: the VM kernel lacks vkms"
connector=$(ls -d /sys/class/drm/card0-Virtual-* | head -1)
echo on > "$connector/status"

echo "== connectors"
"$player" play --drm-connector help | tee "$out/connectors.txt"
grep -q "Virtual-1: connected" "$out/connectors.txt" || fail "--drm-connector help does not list Virtual-1 as connected"
grep -q "writeback connector" "$out/connectors.txt" || fail "--drm-connector help does not list vkms' writeback connector"

# AO off and a small mode: the VM renders with llvmpipe under TCG, about 30 times slower than the host.
common=(play builtin:demo --platform kms --drm-mode 640x480 --ao off --shader-cache "$cache")

# The default platform is what a board gets: kms, since no display server runs in the guest.
echo "== atomic, $frames frames, the platform chosen by default"
bounded 600 "$out/atomic.out" env -u DISPLAY -u WAYLAND_DISPLAY "$player" play builtin:demo --drm-mode 640x480 --ao off \
  --shader-cache "$cache" --status "$out/status.json" --frames "$frames" --log "$out/atomic.log" --snapshot "$out/drawn.png" \
  --drm-writeback "$out/scanout.png" ||
  { status=$?; cat "$out/atomic.out"; fail "player exited with $status"; }
cat "$out/atomic.out"
grep -q "^platform: kms (DRM/KMS on /dev/dri/card0 (vkms), atomic modesetting, XRGB8888, Virtual-1 640x480@" "$out/atomic.out" ||
  fail "the first line does not name kms, atomic modesetting and the mode"
grep -q "^platform: kms .*chosen because /dev/dri/card0 drives displays (KMS) and no display server runs" "$out/atomic.out" ||
  fail "auto did not choose kms, or the first line does not say why"
grep -q "^played $frames frames, 0 error(s)" "$out/atomic.out" || fail "expected $frames frames and no error"
grep -q "warning" "$out/atomic.out" && fail "warnings while playing"
[ "$(wc -l <"$out/atomic.log")" -eq "$frames" ] || fail "the log has $(wc -l <"$out/atomic.log") lines, expected $frames"
# The scanout equals the frame drawn, exactly: vkms composes one opaque XRGB8888 plane at 1:1, so any
# difference is a wrong format, stride, channel order, row order or a stale buffer on screen.
"$image_check" --size 640x480 --min-colours 64 --same-as "$out/drawn.png" --max-diff 0 "$out/scanout.png" ||
  fail "what the display shows differs from the frame drawn"

echo "== a warm start: the same player again, its programs from the shader cache"
bounded 300 "$out/warm.out" "$player" "${common[@]}" --frames 1 || { status=$?; cat "$out/warm.out"; fail "player (warm start) exited with $status"; }
grep -q "^shader cache: $cache$" "$out/warm.out" || { cat "$out/warm.out"; fail "the warm start does not name the shader cache"; }
grep -q "^first frame presented .*; shaders: 0 compiled, [1-9][0-9]* loaded from $cache/programs$" "$out/warm.out" ||
  { cat "$out/warm.out"; fail "the warm start compiled programs, or loaded none, though the cold start had kept them"; }
grep -q "^first frame presented .*; shaders: [1-9][0-9]* compiled, 0 loaded from $cache/programs$" "$out/atomic.out" ||
  fail "the cold start did not compile its programs into the empty cache"

echo "== legacy, 10 frames"
bounded 300 "$out/legacy.out" "$player" "${common[@]}" --drm-atomic no --frames 10 --log "$out/legacy.log" ||
  { status=$?; cat "$out/legacy.out"; fail "player (legacy) exited with $status"; }
grep -q "legacy modesetting" "$out/legacy.out" || fail "--drm-atomic no did not use legacy modesetting"
grep -q "^played 10 frames, 0 error(s)" "$out/legacy.out" || fail "legacy: expected 10 frames and no error"

# `player ctl display off|on`, as the opening hours switch the display: the CRTC goes inactive (read
# back from the kernel through libdrm: atomic ACTIVE, legacy DPMS), then frames flip again.
display_off_and_on() {  # NAME EXPECTED_OFF_STATE [PLAY OPTIONS...]
  local name=$1 expected=$2 socket=/run/ssao-player-vm-control pid
  shift 2
  rm -f "$out/$name.log"
  "$player" "${common[@]}" "$@" --control "$socket" --log "$out/$name.log" >"$out/$name.out" 2>&1 &
  pid=$!
  wait_log() {
    for _ in $(seq 1 3000); do [ "$({ wc -l <"$out/$name.log"; } 2>/dev/null || echo 0)" -ge "$1" ] && return 0; sleep 0.1; done
    return 1
  }
  wait_log 3 || { kill "$pid"; cat "$out/$name.out"; fail "$name: no frames within 300 s"; }
  "$player" ctl --control "$socket" --timeout 60 display off || { kill "$pid"; fail "$name: display off was refused"; }
  grep -q "^schedule: off by command; display off (Virtual-1 $expected)" "$out/$name.out" ||
    { kill "$pid"; cat "$out/$name.out"; fail "$name: the kernel does not report the display off ($expected)"; }
  local before
  before=$(wc -l <"$out/$name.log")
  sleep 2
  [ "$(wc -l <"$out/$name.log")" = "$before" ] || { kill "$pid"; fail "$name: frames were presented while the display was off"; }
  "$player" ctl --control "$socket" --timeout 60 display on || { kill "$pid"; fail "$name: display on was refused"; }
  wait_log $((before + 3)) || { kill "$pid"; cat "$out/$name.out"; fail "$name: no frames after display on"; }
  kill -TERM "$pid"
  wait "$pid" || { cat "$out/$name.out"; fail "$name: the player exited with $? on SIGTERM"; }
  grep -q "^warning\|^error" "$out/$name.out" && { cat "$out/$name.out"; fail "$name: warnings or errors"; }
  grep -q "^played [0-9]* frames, 0 error(s)" "$out/$name.out" || { cat "$out/$name.out"; fail "$name: errors while playing"; }
}
echo "== display off and on (atomic)"
display_off_and_on power-atomic "CRTC [0-9]* ACTIVE=0" --drm-writeback "$out/power-scanout.png"
# What the display shows after it came back on (read back through the writeback connector at exit)
# is a frame, not black.
"$image_check" --size 640x480 --min-colours 64 "$out/power-scanout.png" || fail "the display shows no frame after display on"
echo "== display off and on (legacy)"
display_off_and_on power-legacy "DPMS=off" --drm-atomic no

echo "== a mode the display does not offer"
if "$player" play builtin:demo --platform kms --drm-mode 1234x567 --frames 1 >"$out/bad_mode.out" 2>&1; then
  fail "an unknown mode was accepted"
fi
grep -q "error: kms: --drm-mode: Virtual-1 offers no mode 1234x567 (it offers .*640x480@" "$out/bad_mode.out" ||
  { cat "$out/bad_mode.out"; fail "the error does not list the modes"; }
grep -q "Virtual-1: connected" "$out/bad_mode.out" || fail "the error does not list the connectors"

echo "== figures"
first=$(sed -n 's/^first frame presented \([0-9.]*\) ms.*/\1/p' "$out/atomic.out")
warm=$(sed -n 's/^first frame presented \([0-9.]*\) ms.*/\1/p' "$out/warm.out")
# Frame intervals after the first few (shader warm-up), paced by the page flips.
sed -n 's/.* ms=\([0-9.]*\) .*/\1/p' "$out/atomic.log" | tail -n +6 | sort -g >"$out/intervals.txt"
n=$(wc -l <"$out/intervals.txt")
median=$(sed -n "$(((n + 1) / 2))p" "$out/intervals.txt")
p99=$(sed -n "$(((n * 99 + 99) / 100))p" "$out/intervals.txt")
refresh=$(sed -n 's/.*Virtual-1 640x480@\([0-9.]*\).*/\1/p' "$out/atomic.out" | head -1)
echo "kms figures: first flip ${first} ms after process start (cold: empty shader cache), ${warm} ms warm; frame interval median ${median} ms, p99 ${p99} ms over $n frames;" \
  "mode refresh ${refresh} Hz ($(awk -v r="$refresh" 'BEGIN { printf "%.2f", 1000 / r }') ms)"
echo "PASS"
