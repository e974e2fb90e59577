# SPDX-License-Identifier: MIT
# Load on the emulated controller board (docs/targets.md, "Load test"): 6 joints at 1 kHz for 60 s on
# vcan0. The drivers are three jacobid sim-can processes, each the 2R robot on two MIT motor ids (1-2,
# 3-4, 5-6): 6000 frames/s into one jacobid-fw with a 6-joint config, streaming to jacobid record.
# Gated: the stream is complete (record: 0 datagrams lost/late/malformed), every frame sent was decoded
# (none rejected, no receive overflow), every process exits 0, one datagram per firmware cycle.
# Reported, not gated (emulated time is not real time): firmware overruns, wake-up latency, rows with a
# stale joint.
# The contact monitor is on (fw.yaml monitor:, issue 40; docs/firmware.md "Contact monitor"): a 6-joint arm's
# model (the UR5-like rows of examples/robots/ur5_like.yaml, rotor inertias, smoothed Coulomb) runs its
# momentum observer in every cycle and the stream is version 2. The drives are 2R robots, not that arm, so
# its estimate is large: action flag (nothing stops); what is loaded is the estimator's cost.
# modules: can can-raw vcan
# binaries: jacobid-vcan-link
# dynamic: jacobid jacobid-fw
# include: chain-lib.sh
# memory: 1024
# smp: 1
# qemu: -icount shift=1,sleep=off
# cmdline: preempt=full
set -u
SCENARIO=board-load
. /scenario-lib/chain-lib.sh
DURATION=60

jacobid-vcan-link add vcan0 --mtu 16 || exit 10
cat > robot.yaml <<'EOF'
model: planar2r
L1: 0.5
friction: {coulomb: smooth, alpha: 100}
EOF
# The monitor's files: the arm's description and thresholds (flagged only).
cat > arm.yaml <<'EOF'
model: mdh
gravity: [0, 0, -9.81]
joints:
  - {name: shoulder_pan,  sigma: 0, alpha: 0,                   d: 0,        theta: 0, r: 0.089159}
  - {name: shoulder_lift, sigma: 0, alpha: 1.5707963267948966,  d: 0,        theta: 0, r: 0}
  - {name: elbow,         sigma: 0, alpha: 0,                   d: -0.425,   theta: 0, r: 0}
  - {name: wrist_1,       sigma: 0, alpha: 0,                   d: -0.39225, theta: 0, r: 0.10915}
  - {name: wrist_2,       sigma: 0, alpha: 1.5707963267948966,  d: 0,        theta: 0, r: 0.09465}
  - {name: wrist_3,       sigma: 0, alpha: -1.5707963267948966, d: 0,        theta: 0, r: 0.0823}
friction: {coulomb: smooth, alpha: 100}
rotor_inertia: true
parameters: {M1: 3.7, MZ1: -0.095, ZZ1: 0.0067, M2: 8.393, MX2: -1.78, MZ2: 0.95, ZZ2: 0.51, XZ2: 0.2, M3: 2.275, MX3: -0.55, ZZ3: 0.164,
  M4: 1.219, MY4: -0.02, M5: 1.219, MY5: 0.02, M6: 0.1879, ZZ6: 0.0001, FV1: 1, FC1: 7, FV2: 1, FC2: 7, FV3: 1, FC3: 5, FV4: 0.3,
  FC4: 1.5, FV5: 0.3, FC5: 1.5, FV6: 0.3, FC6: 1.5, IA1: 0.2, IA2: 0.2, IA3: 0.1, IA4: 0.02, IA5: 0.02, IA6: 0.02}
