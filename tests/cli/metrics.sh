#!/usr/bin/env bash
# `player play --metrics FILE`: the file a node_exporter textfile collector reads, checked by
# Prometheus' own promtool, with the figures of the run in it.
# Usage: metrics.sh PLAYER PROMTOOL OUT_DIR
set -u
player=$1 promtool=$2 out=$3
dir=$out/metrics
rm -rf "$dir" && mkdir -p "$dir"
fail() { echo "metrics: $*"; exit 1; }
[ -x "$promtool" ] || fail "no promtool at '$promtool': tools/install-deps unpacks Debian's into ~/.cache/ssao-player/promtool"

# A scene that is missing makes one content error; the other item plays.
"$player" play builtin:demo "$dir/missing.glb" --duration 1 --platform egl --size 64x48 --frames 90 --shader-cache off \
  --metrics "$dir/player.prom" >"$dir/stdout" 2>"$dir/stderr" || fail "the player exited with $?: $(cat "$dir/stderr")"
[ -f "$dir/player.prom" ] || fail "no metrics file"
[ "$(ls "$dir")" = "$(printf 'player.prom\nstderr\nstdout')" ] || fail "files left beside the metrics file: $(ls "$dir")"
"$promtool" check metrics <"$dir/player.prom" >"$dir/promtool.out" 2>&1 || fail "promtool check metrics: $(cat "$dir/promtool.out")"
for line in 'ssao_player_frames_total 90' 'ssao_player_frame_seconds_count 89' 'ssao_player_errors_total{kind="content"} 1' \
  'ssao_player_display_connected 1' 'ssao_player_open 1' 'ssao_player_gpu_resets_total 0' 'ssao_player_state{state="playing"} 1'; do
  grep -qxF "$line" "$dir/player.prom" || fail "no line '$line' in: $(cat "$dir/player.prom")"
done
grep -q '^ssao_player_info{version="[0-9.]*",platform="egl",renderer="[^"]*"} 1$' "$dir/player.prom" || fail "no info line"
grep -q '^ssao_player_scene_load_seconds [0-9.e-]*$' "$dir/player.prom" || fail "no scene load time"
echo "metrics: promtool reads them, and they count the run"
