#!/usr/bin/env bash
# Synchronised screens: players on one wallclock playlist show the same item, camera phase and
# animation time at the same wall-clock moment, however far apart they started. Two players on the
# reproducible clock (--start-time: the wall clock read that at the start; each frame 1/30 s later)
# started 2 s apart: for every frame of the second, the first's frame of the same instant is the one
# that matches best (offset 0 frames), and from the first item change on (both AO histories then
# start together) they are the same to the pixel.
# Usage: sync.sh PLAYER IMAGE_CHECK OUT_DIR
set -u
player=$1 image_check=$2 out=$3
dir=$out/sync
rm -rf "$dir" && mkdir -p "$dir"
fail() { echo "sync: $*"; exit 1; }
cat >"$dir/show.toml" <<'TOML'
schedule = "wallclock"
[[item]]
scene = "builtin:demo"
duration = 3
[[item]]
scene = "builtin:spheres"
duration = 3
TOML
start=1796724000  # 2026-12-08 08:40:00 UTC, on a whole 6-second cycle of the playlist
lag_frames=60     # the second player starts 2 s later
frames=90
run() {  # NAME START FRAMES
  "$player" play "$dir/show.toml" --platform egl --size 96x64 --shader-cache off --start-time "$2" --frames "$3" \
    --out "$dir/$1" >"$dir/$1.log" 2>&1 || fail "player $1: $(cat "$dir/$1.log")"
}
run first "$start" $((lag_frames + frames + 2))
run second "$((start + 2))" "$frames"
frame() { printf '%s/%s/frame-%06d.png' "$dir" "$1" "$2"; }
# Differing pixels of each second-player frame against the first player's frame at offset D.
for d in -1 0 1; do
  args=()
  for j in $(seq 0 $((frames - 1))); do
    i=$((j + lag_frames + d))
    [ "$i" -ge 0 ] && args+=(--same-as "$(frame first "$i")" --max-diff 255 "$(frame second "$j")")
  done
  "$image_check" --size 96x64 "${args[@]}" | sed -n 's/^.*frame-\([0-9]*\)\.png: against .*: \([0-9]*\) of [0-9]* pixels differ.*/\1 \2/p' \
    | sed 's/^0*\([0-9]\)/\1/' >"$dir/offset$d.txt"
  [ "$(wc -l <"$dir/offset$d.txt")" = "$frames" ] || fail "image_check compared $(wc -l <"$dir/offset$d.txt") frames at offset $d"
done
# The best offset per frame (ties go to 0), and the frames that are not pixel-identical at offset 0.
join <(sort -k1,1 "$dir/offset-1.txt") <(sort -k1,1 "$dir/offset0.txt") | join - <(sort -k1,1 "$dir/offset1.txt") | sort -n >"$dir/table.txt"
awk -v lag="$lag_frames" '
  { best = 0; if ($2 < $3) best = -1; if ($4 < $3 && $4 < $2) best = 1; if (best != 0) off++; if ($3 > 0) { unequal++; last = $1 } }
  END {
    printf "sync: offset 0 frames for %d of %d frames; %d not pixel-identical (the last, frame %d, before the first item change at frame 30)\n", NR - off, NR, unequal, last
    if (off > 0 || last >= 30) exit 1
  }' "$dir/table.txt" || fail "the players drift: $(cat "$dir/table.txt")"
echo "sync: two players 2 s apart show the same frame at the same instant"