EOF
cat > monitor.yaml <<'EOF'
estimator: {type: observer, gain: 100, velocity_window: 0.05, xi: 0}
standing_velocity: 0.02
standing_time: 0.1
joints: [{moving: 5, standing: 1}, {moving: 5, standing: 1}, {moving: 5, standing: 1}, {moving: 1, standing: 0.5}, {moving: 1, standing: 0.5}, {moving: 1, standing: 0.5}]
EOF
# joints ID...: the joint lines of a config (MIT, the chain config's ranges).
joints() {
  echo "joints:"
  for id in "$@"; do
    echo "  - {name: j$id, profile: mit, motor_id: $id, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-30, 30]}"
  done
}
# config FILE ID...: a jacobid-fw config with these joints (sim-can reads its ids and encodings from it);
# the firmware's (6 joints) with the monitor.
config() {
  f=$1; shift
  monitor=""
  [ $# -eq 6 ] && monitor="monitor: {robot: arm.yaml, thresholds: monitor.yaml, action: flag}"
  { echo "can: {interface: vcan0, sync_id: 0x080}"; echo "rate: 1000"; joints "$@"
    echo "estimator: {position_window: 0.02, velocity_window: 0.05, acceleration_window: 0.1}"
    echo "stream: {host: 127.0.0.1, port: 5005}"
    echo "realtime: {priority: 80, cpu: -1, lock_memory: true, report_period: 10}"; echo "$monitor"; } > "$f"
}
config fw.yaml 1 2 3 4 5 6
config drives12.yaml 1 2
config drives34.yaml 3 4
config drives56.yaml 5 6

start_record 5005 all.csv record.json || exit 11
start_firmware fw.yaml || exit 12
say "record + jacobid-fw (6 joints) up at $(elapsed) s; 3 x sim-can (2 joints each), $DURATION s at 1 kHz"
s0=$(uptime_s)
pids=""
# --substeps 1: the drivers integrate their robot with one RK4 step per sample instead of five. What is loaded
# here is jacobid-fw (its frames, decoding, estimator and stream), not the drivers' simulation, whose fidelity no
# gate reads; at five substeps the three simulations took three quarters of the emulated CPU (19 of 25 s per
# 30 s of guest time), stretching the test's emulation time without loading the firmware more.
for d in 12 34 56; do
  jacobid sim-can --robot robot.yaml --config drives$d.yaml --iface vcan0 --duration $DURATION --seed $d --substeps 1 2> sim$d.err &
  pids="$pids $!"
done
# Guest CPU half-way: how loaded the emulated 500 MIPS board is, and by whom (the processes' user + system
# time; softirq work for other tasks is not in it). /proc/stat's totals are not usable under -icount here.
sleep $((DURATION / 2))
cpus="$(cpu_s $fw) $(cpu_s $rec) $(for p in $pids; do printf '%s ' "$(cpu_s $p)"; done)"
say "guest CPU after $(since "$s0") s: jacobid-fw, record, 3 x sim-can: $cpus s; together $(echo $cpus | awk '{ for (i = 1; i <= NF; i++) t += $i; printf "%.1f", t }') s"
sim_rc=0
for p in $pids; do wait $p || sim_rc=$?; done
say "sim-can x 3 done: $DURATION s of guest time in $(since "$s0") s of guest uptime"
cat sim12.err sim34.err sim56.err
stop_chain

run_rows all.csv run.csv
rows=$(($(wc -l < run.csv) - 1))
cycles=$(sed -n 's/.*: cycles \([0-9]*\), datagrams \([0-9]*\) (publish failures \([0-9]*\)).*/\1 \2 \3/p' fw.out)
say "inside the run: $rows rows, $(holes run.csv) with a stale or undecodable joint (reported), $(fw_overruns fw.out) firmware overrun(s) (reported)"
say "jitter: $(grep "overruns)" fw.out | tail -1 | sed 's/^jacobid-fw: //')"
say "$(grep "jacobid-fw: monitor:" fw.out | tail -1 | sed 's/^jacobid-fw: //') (the drives are 2R robots, not the monitor's arm)"

verdict=0
[ "$sim_rc" -eq 0 ] && [ "$fw_rc" -eq 0 ] && [ "$rec_rc" -eq 0 ] || { say "a process failed (sim-can $sim_rc, jacobid-fw $fw_rc, record $rec_rc)"; verdict=1; }
gate_can "sim12.err sim34.err sim56.err" fw.out || verdict=1
gate_stream record.json || verdict=1
# The monitor ran in the stream: version 2 with its tau_ext columns.
grep -q '"version": *2' record.json && head -1 all.csv | grep -q ',tau_ext6_hat' || { say "the stream is not the monitor's version 2"; verdict=1; }
# One datagram per cycle once the estimator's delay line is full (its first `delay` cycles publish nothing).
delay=$(sed -n 's/.*estimates delayed \([0-9]*\) samples.*/\1/p' fw.out)
set -- $cycles
[ $# -eq 3 ] && [ -n "$delay" ] && [ $(($1 - delay)) = "$2" ] && [ "$3" = 0 ] && [ "$2" = "$(num received record.json)" ] ||
  { say "cycles/datagrams/publish failures '$cycles' (delay '$delay'), record received $(num received record.json)"; verdict=1; }
# Missed periods are samples the firmware skipped (sample-index jumps, reported): rows + them cover the run.
[ $((rows + $(fw_overruns fw.out))) -ge $((DURATION * 1000 - 10)) ] || { say "only $rows rows for $DURATION s at 1 kHz"; verdict=1; }
say "done at $(elapsed) s"
exit $verdict
