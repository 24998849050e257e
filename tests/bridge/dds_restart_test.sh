#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A running bridge outlives its simulator: the first simulator is killed mid-flight (the bridge
# stops its commands within the input timeout and says so), a second one starts, the bridge
# discovers it and flies its flight to the end, then exits (--flights 1) with status 0.
# Usage: dds_restart_test.sh GEAWARE OUTDIR DOMAIN SCENARIO
set -euo pipefail
geaware=$1 out=$2 domain=$3 scenario=$4
timeout_s=0.3
mkdir -p "$out"
rm -f "$out"/*
"$geaware" bridge --scenario "$scenario" --domain "$domain" --input-timeout "$timeout_s" \
  --flights 1 >"$out/bridge.out" 2>"$out/bridge.err" &
bridge=$!
"$geaware" sitl --scenario "$scenario" --domain "$domain" --wait-bridge 60 \
  >"$out/sitl1.out" 2>"$out/sitl1.err" &
sitl=$!
trap 'kill "$bridge" "$sitl" 2>/dev/null || true' EXIT
for _ in $(seq 1 600); do
  grep -q "sending motor commands" "$out/bridge.err" && break
  sleep 0.1
done
sleep 1
kill -9 "$sitl"
wait "$sitl" 2>/dev/null || true
killed=$(date +%s.%N)
for _ in $(seq 1 250); do
  grep -q "motor commands stopped" "$out/bridge.err" && break
  sleep 0.02
done
reported=$(date +%s.%N)
grep -q "mid-flight" "$out/bridge.err" || { echo "no stop reported"; cat "$out/bridge.err"; exit 1; }
elapsed=$(python3 -c "print(f'{$reported - $killed:.3f}')")
echo "the bridge reported the stop $elapsed s after the kill (input timeout $timeout_s s)"
python3 -c "import sys; sys.exit(0 if $elapsed < $timeout_s + 1.0 else 1)" || { echo "too slow"; exit 1; }
# A new simulator: the same bridge flies it to the end.
"$geaware" sitl --scenario "$scenario" --domain "$domain" --wait-bridge 60 \
  >"$out/sitl2.out" 2>"$out/sitl2.err" || { echo "second sitl failed"; cat "$out"/sitl2.* "$out/bridge.err"; exit 1; }
status=0
wait "$bridge" || status=$?
trap - EXIT
cat "$out/bridge.err" "$out/bridge.out" "$out/sitl2.out"
[[ $status -eq 0 ]] || { echo "bridge exit status $status"; exit 1; }
grep -q "1 flights completed" "$out/bridge.out"
grep -q "completed, no crash" "$out/sitl2.out"
