#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the seed corpora of the fuzz targets (fuzz/corpus/<target>/seed-*).

Text seeds are the examples of the tests and docs (named below); binary seeds (estimate datagrams, CAN
frames) are encoded here from the wire formats (docs/stream-format.md, the profile headers), independently
of the C++ encoders. Re-run after a format change: python3 fuzz/corpus/make_seeds.py
"""
import math
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))


def write(target, name, data):
    d = os.path.join(HERE, target)
    os.makedirs(d, exist_ok=True)
    if isinstance(data, str):
        data = data.encode()
    with open(os.path.join(d, "seed-" + name), "wb") as f:
        f.write(data)


# --- CSV logs (tests/integration/identify, tests/integration/cli: t, q1, q2, tau1, tau2 logs) ---------------
rows = ["t,q1,q2,tau1,tau2"]
for k in range(40):
    t = k * 0.001
    rows.append(f"{t:.3f},{math.sin(t):.9f},{math.cos(t):.9f},{0.5 * math.sin(3 * t):.6f},{-0.25:.2f}")
write("csv_log", "identify_log.csv", "\n".join(rows) + "\n")
write("csv_log", "crlf_spaces.csv", "t , x\r\n0, 1.5\r\n0.001 ,-2e-3\r\n0.002, 3")
write("csv_log", "single_column.csv", "time\n0\n0.5\n1\n")
write("csv_log", "nan_cell.csv", "t,q\n0,1\n0.1,nan\n")
write("csv_log", "ragged.csv", "t,q\n0,1,2\n0.1\n")

# --- candump -L logs (tests/integration/stream/test_candump_log.cpp) ---------------------------------------
write("candump_log", "formats.log",
      "(1700000000.123456) can0 123#DEADBEEF\n"
      "(1700000000.123457) can0 1ABCDEF0#0011223344556677\n"
      "(1700000000.200000) vcan1 7FF#\n"
      "(1700000001.000001) can0 321#R\r\n"
      "(1700000001.000002) can0 00000321#R4\n"
      "(1700000002.500000) can0 0C0##1000102030405060708090A0B\n"
      "(1700000002.600000) can0 456##0\n"
      "(0000000003.000000) can0 000#00 R\n"
      "(1700000004.999999) can0 1FFFFFFF#FF T\n"
      "(1700000005.000000) can0 20000080#0000000000000000\n")
write("candump_log", "nanoseconds.log", "(1.5) can0 001#\n(9223372035.999999999) can0 001#\n")


def mit_reply(motor, position, velocity, effort, temperature=65, error=0):
    """MIT-mode reply payload (mini-cheetah pack_reply layout, hal/profiles/mit.hpp)."""
    return bytes([motor, position >> 8, position & 0xFF, velocity >> 4,
                  ((velocity & 0xF) << 4) | (effort >> 8), effort & 0xFF, temperature, error])


def candump(t_us, can_id, data, extended=False):
    ident = f"{can_id:08X}" if extended else f"{can_id:03X}"
    return f"({t_us // 1000000}.{t_us % 1000000:06d}) can0 {ident}#{data.hex().upper()}\n"


# The four joints fuzz_candump_log configures: MIT motors 1 and 2 on id 0, CiA 402 node 3 (TPDO1 0x183,
# INT32 position + INT16 torque per mille), ODrive node 4 (encoder estimates 0x89, Iq 0x94, float32 LE).
log = ""
for k in range(6):
    t = 1700000000000000 + 1000 * k
    log += candump(t, 0x000, mit_reply(1, 32768 + 10 * k, 2048, 2048))
    log += candump(t + 10, 0x000, mit_reply(2, 32768 - 10 * k, 2040, 2050))
    log += candump(t + 20, 0x183, struct.pack("<ih", 1000 * k, 250))
    log += candump(t + 30, (4 << 5) | 0x09, struct.pack("<ff", 0.01 * k, 0.5))
    log += candump(t + 40, (4 << 5) | 0x14, struct.pack("<ff", 1.0, 1.25))
write("candump_log", "four_joints.log", log)

# --- Estimate datagrams (docs/stream-format.md: 48-byte header, 44 bytes per joint, little-endian) ----------
def datagram(joints, sequence, flags=0, period=0.001, index=None, joint_flags=0, count=None):
    header = b"JDST" + struct.pack("<HHIIQQqd", 1, len(joints) if count is None else count, flags, 4,
                                   sequence, sequence if index is None else index, 1000000 * sequence, period)
    body = b"".join(struct.pack("<dddddI", q, q, 0.1, -0.2, tau, joint_flags) for q, tau in joints)
    return header + body


write("estimate_datagram", "two_joints", datagram([(0.5, 1.0), (-0.25, 2.0)], 7))
write("estimate_datagram", "one_joint_restart", datagram([(0.0, 0.0)], 0, flags=2))
write("estimate_datagram", "stale_nan", datagram([(float("nan"), float("nan"))], 3, joint_flags=1))
write("estimate_datagram", "truncated", datagram([(1.0, 1.0)], 1)[:60])
write("estimate_datagram", "count_mismatch", datagram([(1.0, 1.0)], 1, count=2))

# --- Stream recorder: FuzzedDataProvider input; seeds of raw bytes still reach the decode path --------------
write("stream_recorder", "datagrams", b"".join(datagram([(0.1 * s, 1.0)], s) for s in (1, 2, 4, 3, 3, 9)))
write("stream_recorder", "zeros", bytes(64))

# --- Device profile decoders: FuzzedDataProvider input (configuration from the end, frames from the start);
# the payloads of the tests' vectors give the frame bytes realistic values. ---------------------------------
write("profile_mit", "replies", mit_reply(1, 0x8000, 0x7FF, 0x800) + mit_reply(1, 0xFFFF, 0, 0xFFF) + bytes(16))
write("profile_cia402", "tpdo", struct.pack("<ihh", -5, 1000, 0) + struct.pack("<ih", 2**31 - 1, -32768) + bytes(16))
write("profile_odrive", "floats", struct.pack("<ffff", 0.25, 1.5, 2.0, float("inf")) + bytes(16))
write("profile_generic", "fields", bytes(range(0, 64)) + bytes(16))

# --- Robot description YAML (host-tools/src/robot/robot_description.hpp example) ----------------------------
write("robot_description", "planar2r.yaml",
      "model: planar2r\n"
      "L1: 0.5\n"
      "joints:\n"
      "  - {name: shoulder, position: q1, torque: tau1, limits: [-2.5, 2.5]}\n"
      "  - {name: elbow,    position: q2, torque: tau2, limits: [-2.5, 2.5]}\n"
      "friction:\n"
      "  coulomb: smooth\n"
      "  alpha: 100\n"
      "  offset: false\n"
      "rotor_inertia: false\n"
      "parameters: {ZZ1R: 3.496, FV1: 0.1}\n")
write("robot_description", "minimal.yaml", "model: planar2r\n")
write("robot_description", "sign_friction.yaml",
      "model: planar2r\nL1: 0.3\njoints: [a, b]\nfriction: {coulomb: sign, offset: true}\nrotor_inertia: true\n")

write("robot_description", "mdh.yaml",
      "model: mdh\n"
      "gravity: [0, 0, -9.81]\n"
      "joints:\n"
      "  - {name: j1, sigma: 0, alpha: 0, d: 0, theta: 0, r: 0, antecedent: 0, limits: [-2.5, 2.5], position: q1, torque: tau1}\n"
      "  - {name: j2, sigma: 0, alpha: 1.5707963, d: 0.1, theta: 0, r: 0.3, antecedent: 1}\n"
      "  - {name: j3, sigma: 1, alpha: 0, d: 0.4, theta: 0, r: 0, antecedent: 2, limits: [0, 0.2]}\n"
      "parameters: {ZZ1: 1.2, M2: 3.0, FV1: 0.2}\n")

# --- URDF (tests/unit/robot/test_serial_descriptions.cpp, kArm) ----------------------------------------------
write("urdf", "arm.urdf", """<robot name="arm">
  <link name="base"/>
  <link name="l1"><inertial><origin xyz="0.05 0.01 0.1" rpy="0 0 0"/><mass value="3"/>
    <inertia ixx="0.02" ixy="0.001" ixz="0" iyy="0.03" iyz="0.002" izz="0.01"/></inertial></link>
  <link name="l2"><inertial><origin xyz="0.2 0 0.02" rpy="0.3 0.1 -0.2"/><mass value="2"/>
    <inertia ixx="0.004" ixy="0" ixz="0.0005" iyy="0.05" iyz="0" izz="0.05"/></inertial></link>
  <link name="tool"><inertial><origin xyz="0 0 0" rpy="0 0 0"/><mass value="0.5"/>
    <inertia ixx="0.001" ixy="0" ixz="0" iyy="0.001" iyz="0" izz="0.001"/></inertial></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/><origin xyz="0 0 0" rpy="0 0 0"/>
    <axis xyz="0 0 1"/><limit lower="-2" upper="2" effort="10" velocity="1"/><dynamics damping="0.3" friction="0.7"/></joint>
  <joint name="j2" type="continuous"><parent link="l1"/><child link="l2"/><origin xyz="0.1 0 0.3" rpy="0 0 0"/>
    <axis xyz="0 1 0"/></joint>
  <joint name="flange" type="fixed"><parent link="l2"/><child link="tool"/><origin xyz="0.4 0 0" rpy="0 0 0"/></joint>
