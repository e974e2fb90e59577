# SPDX-License-Identifier: MIT
# Shared by the acquisition-chain scenarios (chain.sh, board.sh, board-load.sh; `# include: chain-lib.sh`,
# sourced from /scenario-lib) and board.sh's host step (identify-on-host.sh, on the build machine): starting
# and stopping the chain's processes, reading their reports, the gates on a complete stream, and the
# identification bars. busybox sh + awk (the host step: bash + Debian's awk). Set SCENARIO first.
# run_chain + gate_chain are the whole 2R chain: sim-can -> vcan0 -> jacobid-fw -> UDP -> record -> identify.
T0=$(cut -d' ' -f1 /proc/uptime)
say() { echo "JACOBID-VM: $SCENARIO: $*"; }  # the prefix: shown by the harness under --quiet too
uptime_s() { cut -d' ' -f1 /proc/uptime; }
since() { awk -v a="$1" -v b="$(uptime_s)" 'BEGIN { printf "%.1f", b - a }'; }  # seconds since uptime $1
elapsed() { since "$T0"; }

# start_record PORT CSV SUMMARY: jacobid record in the background (pid in $rec, stderr in record.err),
# returns once it listens.
start_record() {
  jacobid record --udp "127.0.0.1:$1" -o "$2" --summary "$3" --on-gap mark --quiet 2> record.err &
  rec=$!
  i=0
  until grep -q "listening" record.err 2>/dev/null; do
    i=$((i + 1)); [ $i -le 300 ] || { cat record.err; say "record did not start"; return 1; }
    sleep 0.1
  done
}

# start_firmware CONFIG: jacobid-fw in the background (pid in $fw, output in fw.out); fails if it exits at start.
start_firmware() {
  jacobid-fw --config "$1" > fw.out 2>&1 &
  fw=$!
  sleep 1
  kill -0 $fw 2>/dev/null || { cat fw.out; say "jacobid-fw exited at start"; return 1; }
}

# cpu_s PID: user + system CPU seconds of a running process (guest time; /proc/PID/stat fields 14, 15).
cpu_s() { awk '{ sub(/^.*\) /, ""); printf "%.1f", ($12 + $13) / 100 }' "/proc/$1/stat" 2>/dev/null; }

# stop SIGNAL PID: signal a background process and return its exit status.
stop() { kill "-$1" "$2"; wait "$2"; }

# num KEY FILE: a number from a pretty-printed JSON file (one key a line), first occurrence.
num() { awk -v k="\"$1\":" '$1 == k { gsub(",", "", $2); print $2; exit }' "$2"; }

# run_rows IN OUT: the rows from the first to the last row where every joint is fresh (flags<j> bits 0-1
# clear): before the drivers' first frame and after their last one there is no measurement. Every row in
# between stays, stale or not (a stale sample holds the last value). Prints nothing.
run_rows() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^flags[0-9]+$/) f[++n] = i; print; next }
           { fresh = 1; for (j = 1; j <= n; j++) if (and($(f[j]), 3) != 0) fresh = 0 }
           fresh && !first { first = NR } first { row[NR] = $0; if (fresh) last = NR }
           END { for (i = first; i <= last; i++) print row[i] }' "$1" > "$2"
}

# holes CSV: rows where some joint has no fresh sample (stale or undecodable).
holes() {
  awk -F, 'NR == 1 { for (i = 1; i <= NF; i++) if ($i ~ /^flags[0-9]+$/) f[++n] = i; next }
           { for (j = 1; j <= n; j++) if (and($(f[j]), 3) != 0) { h++; break } } END { print h + 0 }' "$1"
}

# fw_overruns FW_OUT: missed periods in jacobid-fw's final report.
fw_overruns() { grep "overruns)" "$1" | tail -1 | sed 's/.*cycles, \([0-9]*\) overruns.*/\1/'; }

