#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Reference reader for tests/integration/stream/test_candump_log.cpp: reads a candump -L log with
python-can's CanutilsLogReader (Debian python3-can) and prints one line per message:

  <timestamp %.17g> <timestamp in whole microseconds> <extended 0|1> <remote 0|1> <fd 0|1> <error 0|1>
  <brs 0|1> <esi 0|1> <arbitration id, hex> <dlc> <data, hex or '-'>

The microsecond count is exact for candump's 6-decimal stamps: a double near 1.7e9 s is within 0.12 us
of the printed value, so rounding to whole microseconds recovers it.
"""
import sys

import can

for msg in can.CanutilsLogReader(sys.argv[1]):
    data = bytes(msg.data).hex().upper() if msg.data else "-"
    print("%.17g %d %d %d %d %d %d %d %X %d %s" % (
        msg.timestamp, round(msg.timestamp * 1e6), msg.is_extended_id, msg.is_remote_frame, msg.is_fd,
        msg.is_error_frame, msg.bitrate_switch, msg.error_state_indicator, msg.arbitration_id, msg.dlc, data))
