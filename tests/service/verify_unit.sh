#!/bin/sh
# systemd-analyze verify on a unit file, failing on any complaint about it, not only on its exit
# status: verify reports unknown keys and bad values as warnings and still exits 0.
#   verify_unit.sh UNIT PLAYER OUT
# ExecStart's /usr/bin/player is replaced by PLAYER, because verify checks that the binary exists
# and this machine need not have the player installed; everything else is verified as written.
set -eu
unit=$1 player=$2 out=$3
name=$(basename "$unit")
mkdir -p "$out"
if ! grep -q '^ExecStart=/usr/bin/player ' "$unit"; then
  echo "FAIL: $unit: ExecStart: expected /usr/bin/player, the package's binary"
  exit 1
fi
sed "s|^ExecStart=/usr/bin/player |ExecStart=$player |" "$unit" > "$out/$name"
if ! systemd-analyze verify --man=no "$out/$name" > "$out/verify.log" 2>&1; then
  cat "$out/verify.log"
  echo "FAIL: systemd-analyze verify $name exited with an error"
  exit 1
fi
# Complaints name the unit or its file; none is allowed. (Lines about the machine running verify,
# such as a missing $container of PID 1, do not.)
if grep -F "$name" "$out/verify.log"; then
  echo "FAIL: systemd-analyze verify $name has the complaints above"
  exit 1
fi
echo "ok: systemd-analyze verify $name"
