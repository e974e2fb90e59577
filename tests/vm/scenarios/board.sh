# SPDX-License-Identifier: MIT
# The emulated controller board (docs/targets.md, "Emulated controller board"): qemu -M virt (aarch64,
# TCG) with the cross-compiled jacobid-fw and jacobid-board (as `jacobid`: sim-can and record). jacobid-fw plays an excitation table on the drives
# (fw.yaml trajectory:, docs/firmware.md "Trajectory playback": a 1 s ramp, then a 6 s period of five
# harmonics 3 times), jacobid sim-can --follow plays the 2R robot's MIT drivers on vcan0 following those
# commands (20 s at 1 kHz), jacobid-fw reads vcan0, drives the enable and cycle-sync outputs of the board's
# PL061 GPIO chip through libgpiod (e-stop input on a third line) and streams estimate datagrams over UDP
# on the loopback, jacobid record writes the CSV; the board exports it and the build machine's jacobid
# identifies it against the Table II truth (identify-on-host.sh), as a user identifies a controller's log on the PC.
# Gated too: the playback finished (no stop) and the drives followed every command frame but the last.
# Gated: the chain (chain-lib.sh gate_chain: every frame decoded, 0 datagrams lost/late/malformed, no firmware
# overrun, the identification bars; rows with holes are reported) and the GPIO lines driven (enable high and sync toggling while running, as
# debugfs' gpiolib view reads them back from the chip; no e-stop event; released at exit).
# -icount shift=1,sleep=off: the guest's clock follows its executed instructions, idle time included, so
# the host's load cannot delay a guest timer.
# modules: can can-raw vcan
# binaries: jacobid-vcan-link
# dynamic: jacobid jacobid-fw
# include: chain-lib.sh
# host: identify-on-host.sh
# memory: 1024
# smp: 1
# qemu: -icount shift=1,sleep=off
# cmdline: preempt=full
set -u
SCENARIO=board
. /scenario-lib/chain-lib.sh
DURATION=20

jacobid-vcan-link add vcan0 --mtu 16 || exit 10
mount -t debugfs debugfs /sys/kernel/debug || exit 10
# The virt machine's PL061 by label (gpiochip0; line 3 is the power key). The e-stop input is active high
# here: the PL061's unconnected inputs read low, i.e. released.
chain_configs "gpio: {chip: 9030000.pl061, enable_line: 0, sync_line: 1, estop_line: 2, estop_active_low: false}"
# The table: q_j = c_j + sum_l a_jl (1 - cos(l w t)), l = 1..5, w = 2 pi / 6 s (tests/integration/firmware's
# playback loop test, there with a 10 s period), at 1 kHz. Debian's busybox awk has no math functions:
# cos and sin by their series after reduction to [-pi, pi] (terms to x^30: below 1e-12).
awk 'function cosine(x,   s, term, n) { x -= 2 * PI * int(x / (2 * PI)); if (x > PI) x -= 2 * PI; if (x < -PI) x += 2 * PI
                                        s = 1; term = 1; for (n = 1; n <= 15; n++) { term *= -x * x / ((2 * n - 1) * (2 * n)); s += term }; return s }
     function sine(x) { return cosine(x - PI / 2) }
     BEGIN { PI = 3.14159265358979323846; w = 2 * PI / 6; split("0.6 0.2 -0.25 0.1 0.08", a1, " "); split("0.5 0.4 0.3 -0.15 0.1", a2, " ")
             print "t,q1,q2,qd1,qd2"
             for (k = 0; k <= 6000; k++) {
               t = k / 1000; q1 = 0.3; q2 = -0.4; v1 = 0; v2 = 0
               for (l = 1; l <= 5; l++) { c = 1 - cosine(l * w * t); s = l * w * sine(l * w * t); q1 += a1[l] * c; q2 += a2[l] * c; v1 += a1[l] * s; v2 += a2[l] * s }
               printf "%.6f,%.9f,%.9f,%.9f,%.9f\n", t, q1, q2, v1, v2 } }' > traj.csv
cat >> fw.yaml <<'EOF'
trajectory:
  file: traj.csv
  ramp_time: 1
  repeat: 3
  joints:
    - {position: [-3, 3], velocity: 5, acceleration: 20, torque: 120, following_error: 0.2, kp: 40, kd: 1}
    - {position: [-3, 3], velocity: 5, acceleration: 20, torque: 8, following_error: 0.2, kp: 10, kd: 0.5}
EOF
SIM_ARGS=--follow
IDENTIFY=host

# The lines as gpiolib sees them (the chip's data register), every 0.25 or 0.251 s at random while sim-can runs.
# The sync line toggles every 1 ms cycle and the guest's clock is exact (-icount): at a fixed period the samples
# could all fall on the same level (a run saw "sync high 0 / low 79"); the random extra millisecond flips the
# phase by half a toggle period.
gpio_watch() {
  case "$1" in
    start) ( while :; do grep "jacobid-fw" /sys/kernel/debug/gpio; echo "--"; sleep "0.25$((RANDOM % 2))"; done ) > gpio.log 2>&1 &
           watcher=$! ;;
    stop) kill $watcher ;;
  esac
}
run_chain $DURATION gpio_watch
after=$(grep -c "jacobid-fw" /sys/kernel/debug/gpio)
gate_chain $DURATION; verdict=$?
# Playback: finished before sim-can stopped (1 + 3 x 6 s < 20 s), no stop; the drives followed every
# command frame but the last cycle's (sent after sim-can's last sample).
playback=$(grep "playback:" fw.out | tail -1 | sed 's/^jacobid-fw: //')
followed=$(sed -n 's/.*followed \([0-9]*\) command frames (\([0-9]*\) rejected).*/\1 \2/p' sim.err)
say "$playback; sim-can followed/rejected: $followed"
case "$playback" in "playback: finished"*) ;; *) say "the playback did not finish"; verdict=1 ;; esac
set -- $followed
[ $# -eq 2 ] && [ "$2" = 0 ] && [ "$1" -ge 38000 ] || { say "the drives did not follow the commands"; verdict=1; }

# Enable driven high (active high) in every sample while running, sync seen at both levels (it toggles
# every cycle), the e-stop input requested and never active, every line released at the end.
samples=$(grep -c "^--" gpio.log)
enable_hi=$(grep -c "jacobid-fw enable.* out hi" gpio.log)
sync_hi=$(grep -c "jacobid-fw sync.* out hi" gpio.log); sync_lo=$(grep -c "jacobid-fw sync.* out lo" gpio.log)
estop_in=$(grep -c "jacobid-fw estop.* in " gpio.log)
estop_events=$(sed -n 's/.*e-stop events \([0-9]*\) (rows \([0-9]*\)).*/\1 \2/p' fw.out)
grep -m 3 "jacobid-fw" gpio.log
say "GPIO ($samples samples of /sys/kernel/debug/gpio): enable high in $enable_hi, sync high $sync_hi / low $sync_lo, e-stop input requested in $estop_in; jacobid-fw e-stop events/rows '$estop_events'; lines still requested after exit: $after"
[ "$samples" -ge 10 ] && [ "$enable_hi" = "$samples" ] && [ "$sync_hi" -gt 0 ] && [ "$sync_lo" -gt 0 ] &&
  [ "$estop_in" = "$samples" ] && [ "$estop_events" = "0 0" ] && [ "$after" = 0 ] || { say "GPIO lines not driven as expected"; verdict=1; }
say "done at $(elapsed) s"
exit $verdict
