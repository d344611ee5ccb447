#!/usr/bin/env bash
# `player ctl` against a running `player play --control PATH`: each command is done and answered,
# a bad one is refused with a reason and changes nothing, and the socket goes with the player.
# Usage: control.sh PLAYER OUT_DIR
set -u
player=$1 out=$2
dir=$out/control
rm -rf "$dir" && mkdir -p "$dir"
socket=$dir/control
fail() { echo "control: $*"; [ -n "${pid:-}" ] && kill "$pid" 2>/dev/null; exit 1; }
wait_for() {  # PATTERN SECONDS FILE
  for _ in $(seq 1 $(($2 * 10))); do grep -q -- "$1" "$3" 2>/dev/null && return 0; sleep 0.1; done
  return 1
}
ctl() { "$player" ctl --control "$socket" "$@"; }

# Three items that each last long enough that only a command changes them.
"$player" play builtin:demo builtin:corner builtin:demo --duration 1000 --platform egl --size 64x48 --fps 30 \
  --shader-cache off --log "$dir/log" --control "$socket" >"$dir/stdout" 2>"$dir/stderr" &
pid=$!
wait_for "state=playing" 60 "$dir/log" || fail "nothing played within 60 s: $(cat "$dir/stderr")"
grep -q "^control: listening on $socket$" "$dir/stdout" || fail "the player does not say where it listens: $(cat "$dir/stdout")"
[ "$(stat -c %a "$socket")" = 660 ] || fail "the socket's mode is $(stat -c %a "$socket"), expected 660"

reply=$(ctl item 2) || fail "item 2 failed: $reply"
[ "$reply" = "ok: item 2" ] || fail "item 2 replied '$reply'"
wait_for "item=2 .*actions=item:2" 10 "$dir/log" || fail "item 2 was not shown, or the log does not name the command"

[ "$(ctl pause)" = "ok: paused" ] || fail "pause"
[ "$(ctl pause)" = "ok: paused already" ] || fail "pause twice"
[ "$(ctl resume)" = "ok: playing" ] || fail "resume"

reply=$(ctl item 3 2>&1)
[ $? -eq 1 ] || fail "item 3 of a three-item playlist did not exit 1"
[ "$reply" = "error: item 3: the playlist has 3 items, 0 to 2" ] || fail "item 3 replied '$reply'"

reply=$(ctl jump 2>&1)
[ $? -eq 2 ] || fail "an unknown command did not exit 2"
grep -q "^error: unknown command 'jump' (expected one of next, previous, pause, resume, check, reload, restart, item N, screenshot, display on|off)$" \
  <<<"$reply" || fail "an unknown command said '$reply'"
grep -q "jump" "$dir/stdout" && fail "an unknown command reached the player"

# A screenshot: the next frame drawn, written beside the socket, the reply given once it is.
reply=$(ctl screenshot) || fail "screenshot failed: $reply"
# The board's mock camera films only the self-check's frames, so before a check it has none to add.
grep -Eqx "ok: frame [0-9]* written to $dir/screenshot.png; camera: the camera has delivered no frame yet" <<<"$reply" ||
  fail "screenshot replied '$reply'"
[ "$(head -c 8 "$dir/screenshot.png" | od -An -tx1 | tr -d ' \n')" = 89504e470d0a1a0a ] || fail "the screenshot is not a PNG"
[ "$(od -An -tu1 -j16 -N8 "$dir/screenshot.png" | tr -s ' ')" = " 0 0 0 64 0 0 0 48" ] || fail "the screenshot is not 64x48"

[ "$(ctl next)" = "ok: next" ] || fail "next"
wait_for "item=0 .*actions=next" 10 "$dir/log" || fail "next after the last item did not show item 0"
grep -q "^control: next from pid [0-9]* (uid $(id -u)): ok: next$" "$dir/stdout" || fail "the player did not log the command"

reply=$("$player" ctl --control "$dir/nothing-here" next 2>&1)
[ $? -eq 2 ] || fail "no player listening did not exit 2"
grep -q "no player listens there" <<<"$reply" || fail "no player listening said '$reply'"

kill -TERM "$pid"
wait "$pid" || fail "the player exited with $? on SIGTERM"
[ -e "$socket" ] && fail "the socket outlived the player"
grep -q "error" "$dir/stderr" && fail "errors while playing: $(cat "$dir/stderr")"
echo "control: every command done and answered"
