#!/usr/bin/env bash
# Content that arrives whole, as an operator installs it: `player content install` checks a bundle
# with the loader before it becomes current; a bundle with a corrupt scene is refused, reported by
# the playing player, and the old version keeps playing; a good one swapped in during playback is
# shown from the next item boundary; rollback restores the previous version exactly; tars unpack,
# and one that reaches outside the bundle or holds a link is refused; --keep prunes.
# Usage: content.sh PLAYER SCENES_DIR OUT_DIR
set -u
player=$1 scenes=$2 out=$3
dir=$out/content
rm -rf "$dir" && mkdir -p "$dir"
pid=
cleanup() { [ -n "$pid" ] && kill "$pid" 2>/dev/null; wait 2>/dev/null; }
trap cleanup EXIT
fail() { echo "content: $*"; exit 1; }
wait_for() {  # PATTERN SECONDS FILE
  for _ in $(seq 1 $(($2 * 10))); do grep -q -- "$1" "$3" 2>/dev/null && return 0; sleep 0.1; done
  return 1
}
root=$dir/root
# Two shows of 1-second items (boundaries at whole seconds of the playlist clock), and a broken one.
mkdir -p "$dir/v1/models" "$dir/v2" "$dir/bad"
cp "$scenes/spot.glb" "$dir/v1/models/spot.glb"
printf '[[item]]\nscene = "models/spot.glb"\nduration = 1\n[[item]]\nscene = "builtin:spheres"\nduration = 1\n' >"$dir/v1/playlist.toml"
cp "$scenes/fandisk.glb" "$dir/v2/fandisk.glb"
printf 'fade = 0\n[[item]]\nscene = "fandisk.glb"\nduration = 1\n[[item]]\nscene = "builtin:demo"\nduration = 1\n' >"$dir/v2/playlist.toml"
touch "$dir/v2/.syncthing.fandisk.glb.tmp"  # a synchroniser's partial file: left out
cp "$dir/v1/playlist.toml" "$dir/bad/playlist.toml"
mkdir -p "$dir/bad/models"
head -c 2000 "$scenes/spot.glb" >"$dir/bad/models/spot.glb"

"$player" content install "$dir/v1" --root "$root" >"$dir/install-v1.log" 2>&1 || fail "v1: $(cat "$dir/install-v1.log")"
v1=$(sed -n 's/^ok: installed \([^ ]*\) .*/\1/p' "$dir/install-v1.log")
[ -n "$v1" ] && [ "$(readlink "$root/current")" = "versions/$v1" ] || fail "v1 is not current: $(ls -l "$root")"
diff -r "$dir/v1" "$root/versions/$v1" >/dev/null || fail "v1 was not installed as it is"
touch "$root/versions/$v1/playlist.toml" 2>/dev/null && [ "$(id -u)" != 0 ] && fail "an installed version is writable"

"$player" play "$root/current/playlist.toml" --platform egl --size 64x48 --fps 30 --shader-cache off --hal mock \
  --log "$dir/play.log" --status "$dir/status.json" >"$dir/play.out" 2>&1 &
pid=$!
wait_for "playing $root/versions/$v1/playlist.toml" 60 "$dir/play.out" || fail "the player did not start on v1: $(cat "$dir/play.out")"
wait_for " item=1 " 60 "$dir/play.log" || fail "v1 does not play: $(tail -3 "$dir/play.log")"

# A corrupt scene: refused with the file named, nothing changed, the player reports it and plays on.
if "$player" content install "$dir/bad" --root "$root" >"$dir/install-bad.log" 2>&1; then fail "the corrupt bundle was installed"; fi
grep -q "^error: .*bad/models/spot.glb: not a valid glTF.*the bundle was not installed; version $v1 stays" "$dir/install-bad.log" ||
  fail "the refusal does not name the file: $(cat "$dir/install-bad.log")"
[ "$(readlink "$root/current")" = "versions/$v1" ] || fail "current moved after a refused install"
[ "$(ls "$root/versions")" = "$v1" ] || fail "the refused bundle left files: $(ls -a "$root/versions")"
wait_for "content install of .*bad refused: .*models/spot.glb" 60 "$dir/status.json" || fail "the player did not report the refusal: $(cat "$dir/status.json")"
grep -q '"error": *"blink-slow"' "$dir/status.json" || fail "the error LED does not warn: $(cat "$dir/status.json")"
echo "ok: a bundle with a corrupt scene is refused and reported; $v1 plays on"

# A good one, as a tar of its folder: shown from the next item boundary.
tar -C "$dir" -czf "$dir/v2.tar.gz" v2
"$player" content install "$dir/v2.tar.gz" --root "$root" >"$dir/install-v2.log" 2>&1 || fail "v2: $(cat "$dir/install-v2.log")"
v2=$(sed -n 's/^ok: installed \([^ ]*\) .*/\1/p' "$dir/install-v2.log")
[ -e "$root/versions/$v2/.syncthing.fandisk.glb.tmp" ] && fail "a dot-file was installed"
wait_for "content: playing $root/versions/$v2/playlist.toml from frame" 90 "$dir/play.out" || fail "v2 was not followed: $(cat "$dir/play.out")"
frame=$(sed -n "s|^content: playing $root/versions/$v2/playlist.toml from frame \([0-9]*\)$|\1|p" "$dir/play.out")
# The frame before the swap and the swap's frame lie on either side of a whole second.
awk -v f="$frame" '{ sub("t=", "", $2) } $1 == f - 1 { before = $2 } $1 == f { at = $2 } END {
  if (before == "" || at == "" || int(before) == int(at)) { print "swap at frame " f ": t " before " -> " at; exit 1 } }' "$dir/play.log" ||
  fail "v2 was not swapped in at an item boundary"
