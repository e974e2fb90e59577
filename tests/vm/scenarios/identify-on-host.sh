# SPDX-License-Identifier: MIT
# board.sh's host step (`# host:`, tests/vm/vm_harness.py): on the build machine, after the emulated board
# passed, in the directory of the files it exported (robot.yaml, log.csv: the run's rows as jacobid record
# wrote them on the board). The board's jacobid (jacobid-board) has no identification: the PC's jacobid
# ($JACOBID) identifies the log and the Table II bars gate it (chain-lib.sh identify_bars), as a user would
# identify a log recorded on the controller.
set -u
SCENARIO=board-host
. "$(dirname "$0")/chain-lib.sh"
[ -f robot.yaml ] && [ -f log.csv ] || { say "robot.yaml or log.csv was not exported by the board"; exit 1; }
jacobid() { "$JACOBID" "$@"; }
identify_bars
