#!/usr/bin/env bash
# Hot reload while `player play` runs: a good new scene (written as a dot-file and renamed into
# place) is swapped in; a corrupt one and a broken playlist are refused while the last good content
# keeps playing; SIGTERM ends the player cleanly within a second.
# Usage: hot_reload.sh PLAYER SHARED_SCENES OUT_DIR
set -u
player=$1 scenes=$2 out=$3
dir=$out/hot-reload
rm -rf "$dir" && mkdir -p "$dir/content"
cp "$scenes/spot.glb" "$dir/content/scene.glb"
cat > "$dir/content/list.toml" <<'TOML'
[[item]]
scene = "scene.glb"
duration = 1000.0
TOML
fail() { echo "hot_reload: $*"; [ -n "${pid:-}" ] && kill "$pid" 2>/dev/null; exit 1; }
# Waits up to $2 seconds for the grep pattern $1 in file $3.
wait_for() {
  for _ in $(seq 1 $(($2 * 10))); do grep -q -- "$1" "$3" 2>/dev/null && return 0; sleep 0.1; done
  return 1
}

"$player" play "$dir/content/list.toml" --platform egl --size 64x48 --fps 30 --log "$dir/log" \
  --status "$dir/status.json" > "$dir/stdout" 2> "$dir/stderr" &
pid=$!
# Changed before the first version is on the GPU, the file would be the first version (no swap):
# the change is made once the first scene plays.
wait_for "state=playing" 60 "$dir/log" || fail "nothing played within 60 s: $(cat "$dir/stderr")"
grep -q "swaps=0" "$dir/log" || fail "the first scene counts as a swap"

cp "$scenes/fandisk.glb" "$dir/content/.scene.glb" && mv "$dir/content/.scene.glb" "$dir/content/scene.glb"
wait_for "swaps=1 " 30 "$dir/log" || fail "the good change was not swapped in: $(cat "$dir/stderr")"

printf 'glTF not really' > "$dir/content/.scene.glb" && mv "$dir/content/.scene.glb" "$dir/content/scene.glb"
wait_for "scene.glb: not a valid glTF" 30 "$dir/stderr" || fail "the corrupt change was not reported"
printf '[[item]]\nscene = 3\n' > "$dir/content/.list.toml" && mv "$dir/content/.list.toml" "$dir/content/list.toml"
wait_for "list.toml:2:9: item\[0\].scene: expected" 30 "$dir/stderr" || fail "the broken playlist was not reported: $(cat "$dir/stderr")"
frames_then=$(wc -l < "$dir/log")
sleep 1
[ "$(wc -l < "$dir/log")" -gt "$frames_then" ] || fail "playback stopped after the bad changes"
tail -n 1 "$dir/log" | grep -q "state=playing .*swaps=1 " || fail "the last good content is not what plays: $(tail -n 1 "$dir/log")"
# The first frames may show "loading" (the paced clock does not wait for the loader); after the
# first playing frame every frame plays.
awk '/state=playing/ { on = 1 } on && !/state=playing/ { print; bad = 1 } END { exit bad }' "$dir/log" ||
  fail "a frame after the first was not playing"

kill -TERM "$pid"
for _ in $(seq 1 10); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
kill -0 "$pid" 2>/dev/null && fail "still running 1 s after SIGTERM"
wait "$pid"; rc=$?
[ "$rc" -eq 0 ] || fail "exit code $rc after SIGTERM: $(cat "$dir/stderr")"
grep -q '"state": "playing"' "$dir/status.json" || fail "status: $(cat "$dir/status.json")"
grep -q 'not a valid glTF' "$dir/status.json" || fail "status lacks the refused scene: $(cat "$dir/status.json")"
echo "hot_reload: good change swapped in, bad scene and playlist refused, clean stop on SIGTERM"
