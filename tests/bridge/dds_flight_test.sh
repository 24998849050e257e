#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# `geaware sitl` + `geaware bridge` as two processes over DDS (unicast 127.0.0.1, multicast off,
# domain DOMAIN of this test's own) fly SCENARIO to the end; all-RMSE within 1.5x of the same
# flight in one process (`geaware fly`, same scenario: same seed, same truth), no strike.
# Usage: dds_flight_test.sh GEAWARE OUTDIR DOMAIN SCENARIO [CONTROLLER]
# CONTROLLER: the scenario's, for the bridge (default: the bridge takes the scenario's own).
set -euo pipefail
geaware=$1 out=$2 domain=$3 scenario=$4
controller=()
[[ $# -ge 5 ]] && controller=(--controller "$5")
mkdir -p "$out"
rm -f "$out"/fly.json "$out"/sitl.json
"$geaware" fly --scenario "$scenario" --quiet --json "$out/fly.json" >/dev/null
# The scenario file's controller for both, so that the flights compare.
fly_dds() {
"$geaware" bridge --scenario "$scenario" "${controller[@]}" --domain "$domain" \
  --flights 1 --input-timeout 1 --exit-on-stale --stats >"$out/bridge.out" 2>"$out/bridge.err" &
bridge=$!
trap 'kill "$bridge" 2>/dev/null || true' EXIT
"$geaware" sitl --scenario "$scenario" --domain "$domain" --wait-bridge 60 --json "$out/sitl.json" \
  >"$out/sitl.out" 2>"$out/sitl.err" || { echo "sitl failed:"; cat "$out/sitl.out" "$out/sitl.err"; cat "$out/bridge.err"; exit 1; }
wait "$bridge" || { echo "bridge failed:"; cat "$out/bridge.out" "$out/bridge.err"; exit 1; }
trap - EXIT
}
fly_dds
# Samples that reach the bridge after their tick has run ("N late") break the lockstep's
# determinism; on a loaded machine a few runs in ten showed some (a known race, docs/bridge.md,
# "Lockstep"). Such a run is flown once more; a second one with late samples is judged as it is.
if ! grep -q ", 0 late" "$out/bridge.out"; then
  echo "late samples in the lockstep: $(grep -o '[0-9]* late' "$out/bridge.out"); flying again once"
  rm -f "$out"/sitl.json
  fly_dds
fi
cat "$out/sitl.out" "$out/bridge.out"
python3 - "$out/fly.json" "$out/sitl.json" <<'PY'
import json, sys
fly, sitl = (json.load(open(p)) for p in sys.argv[1:3])
a, b = fly["rmse_all_cm"], sitl["rmse_all_cm"]
print(f"all-RMSE in one process {a:.3f} cm, through DDS {b:.3f} cm, ratio {b / a:.3f}")
assert not sitl["crashed"], f"strike: {sitl['crash']}"
assert sitl["samples"] == fly["samples"], f"flew {sitl['samples']} of {fly['samples']} ticks"
assert b <= 1.5 * a, "all-RMSE through DDS more than 1.5x the in-process flight's"
PY
grep -q "1 flights completed" "$out/bridge.out"
