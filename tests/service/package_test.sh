#!/bin/sh
# The Debian package as a board gets it, built by cpack from the build tree the tests run in (the
# binaries the other tests ran; nothing is rebuilt in another preset).
#   package_test.sh BUILD OUT
# Checks: the file name; the file list, exactly; the conffiles; Depends computed by dpkg-shlibdeps;
# the package unpacked into a scratch root (dpkg-deb -x) with postinst run against that root as
# dpkg --root runs it (DPKG_ROOT: the user and groups land in the root's /etc, nothing touches this
# machine's); the installed unit through systemd-analyze verify; the installed demo playlist played.
set -eu
build=$(cd "$1" && pwd)
out=$2
here=$(cd "$(dirname "$0")" && pwd)
source_dir=$(cd "$here/../.." && pwd)
rm -rf "$out"
mkdir -p "$out"
out=$(cd "$out" && pwd)
fail() {
  echo "FAIL: $*"
  exit 1
}

# cpack runs the build's `preinstall` target first; in a built tree that finds nothing to do.
if ! cpack -G DEB --config "$build/CPackConfig.cmake" -B "$out/cpack" > "$out/cpack.log" 2>&1; then
  cat "$out/cpack.log"
  fail "cpack -G DEB in $build"
fi
version=$(sed -n 's/^set(CPACK_PACKAGE_VERSION "\(.*\)")$/\1/p' "$build/CPackConfig.cmake")
arch=$(dpkg --print-architecture)
deb=$out/cpack/ssao-player_${version}_${arch}.deb
[ -f "$deb" ] || fail "expected $deb; cpack wrote: $(ls "$out/cpack")"
echo "package: $(basename "$deb")"

