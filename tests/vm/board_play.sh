#!/usr/bin/env bash
# Runs inside the test VM (tools/vm/run), as root: `player play` on a virtual Raspberry Pi 4, with
# every device a kernel simulator. board/raspberry-pi-4.toml as shipped, but for its camera (vivid
# captures YUYV, not the C920's MJPEG): gpio-sim lines named as the Pi's (GPIO17 play, GPIO27 next,
# GPIO22 check, GPIO23 status LED, GPIO24 error LED), vivid behind the board's by-id name, a uinput
# keyboard, vkms. Pulling a button's line acts in the player; the LED lines, read back through
# gpio-sim, show the patterns; a key acts as its button; the camera unbound mid-stream is reported
# and reopened after rebind while playback never stops; `player ctl` reaches it through the board's
# control socket and its metrics file says kms and a display; SIGTERM stops it cleanly.
#
#   board_play.sh PLAYER SOURCE_DIR OUT_DIR
set -euo pipefail
player=$1 source=$2 out=$3
mkdir -p "$out"
rm -f "$out/board.log" "$out/board.out" "$out/board.toml"
export MESA_SHADER_CACHE_DIR=${TMPDIR:-/run}/mesa-shader-cache
pid=
fail() {
  echo "FAIL: $*"
  [ -f "$out/board.out" ] && tail -20 "$out/board.out"
  [ -f "$out/board.log" ] && tail -5 "$out/board.log"
  [ -n "$pid" ] && kill "$pid" 2>/dev/null
  [ -n "${keys:-}" ] && kill "$keys" 2>/dev/null
  exit 1
}

# gpio-sim: one chip whose lines carry the Pi's names.
sim=/sys/kernel/config/gpio-sim/pi
names=(GPIO17 GPIO27 GPIO22 GPIO23 GPIO24)
mkdir "$sim" "$sim/bank0"
echo ${#names[@]} >"$sim/bank0/num_lines"
for i in "${!names[@]}"; do
  mkdir "$sim/bank0/line$i"
  echo "${names[$i]}" >"$sim/bank0/line$i/name"
done
echo 1 >"$sim/live"
line() { echo "/sys/devices/platform/$(cat "$sim/dev_name")/$(cat "$sim/bank0/chip_name")/sim_gpio$1"; }
play=$(line 0) next=$(line 1) status_led=$(line 3) error_led=$(line 4)

# vivid behind the name the board file gives its camera.
vivid=
for node in /sys/class/video4linux/video*; do
  grep -q "vivid.*vid-cap" "$node/name" && { vivid=/dev/$(basename "$node"); break; }
done
[ -n "$vivid" ] || fail "no vivid capture node"
camera=$(sed -n 's/^device = "\(.*\)".*/\1/p' "$source/board/raspberry-pi-4.toml")
mkdir -p "$(dirname "$camera")" /run/ssao-player
ln -sf "$vivid" "$camera"
# The camera's own settings aside, the file is the Pi's; the no-frame timeout is raised because a
# frame of the player takes over a second under TCG, and the reopen is quicker to keep the test short.
# The long press is 5 s instead of 0.8: a guest starved of CPU once let 0.8 s pass between the two
# writes of a click (below), and the player, reading the kernel's timestamps, rightly saw a long press.
sed -e 's/^format = "mjpeg"/format = "yuyv"/' -e 's/^long_press_ms = .*/long_press_ms = 5000/' -e 's/^width = .*/width = 640/' -e 's/^height = .*/height = 480/' \
  -e "s/^reopen_interval_ms = .*/reopen_interval_ms = 500\nframe_timeout_ms = 10000/" "$source/board/raspberry-pi-4.toml" >"$out/board.toml"

# The number of the last frame logged.
last_frame() { tail -1 "$out/board.log" 2>/dev/null | cut -d' ' -f1; }
# Samples a line's value every 0.1 s: "0", "1" or "01" (it changed). The player sets its LEDs between
# frames, and a frame of this guest took 2.5 s on a slower host, where the heartbeat (on for 200 ms
# of 1200) showed as one level for a whole 2.4 s look. So `levels LINE 01` looks until the line
# changes (at most 90 s); any other look lasts at least 2.4 s and 4 of the player's frames.
levels() {
  local seen="" start samples=0
  start=$(last_frame)
  while [ $samples -lt 900 ]; do
    seen+=$(cat "$1/value")
    samples=$((samples + 1))
    case "$seen" in *0*1* | *1*0*) break ;; esac
    [ "${2:-}" != 01 ] && [ $samples -ge 24 ] && [ "$(last_frame)" -ge $((start + 4)) ] && break
    sleep 0.1
  done
  case "$seen" in *0*1* | *1*0*) echo 01 ;; *1*) echo 1 ;; *) echo 0 ;; esac
}
# Waits up to $3 seconds for a frame after frame $1 whose log line matches the regex $2.
wait_log() {
  for _ in $(seq $(($3 * 5))); do
    awk -v n="$1" -v re="$2" '$1 + 0 > n + 0 && $0 ~ re { found = 1 } END { exit !found }' "$out/board.log" 2>/dev/null && return 0
    kill -0 "$pid" 2>/dev/null || fail "the player exited while waiting for '$2'"
    sleep 0.2
  done
  fail "no frame after $1 matching '$2' within $3 s"
}
# A button between its pin and GND: pressed is the line pulled low. Held briefly: the play button
# has a long press (restart), and a guest starved of CPU may sleep longer than asked.
click() {
  echo pull-down >"$1/pull"
  sleep 0.1
  echo pull-up >"$1/pull"
}