echo "ok: $v2 (from a tar) shown from frame $frame, an item boundary"

# Rollback: v1 again, byte for byte, followed by the player.
(cd "$root/versions/$v1" && find . -type f | sort | xargs sha256sum) >"$dir/v1.sums"
"$player" content rollback --root "$root" >"$dir/rollback.log" 2>&1 || fail "rollback: $(cat "$dir/rollback.log")"
grep -q "^ok: current -> versions/$v1, was $v2$" "$dir/rollback.log" || fail "rollback: $(cat "$dir/rollback.log")"
(cd "$root/current" && sha256sum -c --quiet "$dir/v1.sums") || fail "the rolled back version differs from v1"
diff -r "$dir/v1" "$root/current/" >/dev/null || fail "the rolled back version differs from the v1 bundle"
wait_for "content: playing $root/versions/$v1/playlist.toml from frame" 90 "$dir/play.out" || fail "the rollback was not followed"
if "$player" content rollback --root "$root" >"$dir/rollback-again.log" 2>&1; then fail "rolled back past the oldest version"; fi
grep -q "no version older than the current $v1" "$dir/rollback-again.log" || fail "$(cat "$dir/rollback-again.log")"
"$player" content install "$dir/v2" --root "$root" >"$dir/install-v2-again.log" 2>&1 || fail "$(cat "$dir/install-v2-again.log")"
grep -q "is version $v2 again: current -> versions/$v2" "$dir/install-v2-again.log" || fail "$(cat "$dir/install-v2-again.log")"
echo "ok: rollback restored $v1 exactly; installing v2 again made it current without a copy"
kill "$pid"
wait "$pid" 2>/dev/null
pid=

# Tars that reach outside the bundle or hold a link are refused before anything is written there.
python3 - "$dir" <<'PY'
import io, sys, tarfile
d = sys.argv[1]
def tar(name, members):
    with tarfile.open(f"{d}/{name}", "w") as t:
        for member, data in members:
            t.addfile(member, io.BytesIO(data) if data is not None else None)
def file(name, data):
    m = tarfile.TarInfo(name); m.size = len(data); return (m, data)
def link(name, target):
    m = tarfile.TarInfo(name); m.type = tarfile.SYMTYPE; m.linkname = target; return (m, None)
playlist = b'[[item]]\nscene = "builtin:demo"\n'
tar("escape.tar", [file("playlist.toml", playlist), file("../escaped.txt", b"x")])
tar("absolute.tar", [file("playlist.toml", playlist), file("/tmp/absolute.txt", b"x")])
tar("link.tar", [file("playlist.toml", playlist), link("scene.glb", "/etc/passwd")])
PY
for name in escape absolute link; do
  if "$player" content install "$dir/$name.tar" --root "$root" >"$dir/$name.log" 2>&1; then fail "$name.tar was installed"; fi
done
grep -q "escape.tar: ../escaped.txt: a path outside the bundle" "$dir/escape.log" || fail "$(cat "$dir/escape.log")"
grep -q "absolute.tar: /tmp/absolute.txt: a path outside the bundle" "$dir/absolute.log" || fail "$(cat "$dir/absolute.log")"
grep -q "link.tar: scene.glb: not a regular file or folder" "$dir/link.log" || fail "$(cat "$dir/link.log")"
[ -e "$dir/escaped.txt" ] || [ -e "$root/escaped.txt" ] || [ -e "$root/versions/escaped.txt" ] && fail "a file escaped the bundle"
echo "ok: tars with a path outside the bundle or a link are refused"

# An inbox, as ssao-player-content.path hands it over: every bundle taken oldest first and removed,
# the broken one refused and reported, a transfer in progress (a dot-name) left alone.
inbox=$dir/incoming
mkdir -p "$inbox"
tar -C "$dir/bad" -cf "$inbox/1-bad.tar" .
sleep 1
tar -C "$dir/v1" -cf "$inbox/2-v1.tar" .
touch "$inbox/.3-partial.tar"
if "$player" content take "$inbox" --root "$root" >"$dir/take.log" 2>&1; then fail "take reported success with a broken bundle"; fi
grep -q "1-bad.tar: models/spot.glb: not a valid glTF\|1-bad.tar/models/spot.glb: not a valid glTF" "$dir/take.log" || fail "take: $(cat "$dir/take.log")"
grep -q "2-v1.tar is version $v1 again" "$dir/take.log" || fail "take: $(cat "$dir/take.log")"
[ "$(ls -A "$inbox")" = ".3-partial.tar" ] || fail "the inbox holds: $(ls -A "$inbox")"
echo "ok: an inbox of bundles taken in order, the broken one refused"

# --keep: the current version and the N before it stay.
for i in 3 4 5; do
  mkdir -p "$dir/v$i"
  printf '[[item]]\nscene = "builtin:demo"\nduration = %s\n' "$i" >"$dir/v$i/playlist.toml"
  sleep 1  # ids are made of the second they were installed in
  "$player" content install "$dir/v$i" --root "$root" --keep 1 >"$dir/install-v$i.log" 2>&1 || fail "$(cat "$dir/install-v$i.log")"
done
[ "$(ls "$root/versions" | wc -l)" = 2 ] || fail "--keep 1 kept: $(ls "$root/versions")"
"$player" content list --root "$root" >"$dir/list.log" || fail "list"
[ "$(grep -c '^\* ' "$dir/list.log")" = 1 ] && tail -1 "$dir/list.log" | grep -q '^\* ' || fail "list: $(cat "$dir/list.log")"
echo "content: bundles checked, swapped at item boundaries, refused whole, rolled back exactly"
