#!/usr/bin/env bash
# A GPU reset during play, from a driver that tells of it (tests/cli/gpu_reset_shim.c stands in for
# one): the player makes its context and every GL resource anew and plays on from the frame it was
# at, with the playlist clock where it was; resets that keep coming end the process with code 4, for
# systemd to restart it.
#
#   gpu_reset.sh PLAYER SHIM OUT_DIR
set -euo pipefail
player=$1 shim=$2 out=$3
mkdir -p "$out"
fail() { echo "FAIL: $*"; cat "$out/reset.out" 2>/dev/null; exit 1; }
# The shim comes before the sanitizer runtime in the library list, which ASan checks by default.
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}verify_asan_link_order=0"

rm -f "$out/reset.log"
LD_PRELOAD=$shim GPU_RESET_AT=8 "$player" play --platform egl --size 64x48 --frames 20 --log "$out/reset.log" \
  --status "$out/reset.json" >"$out/reset.out" 2>&1 || fail "the player exited with $? after one reset"
cat "$out/reset.out"
grep -q "^warning: the GPU was reset (caused by this player) at frame 7$" "$out/reset.out" || fail "the reset was not reported"
grep -q "^remake: the platform, its context and every GL resource are made anew (the GPU was reset (caused by this player) at frame 7); playing on from frame 8$" "$out/reset.out" ||
  fail "the player did not say it rebuilt"
[ "$(grep -c '^platform: egl' "$out/reset.out")" -eq 2 ] || fail "expected a second context"
grep -q "^played 20 frames, 0 error(s)$" "$out/reset.out" || fail "expected 20 frames in all"
# One log line a frame across both contexts, and the clock (1/30 s a frame) carried over.
[ "$(wc -l <"$out/reset.log")" -eq 20 ] || fail "the log has $(wc -l <"$out/reset.log") lines, expected 20"
for frame in 7 8 19; do
  grep -q "^$frame t=$(awk -v f=$frame 'BEGIN { printf "%g", f / 30 }') " "$out/reset.log" || fail "frame $frame is not at $frame/30 s"
done
grep -q "^8 .* state=playing" "$out/reset.log" || fail "frame 8 (the first of the new context) is not playing"

LD_PRELOAD=$shim GPU_RESET_AT=2 GPU_RESET_REPEAT=1 "$player" play --platform egl --size 64x48 --frames 40 \
  >"$out/reset.out" 2>&1 && fail "resets that keep coming did not end the process"
code=$?
[ "$code" -eq 4 ] || fail "expected exit code 4 after repeated resets, got $code"
grep -q "^error: the platform had to be made anew 4 times within a minute (last: the GPU was reset (caused by this player) at frame [0-9]*); exiting (4) for the service manager to restart the player$" \
  "$out/reset.out" || fail "the repeated resets were not explained"
echo PASS