"$player" play builtin:demo builtin:spheres --duration 1000 --platform kms --drm-mode 640x480 --ao off \
  --board "$out/board.toml" --log "$out/board.log" >"$out/board.out" 2>&1 &
pid=$!
wait_log -1 " state=playing " 120
[ "$(cat "$next/pull")" = "pull-up" ] || fail "the player did not set the buttons' bias (pull-up) as the board file says"

echo "== LEDs while playing: status heartbeat, error off"
[ "$(levels "$status_led" 01)" = 01 ] || fail "the status LED line does not beat while playing"
[ "$(levels "$error_led")" = 0 ] || fail "the error LED line is not off while playing"

echo "== next (GPIO27) pulled low"
at=$(last_frame)
click "$next"
wait_log "$at" " item=1 .*actions=next " 30

echo "== a USB keyboard: space is the play button (pause)"
at=$(last_frame)
# The keyboard stays plugged in until the pause shows: unplugged half a second after the key, it took
# the key with it whenever the player's frame was slower than that (uinput_keys.py says why).
python3 "$source/tests/vm/uinput_keys.py" --reader "$pid" --hold 120 space >"$out/keys.out" 2>&1 &
keys=$!
for _ in $(seq 300); do
  grep -q "^typed" "$out/keys.out" && break
  kill -0 "$keys" 2>/dev/null || fail "the keyboard was not opened by the player: $(cat "$out/keys.out")"
  sleep 0.2
done
grep -q "^typed" "$out/keys.out" || fail "the keyboard typed nothing within 60 s: $(cat "$out/keys.out")"
wait_log "$at" " state=paused .*actions=pause " 60
kill "$keys"
wait "$keys" 2>/dev/null || true
[ "$(levels "$status_led")" = 1 ] || fail "the status LED line is not steadily on while paused"

echo "== play (GPIO17) pulled low: playing again, the same item (a click, not the long press's restart)"
at=$(last_frame)
click "$play"  # play acts on the release of a short press (it has a long press)
wait_log "$at" " item=1 state=playing .*actions=pause " 30

echo "== player ctl on the board's control socket, and its metrics file"
[ -S /run/ssao-player/control ] || fail "the board's control socket /run/ssao-player/control is missing"
at=$(last_frame)
reply=$("$player" ctl item 0 2>&1) || fail "player ctl item 0 failed: $reply"
[ "$reply" = "ok: item 0" ] || fail "player ctl item 0 replied '$reply'"
wait_log "$at" " item=0 .*actions=item:0 " 30
reply=$("$player" ctl screenshot --timeout 60 2>&1) || fail "player ctl screenshot failed: $reply"
[ "$reply" = "${reply#ok: frame }" ] && fail "player ctl screenshot replied '$reply'"
[ -s /run/ssao-player/screenshot.png ] || fail "no screenshot beside the control socket"
grep -qx 'ssao_player_display_connected 1' /run/ssao-player/ssao-player.prom ||
  fail "the metrics file does not say a display is connected: $(cat /run/ssao-player/ssao-player.prom)"
grep -q '^ssao_player_info{version="[0-9.]*",platform="kms",' /run/ssao-player/ssao-player.prom ||
  fail "the metrics file's info does not name kms"

echo "== the camera unbound mid-stream"
wait_log -1 " camera=ok " 30
device=$(basename "$(readlink -f /sys/class/video4linux/$(basename "$vivid")/device)")
echo "$device" >/sys/bus/platform/drivers/vivid/unbind
at=$(last_frame)
wait_log "$at" " camera=lost " 30
lost_at=$(awk -v n="$at" '$1 + 0 > n + 0 && / camera=lost / { print $1; exit }' "$out/board.log")
# Frames go on: three more within 30 s (a frame of a slow guest takes 2.5 s).
wait_log "$((lost_at + 2))" " camera=lost " 30
grep -q "camera" /run/ssao-player/status.json || fail "the status file does not mention the camera"
[ "$(levels "$error_led" 01)" = 01 ] || fail "the error LED line does not blink while the camera is lost"
at=$(last_frame)
echo "$device" >/sys/bus/platform/drivers/vivid/bind
wait_log "$at" " camera=ok " 30

echo "== SIGTERM"
kill -TERM "$pid"
wait "$pid" || fail "the player exited with $? on SIGTERM"
pid=
grep -q "^played [0-9]* frames" "$out/board.out" || fail "no clean stop"
grep -q '"state": "playing"' /run/ssao-player/status.json || fail "the status file's last state is not playing"
[ -e /run/ssao-player/control ] && fail "the control socket outlived the player"
echo 0 >"$sim/live"
echo PASS
