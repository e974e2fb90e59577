# SPDX-License-Identifier: MIT
# The emulated controller board (docs/targets.md, "Emulated controller board"): qemu -M virt (aarch64,
# TCG) with the cross-compiled jacobid-fw and jacobid. jacobid sim-can plays the 2R robot's MIT drivers on
# vcan0 (20 s at 1 kHz), jacobid-fw reads vcan0, drives the enable and cycle-sync outputs of the board's
# PL061 GPIO chip through libgpiod (e-stop input on a third line) and streams estimate datagrams over UDP
# on the loopback, jacobid record writes the CSV, jacobid identify compares with the Table II truth.
# Gated: the chain (chain-lib.sh gate_chain: every frame decoded, 0 datagrams lost/late/malformed, no firmware
# overrun, the identification bars; rows with holes are reported) and the GPIO lines driven (enable high and sync toggling while running, as
# debugfs' gpiolib view reads them back from the chip; no e-stop event; released at exit).
# -icount shift=1,sleep=off: the guest's clock follows its executed instructions, idle time included, so
# the host's load cannot delay a guest timer.
# modules: can can-raw vcan
# binaries: jacobid-vcan-link
# dynamic: jacobid jacobid-fw
# include: chain-lib.sh
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

# The lines as gpiolib sees them (the chip's data register), every 0.25 s while sim-can runs.
gpio_watch() {
  case "$1" in
    start) ( while :; do grep "jacobid-fw" /sys/kernel/debug/gpio; echo "--"; sleep 0.25; done ) > gpio.log 2>&1 &
           watcher=$! ;;
    stop) kill $watcher ;;
  esac
}
run_chain $DURATION gpio_watch
after=$(grep -c "jacobid-fw" /sys/kernel/debug/gpio)
gate_chain $DURATION; verdict=$?

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
