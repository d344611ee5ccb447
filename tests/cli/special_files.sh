#!/usr/bin/env bash
# Every file the player reads by name, given as something that is not a regular file: a FIFO with
# no writer (which would block a plain open or read forever) and a character device (which would
# never end). Each is refused at once, naming the file and what it should have been, with a
# non-zero exit at start-up; a scene that turns out to be a FIFO while playing is reported and the
# rest plays on. Each run has a timeout: a hang fails the test instead of stalling CI.
# Usage: special_files.sh PLAYER OUT_DIR
set -u
player=$1 out=$2
dir=$out/special-files
rm -rf "$dir" && mkdir -p "$dir"
failures=0
fail() { echo "special_files: $*"; failures=$((failures + 1)); }

# expect NAME EXPECTED_TEXT -- COMMAND...: the command exits non-zero within 30 s and its stderr
# holds the text.
expect() {
  local name=$1 text=$2
  shift 3
  timeout 30 "$@" > "$dir/$name.out" 2> "$dir/$name.err"
  local rc=$?
  if [ "$rc" = 124 ]; then fail "$name: hung (killed after 30 s)"; return; fi
  if [ "$rc" = 0 ]; then fail "$name: exit 0, expected a refusal"; return; fi
  grep -qF -- "$text" "$dir/$name.err" || fail "$name: stderr lacks '$text': $(head -c 600 "$dir/$name.err")"
}

mkfifo "$dir/list.toml" "$dir/display.toml" "$dir/visual.json" "$dir/board.toml" "$dir/buttons.script" \
  "$dir/camera.script" "$dir/frame.png" "$dir/scene.gltf" "$dir/scene.bin"
play=("$player" play --platform egl --size 64x48 --frames 3)

expect playlist "$dir/list.toml: the playlist is a FIFO, not a regular file" -- "${play[@]}" "$dir/list.toml"
ln -s /dev/zero "$dir/device.toml"
expect playlist_device "$dir/device.toml: the playlist is a character device, not a regular file" -- \
  "${play[@]}" "$dir/device.toml"
expect display "$dir/display.toml: the display file is a FIFO, not a regular file" -- \
  "$player" render builtin:demo --platform egl --display "$dir/display.toml" -o "$dir/x.png"
printf 'type = "quilt"\ncalibration = "visual.json"\nquilt = "4x3"\nview_size = "20x15"\n' > "$dir/quilt.toml"
expect calibration "$dir/visual.json: the calibration is a FIFO, not a regular file" -- \
  "$player" render builtin:demo --platform egl --display "$dir/quilt.toml" -o "$dir/x.png"
expect board "$dir/board.toml: the board file is a FIFO, not a regular file" -- \
  "${play[@]}" --hal mock --board "$dir/board.toml" builtin:demo
printf '[mock]\nbutton_script = "buttons.script"\n' > "$dir/script-board.toml"
expect button_script "$dir/buttons.script: the button script is a FIFO, not a regular file" -- \
  "${play[@]}" --hal mock --board "$dir/script-board.toml" builtin:demo
printf '[camera]\ndevice = "/dev/v4l/by-id/mock"\n[mock]\ncamera_images = ["frame.png"]\n' > "$dir/camera-board.toml"
expect camera_image "$dir/frame.png: the image is a FIFO, not a regular file" -- \
  "${play[@]}" --hal mock --board "$dir/camera-board.toml" builtin:demo
printf '[camera]\ndevice = "/dev/v4l/by-id/mock"\n' > "$dir/camera-only-board.toml"
expect camera_script "$dir/camera.script: the camera script is a FIFO, not a regular file" -- \
  "${play[@]}" --hal mock --board "$dir/camera-only-board.toml" --camera-script "$dir/camera.script" builtin:demo
expect scene "$dir/scene.gltf: the scene is a FIFO, not a regular file" -- \
  "$player" render "$dir/scene.gltf" --platform egl --size 64x48 -o "$dir/x.png"
mkdir -p "$dir/named"
mkfifo "$dir/named/data.bin"
cat > "$dir/named/scene.gltf" <<'JSON'
{"asset": {"version": "2.0"}, "buffers": [{"uri": "data.bin", "byteLength": 36}],
 "bufferViews": [{"buffer": 0, "byteLength": 36}],
 "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
 "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
 "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0}
JSON
expect named_buffer "the file the scene names is a FIFO, not a regular file" -- \
  "$player" render "$dir/named/scene.gltf" --platform egl --size 64x48 -o "$dir/x.png"

# While playing: an item whose scene is a FIFO is skipped with a warning, the others play.
printf '[[item]]\nscene = "scene.gltf"\nduration = 0.2\n[[item]]\nscene = "builtin:demo"\nduration = 0.2\n' > "$dir/playing.toml"
timeout 60 "$player" play --platform egl --size 64x48 --frames 30 "$dir/playing.toml" > "$dir/playing.out" 2> "$dir/playing.err"
rc=$?
[ "$rc" = 0 ] || fail "playing: exit $rc, expected 0 (the good item plays): $(head -c 600 "$dir/playing.err")"
grep -qF "the scene is a FIFO, not a regular file" "$dir/playing.err" || fail "playing: no warning about the FIFO scene"
grep -q "played 30 frames" "$dir/playing.out" || fail "playing: did not play 30 frames: $(tail -3 "$dir/playing.out")"

[ "$failures" = 0 ] && echo "special_files: every file kind refuses a FIFO or a device without blocking"
[ "$failures" = 0 ]
