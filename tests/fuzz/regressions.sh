#!/usr/bin/env bash
# One fuzz target's regression run outside the fuzz preset (fuzz.regressions.<target>): the seeds and
# regression files through regression_main.cpp, with TMPDIR pointed at a fresh folder so that the
# run also shows it removes its scratch folder (fuzz_dir.h) on exit. Leaking one per run filled /tmp
# with player-fuzz-* folders, a test run at a time.
# Usage: regressions.sh BINARY TMPDIR INPUT...
set -euo pipefail
binary=$1 tmp=$2
shift 2
rm -rf "$tmp"
mkdir -p "$tmp"
TMPDIR=$tmp "$binary" "$@"
left=$(find "$tmp" -mindepth 1 -maxdepth 1)
if [ -n "$left" ]; then
  echo "regressions.sh: $(basename "$binary") left its scratch behind: $left" >&2
  exit 1
fi