</robot>
""")
write("urdf", "prismatic.urdf", """<robot name="p"><link name="a"/><link name="b"/>
  <joint name="slide" type="prismatic"><parent link="a"/><child link="b"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.5" effort="1" velocity="1"/></joint></robot>
""")

# --- Firmware configuration (docs/firmware.md, tests/integration/firmware/firmware_test_support.hpp) -------
write("firmware_config", "chain.yaml",
      "can: {interface: virtual}\n"
      "rate: 1000\n"
      "joints:\n"
      "  - {name: shoulder, profile: mit, motor_id: 1, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-30, 30]}\n"
      "  - {name: elbow, profile: mit, motor_id: 2, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-2, 2]}\n"
      "estimator: {position_window: 0.02, velocity_window: 0.05, acceleration_window: 0.1}\n"
      "stream: {host: 127.0.0.1, port: 5005}\n"
      "gpio: {chip: gpiochip0, estop_line: 4, enable_line: 5, sync_line: 6}\n"
      "realtime: {priority: 70, cpu: 1, report_period: 5}\n")
write("firmware_config", "profiles.yaml",
      "can: {interface: can0}\n"
      "max_age: 2\n"
      "joints:\n"
      "  - {profile: cia402, node_id: 3, effort: current, rated_current: 3, torque_constant: 0.1}\n"
      "  - {profile: odrive, node_id: 4, torque_constant: 0.1, position_wrap_turns: 1}\n"
      "estimator: {kappa: 6, mu: 6, q: 2, xi: 1, discretization: trapezoidal}\n"
      "stream: {host: 127.0.0.1, port: 5005, log: /tmp/x.bin}\n")
