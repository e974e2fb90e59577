# SPDX-License-Identifier: MIT
# The full acquisition chain in the x86_64 VM (docs/targets.md, "Full chain on the x86_64 VM"): jacobid
# sim-can plays the 2R robot's MIT drivers on vcan0 (20 s at 1 kHz), jacobid-fw reads vcan0 and streams
# estimate datagrams over UDP on the loopback, jacobid record writes the CSV, jacobid identify compares with
# the Table II truth. jacobid and jacobid-fw are build-vm's dynamically linked executables (`# dynamic:`).
# Gated (chain-lib.sh gate_chain): every frame decoded, 0 datagrams lost/late/malformed, the processes' exit
# codes, a log covering the run without overruns, the identification bars (holes reported). The aarch64 board (board.sh) runs the same
# chain with the GPIO lines on top.
# -icount shift=1,sleep=off: the guest's clock follows its executed instructions, idle time included, so
# the host's load cannot delay a guest timer; preempt=full: the SCHED_FIFO firmware preempts the other
# processes' kernel work (Debian's default is voluntary).
# modules: can can-raw vcan
# binaries: jacobid-vcan-link
# dynamic: jacobid jacobid-fw
# include: chain-lib.sh
# memory: 1024
# smp: 1
# qemu: -icount shift=1,sleep=off
# cmdline: preempt=full
set -u
SCENARIO=chain
. /scenario-lib/chain-lib.sh
DURATION=20

jacobid-vcan-link add vcan0 --mtu 16 || exit 10
chain_configs
run_chain $DURATION
gate_chain $DURATION; verdict=$?
say "done at $(elapsed) s"
exit $verdict
