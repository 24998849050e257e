#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The rosidl wire check of the bridge's hand-written IDL (issue 12).

For every PX4 type in idl/px4_msgs/msg/, the IDL struct must carry the fields of PX4's .msg
(tests/fixtures/px4_msg/, the commits idl/README.md lists) in the same order, with the types
rosidl makes of them (uint8/char -> uint8, bool -> boolean, float32 -> float, T[n] -> T name[n],
a nested message -> px4_msgs::msg::dds_::T_), constants left out. Then the XCDR1 (plain CDR)
layout of both — each primitive aligned to its size, 8-byte ones to 8, from the start of the
payload — is computed field by field, and the offsets of the two must agree; the total sizes are
pinned to values worked out by hand below, so that a change to either side shows here.

Usage: idl_wire_check.py SOURCE_DIR
"""
import re
import sys
from pathlib import Path

PRIMITIVE = {"boolean": 1, "uint8": 1, "int8": 1, "uint16": 2, "int16": 2, "uint32": 4,
             "int32": 4, "float": 4, "uint64": 8, "int64": 8, "double": 8}
MSG_TO_IDL = {"bool": "boolean", "char": "uint8", "byte": "uint8", "uint8": "uint8", "int8": "int8",
              "uint16": "uint16", "int16": "int16", "uint32": "uint32", "int32": "int32",
              "uint64": "uint64", "int64": "int64", "float32": "float", "float64": "double"}

# Serialized XCDR1 payload sizes [bytes], by hand (offsets in the comments).
PINNED = {
    # timestamp 0, gyro_rad 8, gyro_integral_dt 20, accelerometer_timestamp_relative 24,
    # accelerometer_m_s2 28, accelerometer_integral_dt 40, four uint8 44..47
    "SensorCombined": 48,
    # timestamp 0, timestamp_sample 8, pose_frame 16, position 20, q 32, velocity_frame 48,
    # velocity 52, angular_velocity 64, three variances 76/88/100, reset_counter 112, quality 113
    "VehicleOdometry": 114,
    # timestamp 0, timestamp_sample 8, reversible_flags 16, control 20..67
    "ActuatorMotors": 68,
    # timestamp 0, seven booleans 8..14
    "OffboardControlMode": 15,
    # timestamp 0, device_id 8, four floats 12..27, signal_quality 28, type 29, h_fov 32,
    # v_fov 36, q 40..55, orientation 56, mode 57
    "DistanceSensor": 58,
    # timestamp 0, esc_errorcount 8, esc_rpm 12, four floats 16..31, four uint8 32..35,
    # failures 36, esc_power 38
    "EscReport": 39,
    # timestamp 0, counter 8, motor_temperature_counter 10, four uint8 12..15, esc[k] at 16 + 40·k
    # (each report 39 bytes, the next one aligned to its uint64 timestamp), the last ending at 335
    "EscStatus": 335,
    # timestamp 0, id 8, connected 9, voltage_v 12 … temperature 40, priority 44, interface_error
    # 46, voltage_cell_v 48..103, max_cell_voltage_delta 104, is_powering_off 108, is_required 109,
    # warning 110, faults 112, six floats 116..139, cell_count 140, source 141, capacity 142,
    # cycle_count 144, average_time_to_empty 146, serial_number 148..179, manufacture_date 180,
    # state_of_health 182, max_error 184, three floats 188..199, over_discharge_count 200,
    # nominal_voltage 204, internal_resistance_estimate 208
    "BatteryStatus": 212,
}


def msg_fields(path):
    fields = []
    for line in path.read_text().splitlines():
        line = line.split("#", 1)[0].strip()
        if not line or "=" in line:
            continue
        typ, name = line.split()
        m = re.fullmatch(r"([A-Za-z0-9_]+)(?:\[(\d+)\])?", typ)
        base, n = m.group(1), int(m.group(2)) if m.group(2) else 1
        idl = MSG_TO_IDL.get(base, f"px4_msgs::msg::dds_::{base}_")
        fields.append((name, idl, n))
    return fields


def idl_fields(path):
    text = re.sub(r"//[^\n]*", "", path.read_text())
    body = re.search(r"struct\s+\w+\s*\{(.*?)\};", text, re.S).group(1)
    fields = []
    for decl in body.split(";"):
        decl = decl.strip()
        if not decl:
            continue
        m = re.fullmatch(r"([\w:]+)\s+(\w+)(?:\[(\d+)\])?", decl)
        assert m, f"{path}: cannot read the declaration '{decl}'"
        fields.append((m.group(2), m.group(1), int(m.group(3)) if m.group(3) else 1))
    return fields


def layout(fields, resolve, offset=0):
    """XCDR1 offsets of the fields from `offset`; returns [(name, offset)], end."""
    out = []
    for name, typ, n in fields:
        for k in range(n):
            if typ in PRIMITIVE:
                size = PRIMITIVE[typ]
                offset = (offset + size - 1) // size * size
                if k == 0:
                    out.append((name, offset))
                offset += size
            else:
                inner, offset = layout(resolve(typ), resolve, offset)
                if k == 0:
                    out.append((name, inner[0][1]))
    return out, offset


def main():
    src = Path(sys.argv[1])
    idl_dir, msg_dir = src / "idl/px4_msgs/msg", src / "tests/fixtures/px4_msg"
    failures = []

    def resolve_msg(typ):
        return msg_fields(msg_dir / (typ.split("::")[-1][:-1] + ".msg"))

    def resolve_idl(typ):
        return idl_fields(idl_dir / (typ.split("::")[-1][:-1] + ".idl"))

    names = sorted(p.stem for p in idl_dir.glob("*.idl"))
    assert sorted(PINNED) == names, f"types {names} against pinned {sorted(PINNED)}"
    for name in names:
        mf, idf = msg_fields(msg_dir / f"{name}.msg"), idl_fields(idl_dir / f"{name}.idl")
        if mf != idf:
            for i, (a, b) in enumerate(zip(mf + [None] * len(idf), idf + [None] * len(mf))):
                if a != b:
                    failures.append(f"{name}: field {i}: .msg {a}, IDL {b}")
                    break
            continue
        (mo, mend), (io, iend) = layout(mf, resolve_msg), layout(idf, resolve_idl)
        if mo != io or mend != iend:
            failures.append(f"{name}: CDR offsets differ: .msg {mo} ({mend} B), IDL {io} ({iend} B)")
        if iend != PINNED[name]:
            failures.append(f"{name}: {iend} bytes, pinned {PINNED[name]}")
        print(f"{name}: {len(idf)} fields, XCDR1 payload {iend} bytes, offsets "
              + ", ".join(f"{n} {o}" for n, o in io))
    if failures:
        print("\n".join(failures))
        sys.exit(1)


if __name__ == "__main__":
    main()
