#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# Killing the simulator mid-flight: the bridge stops sending motor commands within its input
# timeout, says so, and (with --exit-on-stale) exits with status 3.
# Usage: dds_kill_test.sh GEAWARE OUTDIR DOMAIN SCENARIO
set -euo pipefail
geaware=$1 out=$2 domain=$3 scenario=$4
timeout_s=0.3
mkdir -p "$out"
# A previous run's bridge.err holds "sending motor commands": the loop below could read it
# before the new bridge's redirection truncates it, and then find it gone ("bridge never flew").
rm -f "$out"/*
"$geaware" bridge --scenario "$scenario" --domain "$domain" --input-timeout "$timeout_s" \
  --exit-on-stale >"$out/bridge.out" 2>"$out/bridge.err" &
bridge=$!
"$geaware" sitl --scenario "$scenario" --domain "$domain" --wait-bridge 60 \
  >"$out/sitl.out" 2>"$out/sitl.err" &
sitl=$!
trap 'kill "$bridge" "$sitl" 2>/dev/null || true' EXIT
# Wait until the bridge flies, then a little more, then kill the simulator without warning.
for _ in $(seq 1 600); do
  grep -q "sending motor commands" "$out/bridge.err" && break
  sleep 0.1
done
grep -q "sending motor commands" "$out/bridge.err" || { echo "bridge never flew"; cat "$out"/*.err; exit 1; }
sleep 1
kill -9 "$sitl"
killed=$(date +%s.%N)
status=0
wait "$bridge" || status=$?
stopped=$(date +%s.%N)
trap - EXIT
cat "$out/bridge.err"
elapsed=$(python3 -c "print(f'{$stopped - $killed:.3f}')")
echo "bridge exited with status $status, $elapsed s after the kill (input timeout $timeout_s s)"
[[ $status -eq 3 ]] || { echo "expected exit status 3"; exit 1; }
grep -q "motor commands stopped" "$out/bridge.err"
grep -q "mid-flight" "$out/bridge.err"
# Within the timeout plus the loop's 10 ms wait and process exit: 1 s is generous.
python3 -c "import sys; sys.exit(0 if $elapsed < $timeout_s + 1.0 else 1)" || { echo "too slow"; exit 1; }
