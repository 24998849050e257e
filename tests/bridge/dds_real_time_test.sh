#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# `geaware sitl --real-time` + `geaware bridge --real-time` (no lockstep: the simulator paces
# itself by the wall clock and flies the newest command, the bridge ticks on the vehicle's IMU
# time, as on a vehicle) fly a short hover descent to its end. Asserts what cannot flake on a
# loaded machine: the flight ran to the end without a strike and without the simulator losing
# the bridge (a simulator without commands for --command-timeout stops, status 3), and the
# bridge answered on most control ticks (it keeps up). No latency or RMSE bound: timings depend
# on the machine; the lockstep tests check the flying.
# Usage: dds_real_time_test.sh GEAWARE OUTDIR DOMAIN
set -euo pipefail
geaware=$1 out=$2 domain=$3
mkdir -p "$out"
rm -f "$out"/sitl.json
sed -e '/^trajectory:/,/^controller:/d' config/scenarios/lemniscate_low_recommended.yaml > "$out/base.yaml"
cat >> "$out/base.yaml" <<'YAML'
trajectory:
  type: hover_descent
  position_xy_m: [0.0, 0.0]
  from_height_m: 0.40
  to_height_m: 0.25
  descent_rate_mps: 0.1
  ramp_time_s: 0.5
  hold_start_s: 0.5
  hold_end_s: 0.5
  yaw_deg: 0.0
controller: recommended
YAML
# The bridge runs until stopped: in real time its trajectory starts at its first tick, 5-20 ms
# after the simulator's, so when the simulator ends with its trajectory the bridge's has not
# quite ended, and --flights 1 / --exit-on-stale would call that "mid-flight" (by a tick or
# less). It is stopped with SIGTERM (its clean stop) once the simulator has finished.
"$geaware" bridge --scenario "$out/base.yaml" --domain "$domain" --real-time \
  --input-timeout 1 --stats >"$out/bridge.out" 2>"$out/bridge.err" &
bridge=$!
trap 'kill "$bridge" 2>/dev/null || true' EXIT
"$geaware" sitl --scenario "$out/base.yaml" --domain "$domain" --real-time --wait-bridge 60 \
  --command-timeout 1 --json "$out/sitl.json" >"$out/sitl.out" 2>"$out/sitl.err" \
  || { echo "sitl failed:"; cat "$out/sitl.out" "$out/sitl.err" "$out/bridge.err"; exit 1; }
kill -TERM "$bridge"
wait "$bridge" || { echo "bridge failed:"; cat "$out/bridge.out" "$out/bridge.err"; exit 1; }
trap - EXIT
cat "$out/sitl.out" "$out/bridge.out"
python3 - "$out/sitl.json" "$out/bridge.out" <<'PY'
import json, re, sys
sitl = json.load(open(sys.argv[1]))
bridge = open(sys.argv[2]).read()
assert not sitl["crashed"], f"strike: {sitl['crash']}"
commands = int(re.search(r"bridge: (\d+) motor commands", bridge).group(1))
ticks = round(sitl["simulated_s"] * 200)
print(f"{commands} commands over {sitl['simulated_s']:.2f} s of flight ({ticks} control periods)")
assert commands >= 0.5 * ticks, "the bridge answered on fewer than half of the control ticks"
PY
