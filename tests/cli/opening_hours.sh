#!/usr/bin/env bash
# Opening hours as an operator meets them: a board's [schedule] closes the kiosk (nothing drawn,
# state closed, the status LED on standby, the metrics say so, no error), opens it again the next
# morning, and `player ctl display on|off` overrides the hours until they next change.
# Usage: opening_hours.sh PLAYER OUT_DIR
set -u
player=$1 out=$2
dir=$out/opening-hours
rm -rf "$dir" && mkdir -p "$dir"
fail() { echo "opening hours: $*"; [ -n "${pid:-}" ] && kill "$pid" 2>/dev/null; exit 1; }
wait_for() {  # PATTERN SECONDS FILE
  for _ in $(seq 1 $(($2 * 10))); do grep -q -- "$1" "$3" 2>/dev/null && return 0; sleep 0.1; done
  return 1
}
cat >"$dir/board.toml" <<'TOML'
[board]
name = "opening hours test"
[schedule]
open = ["Mo-Fr 09:00-18:00"]
timezone = "UTC"
holidays = [2026-12-08]
[[led]]
name = "status"
line = "GPIO23"
[[led]]
name = "error"
line = "GPIO24"
TOML

# A preview on the manual clock: Monday 2026-12-07 two seconds before closing. About 60 frames of
# 1/30 s reach 18:00; the night and the holiday pass without frames; the rest are Wednesday's.
"$player" play builtin:demo --platform egl --size 64x48 --shader-cache off --board "$dir/board.toml" --hal mock \
  --frames 120 --start-time 2026-12-07T17:59:58Z --log "$dir/preview.log" --metrics "$dir/preview.prom" \
  >"$dir/preview.stdout" 2>"$dir/preview.stderr" || fail "the preview exited with $?: $(cat "$dir/preview.stderr")"
grep -q "^schedule: open until 2026-12-07 18:00 UTC; display on (egl: no display of its own to switch) at 0 s$" \
  "$dir/preview.stdout" || fail "the start was not open until 18:00: $(grep schedule "$dir/preview.stdout")"
grep -q "^schedule: closed until 2026-12-09 09:00 UTC; display off (egl: no display of its own to switch) at 2[.0-9]* s$" \
  "$dir/preview.stdout" || fail "18:00 did not close until Wednesday (the 8th a holiday): $(grep schedule "$dir/preview.stdout")"
grep -q "^schedule: open until 2026-12-09 18:00 UTC; display on" "$dir/preview.stdout" \
  || fail "Wednesday did not open: $(grep schedule "$dir/preview.stdout")"
[ "$(wc -l <"$dir/preview.log")" = 120 ] || fail "expected 120 frames, got $(wc -l <"$dir/preview.log")"
# One gap between frames, at 18:00 on Monday: the 39 hours (140400 s) to Wednesday at 9.
gaps=$(awk '{ sub("t=", "", $2) } NR > 1 && $2 - last > 1 { print $1 ": " $2 - last } { last = $2 }' "$dir/preview.log")
grep -Eqx "6[01]: 14040[01](\.[0-9]*)?" <<<"$gaps" && [ "$(wc -l <<<"$gaps")" = 1 ] \
  || fail "expected one gap of 140400 s after about 2 s of frames, got: $gaps"
grep -q 'ssao_player_open 1' "$dir/preview.prom" || fail "open again, the metrics say otherwise: $(cat "$dir/preview.prom")"
[ -s "$dir/preview.stderr" ] && fail "a closed night is no error, yet: $(cat "$dir/preview.stderr")"

# On the real clock, closed (a Saturday), with a control socket: display on until Monday's opening,
# then off again; the status file tells it all.
socket=$dir/control
"$player" play builtin:demo --platform egl --size 64x48 --fps 30 --shader-cache off --board "$dir/board.toml" \
  --hal mock --start-time 2026-12-12T13:00:00+01:00 --control "$socket" --status "$dir/status.json" \
  --metrics "$dir/live.prom" --log "$dir/live.log" >"$dir/live.stdout" 2>"$dir/live.stderr" &
pid=$!
wait_for '"state": *"closed"' 60 "$dir/status.json" || fail "a Saturday did not show closed: $(cat "$dir/status.json" "$dir/live.stderr")"
grep -q '"status": *"standby"' "$dir/status.json" || fail "the status LED is not on standby: $(cat "$dir/status.json")"
wait_for 'ssao_player_state{state="closed"} 1' 10 "$dir/live.prom" || fail "the metrics do not say closed"
grep -q 'ssao_player_open 0' "$dir/live.prom" || fail "the metrics do not say ssao_player_open 0"
[ -s "$dir/live.log" ] && fail "frames were drawn while closed: $(head -3 "$dir/live.log")"
reply=$("$player" ctl --control "$socket" screenshot 2>&1)
[ $? -eq 1 ] || fail "a screenshot while closed was not refused: $reply"
reply=$("$player" ctl --control "$socket" display on) || fail "display on failed: $reply"
[ "$reply" = "ok: display on until the opening hours change at 2026-12-14 09:00 UTC" ] || fail "display on replied '$reply'"
wait_for "state=playing .*actions=display:on" 30 "$dir/live.log" || fail "display on drew no frame: $(cat "$dir/live.stdout")"
wait_for '"state": *"playing"' 10 "$dir/status.json" || fail "the status file does not say playing"
reply=$("$player" ctl --control "$socket" display off) || fail "display off failed: $reply"
[ "$reply" = "ok: display off (as the opening hours have it)" ] || fail "display off replied '$reply'"
wait_for '"state": *"closed"' 10 "$dir/status.json" || fail "display off did not close"
reply=$("$player" ctl --control "$socket" display dim 2>&1)
[ $? -eq 2 ] || fail "display dim was not refused as malformed: $reply"
kill -TERM "$pid"
wait "$pid" || fail "the player exited with $? on SIGTERM"
pid=
grep -q '"state": *"closed"' "$dir/status.json" || fail "stopped while closed, the status file should still say closed"
grep -q "error" "$dir/live.stderr" && fail "errors while closed: $(cat "$dir/live.stderr")"
reply=$("$player" play builtin:demo --platform egl --frames 1 --start-time 2026-12-07T25:00:00Z 2>&1)
[ $? -ne 0 ] || fail "a start time at 25 o'clock was accepted"
grep -q "expected a time as 2026-12-07T17:59:30Z, 2026-12-07T18:59:30+01:00 or Unix seconds, got '2026-12-07T25:00:00Z'" <<<"$reply" ||
  fail "a bad start time said: $reply"
echo "closed, opened and overridden as the hours and commands said"
