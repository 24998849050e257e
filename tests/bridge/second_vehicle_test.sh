#!/usr/bin/env bash
# SPDX-License-Identifier: BSD-3-Clause
# A user's own vehicle end to end (issue 12): the 0.6 kg 5-inch quadrotor of
# config/vehicles/quad5.yaml, built as config/truths/quad5_as_built.yaml, goes
#   rig logs (single-rotor stand; platform: level board, tilted board, mixing) and a flight log
#   (a hover descent) → geaware identify → a vehicle file → `geaware fly` with `recommended` in
#   process → the same flight through `geaware sitl` + `geaware bridge` over DDS.
# Asserts: the identified k_T and throttle curve match the world's (the rigs measure the mean of
# the four motors); the in-process flight with the identified vehicle finishes without a strike;
# through DDS all-RMSE within 1.5x of it, every tick flown, no strike (dds_flight_test.sh).
# Usage: second_vehicle_test.sh GEAWARE OUTDIR DOMAIN   (run from the source root)
# The commands and their numbers: docs/vehicle.md, "A second vehicle".
set -euo pipefail
geaware=$1 out=$2 domain=$3
src=$(pwd)
truth=$src/config/truths/quad5_as_built.yaml
mkdir -p "$out"
cd "$out"
rm -f ./*.csv ./*.yaml ./*.json ./*.txt

# 1. The rigs, in the world as built (docs/identification.md, "Round trip"), the sweeps of the
#    paper's vehicle with heights × 0.7 (this propeller's radius against the paper's) and rotor
#    speeds around this vehicle's hover (10,848 rpm).
"$geaware" rig rotor --truth "$truth" --throttle 0:1:0.1 --seed 1 --out rotor.csv
"$geaware" rig platform --truth "$truth" --heights 0.05:0.70:0.01 --rpm 8000:16000:4000 \
  --samples 20 --seed 2 --out level.csv
"$geaware" rig platform --truth "$truth" --heights 0.06:0.28:0.02 --tilts-deg 2:10:4 \
  --rpm 8000:16000:4000 --samples 20 --seed 3 --out tilted.csv
"$geaware" rig platform --truth "$truth" --heights 0.7:1.4:0.35 --rpm 8000:16000:4000 \
  --rpm-diff -1500:1500:750 --samples 20 --seed 4 --out mixing.csv
awk -F, -v OFS=, -v CONVFMT=%.17g -v OFMT=%.17g \
    'FNR == 1 { if (NR == 1) print; off = t + 1; next } { t = $1 + off; $1 = t; print }' \
    level.csv tilted.csv mixing.csv > platform.csv

# 2. Identify: the stand, then the platform (ground effect as tables), on the team's belief.
"$geaware" identify rotor rotor.csv --vehicle "$src/config/vehicles/quad5.yaml" --out rotor.yaml \
  --json rotor.json > rotor.txt
"$geaware" identify platform platform.csv --ground-effect table --vehicle rotor.yaml \
  --out rigs.yaml --json platform.json > platform.txt

# 3. A flight log: a hover descent from 0.7 m to 0.06 m flown on the rig-identified vehicle
#    (`recommended`, quad5's gains); identify flight --hover replaces k_T and F_G(h) with what
#    the vehicle meets in flight (the rigs' cushion is not the flight's, docs/world.md §3).
"$geaware" fly --truth "$truth" --vehicle rigs.yaml \
  --controller-params "$src/config/controller-params/quad5.yaml" --trajectory hover-descent \
  --from-height 0.7 --height 0.06 --controller recommended --quiet --json descent.json \
  --out hover.csv >/dev/null
"$geaware" identify flight --hover hover.csv --vehicle rigs.yaml --out identified.yaml \
  --json hover.json > hover.txt
cat rotor.txt platform.txt hover.txt

# 4. The lemniscate with `recommended` on the identified vehicle: in process, then over DDS.
sed -e "s|^vehicle: .*|vehicle: $out/identified.yaml|" \
    -e "s|^truth: .*|truth: $truth|" \
    -e "s|^controller_params: .*|controller_params: $src/config/controller-params/quad5.yaml|" \
    "$src/config/scenarios/lemniscate_low_quad5.yaml" > scenario.yaml
cd "$src"
bash "$src/tests/bridge/dds_flight_test.sh" "$geaware" "$out/dds" "$domain" "$out/scenario.yaml"

python3 - "$out" <<'PY'
import json, sys
out = sys.argv[1]
def fitted(path, key):
    return json.load(open(f"{out}/{path}"))["parameters"][key]["value"]
# The world's rotors (config/truths/quad5_as_built.yaml): k_T 1.25e-8 N/rpm² times the motors'
# scales 1.02, 0.98, 0.99, 1.01 — the stand holds motor 1 (1.02), the platform all four (mean 1).
k_stand = fitted("rotor.json", "rotor.k_T_N_per_rpm2")
k_platform = fitted("platform.json", "rotor.k_T_N_per_rpm2")
k_flight = fitted("hover.json", "rotor.k_T_N_per_rpm2")
print(f"k_T stand {k_stand:.5g}, platform {k_platform:.5g}, flight {k_flight:.5g} N/rpm^2")
assert abs(k_stand / (1.02 * 1.25e-8) - 1) < 0.01, "stand k_T off the world's motor 1"
assert abs(k_platform / 1.25e-8 - 1) < 0.01, "platform k_T off the world's mean"
assert abs(k_flight / 1.25e-8 - 1) < 0.02, "flight k_T off the world's mean"
# Throttle curve: the world's n(t) = 2000 + 28000 t rpm at half throttle (motor 1: the curve is
# the ESC's, the same for every motor).
c2, c1, c0 = (fitted("rotor.json", f"throttle_curve.{k}_rpm2") for k in ("c2", "c1", "c0"))
n_half = (c2 * 0.25 + c1 * 0.5 + c0) ** 0.5
print(f"throttle curve: {n_half:.0f} rpm at t = 0.5")
assert abs(n_half / 16000 - 1) < 0.01
descent = json.load(open(f"{out}/descent.json"))
assert not descent["crashed"], "the identification flight struck the ground"
PY
