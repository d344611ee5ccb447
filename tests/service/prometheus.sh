#!/usr/bin/env bash
# The fleet's Prometheus files (board/prometheus/): the example configuration and its alert rules
# are what promtool accepts, and the alerts fire on the series a player in trouble writes
# (prometheus_alerts_test.yml), and not on one that plays.
# Usage: prometheus.sh PROMTOOL SOURCE_DIR OUT_DIR
set -u
promtool=$1 source=$2 out=$3
fail() { echo "prometheus: $*"; exit 1; }
[ -x "$promtool" ] || fail "no promtool at '$promtool': tools/install-deps unpacks Debian's into ~/.cache/ssao-player/promtool"
dir=$out/prometheus
rm -rf "$dir" && mkdir -p "$dir"
"$promtool" check config "$source/board/prometheus/prometheus.yml" >"$dir/config.out" 2>&1 ||
  fail "check config: $(cat "$dir/config.out")"
sed "s|RULES|$source/board/prometheus/ssao-player-alerts.yml|" "$source/tests/service/prometheus_alerts_test.yml" >"$dir/alerts_test.yml"
"$promtool" test rules "$dir/alerts_test.yml" >"$dir/test.out" 2>&1 || fail "test rules: $(cat "$dir/test.out")"
echo "prometheus: the configuration, the rules and their tests pass"
