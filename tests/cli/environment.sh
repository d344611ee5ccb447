#!/usr/bin/env bash
# What lights a scene, as a user gives it: `render --environment FILE`, `play --environment FILE`
# and a playlist item's `environment`. An equirectangular Radiance HDR made here (uniform radiance 1,
# uncompressed scanlines) lights the shaded image and leaves the AO alone; a bad environment is
# refused naming the file (render) or reported while the other items play (play).
# Usage: environment.sh PLAYER OUT_DIR
set -u
player=$1 out=$2
dir=$out/environment
rm -rf "$dir" && mkdir -p "$dir"
failures=0
fail() { echo "environment: $*"; failures=$((failures + 1)); }

# hdr FILE WIDTH HEIGHT RGBE: a Radiance file of one RGBE pixel value (4 bytes as \x escapes).
hdr() {
  { printf '#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n' "$3" "$2"
    for ((i = 0; i < $2 * $3; ++i)); do printf "$4"; done; } > "$1"
}
hdr "$dir/white.hdr" 64 32 '\x80\x80\x80\x81'  # radiance 1 everywhere
hdr "$dir/square.hdr" 32 32 '\x80\x80\x80\x81'  # not 2:1
render=("$player" render builtin:demo --platform egl --size 96x72)

"${render[@]}" -o "$dir/studio.png" > /dev/null 2>&1 || fail "render with the studio failed"
"${render[@]}" --environment "$dir/white.hdr" -o "$dir/white.png" > "$dir/white.out" 2>&1 ||
  fail "render --environment white.hdr failed: $(tail -3 "$dir/white.out")"
cmp -s "$dir/studio.png" "$dir/white.png" && fail "the environment did not change the shaded image"
"${render[@]}" --view ao -o "$dir/studio-ao.png" > /dev/null 2>&1
"${render[@]}" --view ao --environment "$dir/white.hdr" -o "$dir/white-ao.png" > /dev/null 2>&1
cmp -s "$dir/studio-ao.png" "$dir/white-ao.png" || fail "the environment changed the AO view"
"${render[@]}" --environment builtin:studio -o "$dir/named-studio.png" > /dev/null 2>&1
cmp -s "$dir/studio.png" "$dir/named-studio.png" || fail "builtin:studio differs from the default"

# refuse NAME TEXT -- COMMAND...: exits 1 and says TEXT on stderr.
refuse() {
  local name=$1 text=$2
  shift 3
  timeout 60 "$@" > "$dir/$name.out" 2> "$dir/$name.err"
  local rc=$?
  [ "$rc" = 1 ] || fail "$name: exit $rc, expected 1"
  grep -qF -- "$text" "$dir/$name.err" || fail "$name: stderr lacks '$text': $(head -c 600 "$dir/$name.err")"
}
refuse missing "$dir/none.hdr: cannot open the environment image" -- "${render[@]}" --environment "$dir/none.hdr" -o "$dir/x.png"
refuse square "$dir/square.hdr" -- "${render[@]}" --environment "$dir/square.hdr" -o "$dir/x.png"
grep -qF "expected" "$dir/square.err" || fail "square: the refusal does not say what was expected"
refuse builtin "builtin:sky: no such built-in environment (expected builtin:studio)" -- \
  "${render[@]}" --environment builtin:sky -o "$dir/x.png"
mkfifo "$dir/fifo.hdr"
refuse fifo "$dir/fifo.hdr: the environment image is a FIFO, not a regular file" -- \
  "${render[@]}" --environment "$dir/fifo.hdr" -o "$dir/x.png"

# A playlist: one item lit by the file, one by a broken environment (reported, skipped), one by
# the default; it plays all the frames asked for and its status names the bad file.
cat > "$dir/list.toml" <<'TOML'
[[item]]
scene = "builtin:spheres"
duration = 0.5
environment = "white.hdr"

[[item]]
scene = "builtin:corner"
duration = 0.5
environment = "square.hdr"

[[item]]
scene = "builtin:demo"
duration = 0.5
TOML
timeout 120 "$player" play "$dir/list.toml" --platform egl --size 64x48 --frames 45 --status "$dir/status.json" \
  > "$dir/play.out" 2> "$dir/play.err"
rc=$?
[ "$rc" = 0 ] || fail "play: exit $rc: $(tail -5 "$dir/play.err")"
grep -qF "square.hdr" "$dir/status.json" || fail "play: the status does not name the bad environment: $(head -c 800 "$dir/status.json")"
printf '[[item]]\nscene = "builtin:demo"\nenvironment = "builtin:sky"\n' > "$dir/bad-name.toml"
refuse playlist_name "bad-name.toml:3:15: item[0].environment: expected a path or builtin:studio" -- \
  "$player" play "$dir/bad-name.toml" --platform egl --size 64x48 --frames 1
timeout 120 "$player" play builtin:demo --environment "$dir/white.hdr" --platform egl --size 64x48 --frames 3 \
  > "$dir/play-cli.out" 2>&1 || fail "play --environment failed: $(tail -5 "$dir/play-cli.out")"

[ "$failures" = 0 ] && echo "environment: all checks passed"
exit "$failures"
