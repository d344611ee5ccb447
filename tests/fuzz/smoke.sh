#!/usr/bin/env bash
# One fuzz target's smoke run for ctest (label `fuzz`): the committed seeds and regressions are
# copied into a fresh scratch corpus (so a run never grows the committed ones), then libFuzzer
# mutates them for a bounded time from a fixed seed. A finding fails the test and stays in
# <scratch>/findings for `tests/fuzz/regressions/<target>/`.
# Usage: smoke.sh BINARY SCRATCH SECONDS DICT|- INPUT...   (INPUT: a file or a folder, read flat)
set -euo pipefail
binary=$1 scratch=$2 seconds=$3 dict=$4
shift 4
rm -rf "$scratch"
mkdir -p "$scratch/corpus" "$scratch/findings" "$scratch/tmp"
for input in "$@"; do
  if [ -d "$input" ]; then
    find "$input" -maxdepth 1 -type f -exec cp -t "$scratch/corpus" {} +
  elif [ -f "$input" ]; then
    cp "$input" "$scratch/corpus/"
  else
    echo "smoke.sh: $input: expected a seed file or folder" >&2
    exit 2
  fi
done
args=(-max_total_time="$seconds" -seed=1 -timeout=10 -rss_limit_mb=2048 -max_len=65536
      -print_final_stats=1 -artifact_prefix="$scratch/findings/")
[ "$dict" != - ] && args+=(-dict="$dict")
set +e
# The target's scratch folder (fuzz_dir.h) under $scratch: a finding ends the run without exit handlers.
TMPDIR=$scratch/tmp "$binary" "${args[@]}" "$scratch/corpus"
rc=$?
set -e
if [ $rc -ne 0 ]; then
  echo "smoke.sh: $(basename "$binary"): finding(s) in $scratch/findings:" >&2
  ls -l "$scratch/findings" >&2
fi
exit $rc