# The file list, exactly: what the unit, sysusers, udev, the board owner and the docs need.
dpkg-deb -c "$deb" | awk '{ print $NF }' | sed 's|^\./|/|; s|/$||' | grep -v '^$' | sort > "$out/files.actual"
{
  for dir in / /etc /etc/default /etc/ssao-player /usr /usr/bin /usr/lib /usr/lib/ssao-player /usr/lib/systemd /usr/lib/systemd/system \
             /usr/lib/sysusers.d /usr/lib/udev /usr/lib/udev/rules.d /usr/share /usr/share/doc /usr/share/doc/ssao-player \
             /usr/share/ssao-player /usr/share/ssao-player/board /usr/share/ssao-player/board/displays \
             /usr/share/ssao-player/demo /var /var/lib /var/lib/ssao-player; do
    echo "$dir"
  done
  echo /etc/default/ssao-player
  echo /etc/ssao-player/board.toml
  echo /usr/bin/player
  echo /usr/lib/ssao-player/libssao-player-images.so
  echo /usr/lib/systemd/system/ssao-player.service
  echo /usr/lib/systemd/system/ssao-player-fleet.service
  echo /usr/lib/systemd/system/ssao-player-content.service
  echo /usr/lib/systemd/system/ssao-player-content.path
  echo /usr/share/ssao-player/fleet.toml
  echo /usr/lib/sysusers.d/ssao-player.conf
  echo /usr/lib/udev/rules.d/60-ssao-player-gpio.rules
  echo /usr/share/doc/ssao-player/README.md
  echo /usr/share/doc/ssao-player/board.md
  (cd "$source_dir" && find docs -type d -o -type f -name '*.md') | sed 's|^|/usr/share/doc/ssao-player/|'
  for file in raspberry-pi-4.toml raspberry-pi-5.toml mock.toml buttons.script; do echo "/usr/share/ssao-player/board/$file"; done
  for file in "$source_dir"/board/displays/*; do echo "/usr/share/ssao-player/board/displays/$(basename "$file")"; done
  echo /usr/share/ssao-player/demo/playlist.toml
} | sed 's|^//*$|/|' | grep -v '^/$' | sort > "$out/files.expected"
sed -i '/^\/$/d' "$out/files.actual"
if ! diff -u "$out/files.expected" "$out/files.actual"; then fail "the package's files (- expected, + in the package)"; fi
echo "ok: $(wc -l < "$out/files.actual") paths, as expected"

# Control fields.
dpkg-deb -e "$deb" "$out/control"
[ "$(dpkg-deb -f "$deb" Package)" = ssao-player ] || fail "Package: expected ssao-player"
[ "$(dpkg-deb -f "$deb" Architecture)" = "$arch" ] || fail "Architecture: expected $arch"
depends=$(dpkg-deb -f "$deb" Depends)
echo "Depends: $depends"
# Computed from the binary's NEEDED libraries (versioned, as dpkg-shlibdeps writes them), and the
# systemd that postinst's systemd-sysusers comes from; tzdata for opening hours in a named zone.
# libopenimageio comes from the image module (/usr/lib/ssao-player), which the player loads on first use.
for needed in 'libc6 (>= ' 'libegl1' 'libgpiod2' 'libsystemd0' 'libstdc++6 (>= ' 'libopenimageio' 'libdate-tz3' 'libmosquitto1' 'libarchive13' 'systemd' 'tzdata'; do
  case ", $depends," in
    *", $needed"*) ;;
    *) fail "Depends: expected $needed..., got '$depends'" ;;
  esac
done
printf '/etc/default/ssao-player\n/etc/ssao-player/board.toml\n' > "$out/conffiles.expected"
diff -u "$out/conffiles.expected" "$out/control/conffiles" || fail "conffiles (- expected, + in the package)"
for script in postinst prerm postrm; do
  [ -x "$out/control/$script" ] || fail "$script: expected an executable maintainer script"
done

# Unpacked into a scratch root, configured the way dpkg --root configures it.
root=$out/root
dpkg-deb -x "$deb" "$root"
if ! DPKG_ROOT=$root "$out/control/postinst" configure > "$out/postinst.log" 2>&1; then
  cat "$out/postinst.log"
  fail "postinst configure with DPKG_ROOT=$root"
fi
grep -q '^ssao-player:x:[0-9]*:[0-9]*:[^:]*:/nonexistent:/usr/sbin/nologin$' "$root/etc/passwd" ||
  fail "$root/etc/passwd: expected the system user ssao-player with no home and no shell, got: $(cat "$root/etc/passwd")"
for group in video render gpio input; do
  grep -q "^$group:x:[0-9]*:\(.*,\)\?ssao-player\(,.*\)\?$" "$root/etc/group" ||
    fail "$root/etc/group: expected ssao-player in $group, got: $(cat "$root/etc/group")"
done
grep -q '^ssao-player-fleet:x:[0-9]*:[0-9]*:[^:]*:/nonexistent:/usr/sbin/nologin$' "$root/etc/passwd" ||
  fail "$root/etc/passwd: expected the fleet agent's system user ssao-player-fleet, got: $(cat "$root/etc/passwd")"
grep -q "^ssao-player-control:x:[0-9]*:\(.*,\)\?ssao-player-fleet\(,.*\)\?$" "$root/etc/group" ||
  fail "$root/etc/group: expected ssao-player-fleet in ssao-player-control, got: $(cat "$root/etc/group")"
echo "ok: postinst made the users and their groups in the scratch root"

# The unit as installed: ExecStart names the installed binary, the playlist it plays by default
# is installed, and systemd-analyze verify has nothing to say.
unit=$root/usr/lib/systemd/system/ssao-player.service
exec_start=$(sed -n 's/^ExecStart=\([^ ]*\) .*/\1/p' "$unit")
[ -x "$root$exec_start" ] || fail "$unit: ExecStart: $exec_start is not in the package"
playlist=$(sed -n 's/^Environment=PLAYER_PLAYLIST=//p' "$unit")
[ -f "$root$playlist" ] || fail "$unit: PLAYER_PLAYLIST: $playlist is not in the package"
"$here/verify_unit.sh" "$unit" "$root$exec_start" "$out/unit"
"$here/verify_unit.sh" "$root/usr/lib/systemd/system/ssao-player-fleet.service" "$root$exec_start" "$out/fleet-unit"
"$here/verify_unit.sh" "$root/usr/lib/systemd/system/ssao-player-content.service" "$root$exec_start" "$out/content-unit"
# The path unit beside the service it starts (verify looks for it there).
cp "$root/usr/lib/systemd/system/ssao-player-content.path" "$out/content-unit/"
systemd-analyze verify --man=no "$out/content-unit/ssao-player-content.path" > "$out/content-unit/path.log" 2>&1 ||
  fail "systemd-analyze verify ssao-player-content.path: $(cat "$out/content-unit/path.log")"
if grep -F ssao-player-content "$out/content-unit/path.log"; then fail "ssao-player-content.path has the complaints above"; fi
# The example fleet configuration is one the agent takes, once its password and CA files exist.
echo secret > "$out/fleet.password"
sed "s|/etc/ssao-player/fleet.password|$out/fleet.password|; s|/etc/ssl/certs/fleet-ca.pem|/etc/ssl/certs/ca-certificates.crt|" \
  "$root/usr/share/ssao-player/fleet.toml" > "$out/fleet.toml"
"$root$exec_start" fleet --config "$out/fleet.toml" --check > "$out/fleet.log" 2>&1 ||
  fail "the installed example fleet.toml: $(cat "$out/fleet.log")"
grep -q "^ok: .*mqtts://broker.example:8883" "$out/fleet.log" || fail "fleet --check: $(cat "$out/fleet.log")"

# The installed player plays the installed demo playlist (headless here), and writes its last frame
# through the installed image module.
if ! "$root$exec_start" play "$root$playlist" --platform egl --size 64x48 --frames 3 --snapshot "$out/demo.png" \
  --shader-cache off > "$out/demo.log" 2>&1; then
  cat "$out/demo.log"
  fail "the installed player on the installed demo playlist"
fi
grep -q '^playing .*/usr/share/ssao-player/demo/playlist.toml: 3 item(s)$' "$out/demo.log" || fail "demo: $(cat "$out/demo.log")"
grep -q '^played 3 frames, 0 error(s)$' "$out/demo.log" || fail "demo: $(cat "$out/demo.log")"
"$root$exec_start" info --platform egl --shader-cache off > "$out/info.log" 2>&1 || fail "player info: $(cat "$out/info.log")"
grep -q "^image files: *$root/usr/lib/ssao-player/libssao-player-images.so (OpenImageIO " "$out/info.log" ||
  fail "the installed player does not use the installed image module: $(grep '^image files' "$out/info.log")"
[ -s "$out/demo.png" ] || fail "demo: --snapshot wrote no $out/demo.png (the image module: $(cat "$out/demo.log"))"
echo "ok: the installed player plays the installed demo playlist"