# gate_can SIM_ERRS FW_OUT: every frame the sim-can runs (their stderr files, space-separated) sent was
# decoded by jacobid-fw, none refused, rejected or lost to a receive overflow. Prints why not; status 1.
gate_can() {
  sent=$(cat $1 | sed -n 's/.*samples, \([0-9]*\) frames sent, \([0-9]*\) refused.*/\1 \2/p' |
         awk '{ s += $1; r += $2; n++ } END { print s + 0, r + 0, n + 0 }')
  frames=$(sed -n 's/.*frames \([0-9]*\) decoded \([0-9]*\), rejected: short \([0-9]*\) out-of-range \([0-9]*\) unknown-id \([0-9]*\) malformed \([0-9]*\);.*rx overflows \([0-9]*\).*/\1 \2 \3 \4 \5 \6 \7/p' "$2")
  set -- $frames
  s=$(echo $sent | awk '{ print $1 }'); r=$(echo $sent | awk '{ print $2 }')
  if [ $# -eq 7 ] && [ "$1" = "$s" ] && [ "$1" = "$2" ] && [ "$3$4$5$6$7" = 00000 ] && [ "$r" = 0 ] && [ "$s" -gt 0 ]; then
    say "CAN: $s frames sent, all decoded; 0 refused, rejected or lost to rx overflows"
    return 0
  fi
  say "CAN: sim-can sent/refused/instances '$sent', jacobid-fw frames/decoded/rejected(short,range,id,malformed)/overflows '$frames'"
  return 1
}

# gate_stream SUMMARY: every datagram arrived (record's sequence numbers: 0 lost, late, malformed).
gate_stream() {
  lost=$(num lost "$1"); late=$(num late "$1"); malformed=$(num malformed "$1"); received=$(num received "$1")
  say "record: $received datagrams, lost $lost, late $late, malformed $malformed; rows without a fresh sample (whole run): stale $(num stale "$1"), decode-error $(num decode_error "$1"); sample-index jumps $(num sample_index_jumps "$1")"
  [ "$lost" = 0 ] && [ "$late" = 0 ] && [ "$malformed" = 0 ] && [ "${received:-0}" -gt 0 ] && return 0
  say "datagrams lost/late/malformed on the loopback"
  return 1
}

# check_bars ID_JSON: the 2R identification against the Table II truth (ZZ1R, ZZ2, MX2 within 1 %,
# FC1, FC2 within 5 %, relative error norm < 2 %; tests/support/identification_bars.hpp). Status 1 if
# any bar is missed.
check_bars() {
  idj=$1 bars=0
  for spec in "ZZ1R 3.496 0.01" "ZZ2 0.059 0.01" "MX2 0.124 0.01" "FC1 0.431 0.05" "FC2 0.1268 0.05"; do
    set -- $spec
    v=$(awk -v k="\"$1\":" 'f && $1 == "\"value\":" { print $2; exit } $1 == k { f = 1 }' "$idj")
    e=$(awk -v v="$v" -v t="$2" 'BEGIN { e = (v - t) / t; if (e < 0) e = -e; printf "%.3f", 100 * e }')
    if [ -n "$v" ] && awk -v e="$e" -v tol="$3" 'BEGIN { exit !(e < 100 * tol) }'; then
      say "$1 = $v (truth $2): error $e %, ok"
    else
      say "$1 = $v (truth $2): error $e %, over the $(awk -v t="$3" 'BEGIN { print 100 * t }') % bar"; bars=1
    fi
  done
  norm=$(num relative_error_norm "$idj")
  if [ -n "$norm" ] && awk -v n="$norm" 'BEGIN { exit !(n < 0.02) }'; then say "relative error norm $norm: ok"; else say "relative error norm $norm over 0.02"; bars=1; fi
  return $bars
}

# chain_configs [YAML_LINE]: robot.yaml (the 2R robot) and fw.yaml: the MIT 2R config of
# tests/integration/firmware/firmware_test_support.hpp chain_config_yaml() on vcan0, plus YAML_LINE (e.g. a
# gpio: section). The firmware sends a CANopen SYNC every cycle and sim-can (reading the same file) answers
# each one with a sample: the drives are paced by the firmware, as synchronous TPDOs are.
chain_configs() {
  printf 'model: planar2r\nL1: 0.5\nfriction: {coulomb: smooth, alpha: 100}\n' > robot.yaml
  cat > fw.yaml <<'EOF'
can: {interface: vcan0, sync_id: 0x080}
rate: 1000
joints:
  - {name: shoulder, profile: mit, motor_id: 1, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-30, 30]}
  - {name: elbow, profile: mit, motor_id: 2, gear_ratio: 4, velocity_range: [-65, 65], effort_range: [-2, 2]}
estimator: {position_window: 0.02, velocity_window: 0.05, acceleration_window: 0.1}
stream: {host: 127.0.0.1, port: 5005}
realtime: {priority: 80, cpu: -1, lock_memory: true, report_period: 5}
EOF
  [ $# -eq 0 ] || echo "$1" >> fw.yaml
}

# stop_chain: the drivers are done; SIGTERM to jacobid-fw, SIGINT to record (fw_rc, rec_rc), their reports.
stop_chain() {
  sleep 0.5
  stop TERM $fw; fw_rc=$?
  sleep 0.5
  stop INT $rec; rec_rc=$?
  cat fw.out
  grep -v "^record: listening" record.err
}

# run_chain DURATION [HOOK]: record (one file, every row; holes counted in record.json), jacobid-fw, then
# sim-can for DURATION s of the robot at 1 kHz in the foreground (with $SIM_ARGS, e.g. --follow);
# `HOOK start` runs just before sim-can, `HOOK stop` just after it. Then SIGTERM to the firmware, SIGINT
# to the recorder. Sets sim_rc, fw_rc, rec_rc; prints the processes' reports.
run_chain() {
  start_record 5005 all.csv record.json || exit 11
  start_firmware fw.yaml || exit 12
  say "record + jacobid-fw up at $(elapsed) s; sim-can $1 s of robot at 1 kHz"
  [ $# -lt 2 ] || $2 start
  s0=$(uptime_s)
  jacobid sim-can --robot robot.yaml --config fw.yaml --iface vcan0 --duration "$1" ${SIM_ARGS:-} 2> sim.err
  sim_rc=$?
  sim_time=$(since "$s0")
  [ $# -lt 2 ] || $2 stop
  cat sim.err
  stop_chain
  say "sim-can exit $sim_rc ($1 s of robot in $sim_time s of guest time); jacobid-fw exit $fw_rc; record exit $rec_rc"
}

# export_files FILE...: the files to the build machine over the console, gzip-compressed in base64 between
# markers (tests/vm/vm_harness.py writes them beside the console log for the scenario's `# host:` step).
export_files() {
  for f in "$@"; do
    echo "JACOBID-VM-FILE-BEGIN $f"
    gzip -c "$f" | base64
    echo "JACOBID-VM-FILE-END $f"
  done
}

# identify_bars: identify log.csv (robot.yaml) with the jacobid on PATH and check the Table II bars. Status 1 if
# it fails or a bar is missed.
identify_bars() {
  i0=$(uptime_s)
  jacobid identify --robot robot.yaml --in log.csv --method jacobi --format json --quiet > id.json 2> id.err
  id_rc=$?
  say "identify exit $id_rc in $(since "$i0") s"
  cat id.err
  [ $id_rc -eq 0 ] || echo '{}' > id.json  # counts as missing every bar below
  check_bars id.json
}

# gate_chain DURATION: gate the chain and identify the run's rows. Every frame sim-can sent decoded; the
# processes' exit codes; every datagram arrived; the log covers the run and is clean (no row with a stale
# or undecodable joint, no missed period inside it: a held or missing sample costs more than the bars);
# the identification bars: here (identify_bars), or with IDENTIFY=host on the build machine, where
# robot.yaml and log.csv are exported to (the scenario's `# host:` step, identify-on-host.sh). Status 1 if
# any gate fails.
gate_chain() {
  run_rows all.csv log.csv
  rows=$(($(wc -l < log.csv) - 1))
  inside=$(holes log.csv)
  overruns=$(fw_overruns fw.out)
  say "inside the run: $rows rows, $inside without a fresh sample of both joints, $overruns firmware overrun(s)"
  ok=0
  gate_can sim.err fw.out || ok=1
  [ "$sim_rc" -eq 0 ] && [ "$fw_rc" -eq 0 ] && [ "$rec_rc" -eq 0 ] || { say "a process failed"; ok=1; }
  gate_stream record.json || ok=1
  [ "$rows" -ge $(($1 * 1000 - 10)) ] || { say "only $rows rows for $1 s at 1 kHz"; ok=1; }
  [ "$overruns" = 0 ] || { say "$overruns firmware overrun(s)"; ok=1; }
  # With SYNC pacing every answer has most of a period to arrive: a row without a fresh sample is a late
  # or lost frame, not a clock phase.
  [ "$inside" = 0 ] || { say "the log has $inside rows with a stale or undecodable joint"; ok=1; }
  if [ "${IDENTIFY:-here}" = host ]; then
    e0=$(uptime_s)
    export_files robot.yaml log.csv
    say "robot.yaml and log.csv ($(wc -c < log.csv) bytes) exported in $(since "$e0") s; identified on the build machine"
  else
    identify_bars || ok=1
  fi
  return $ok
}
