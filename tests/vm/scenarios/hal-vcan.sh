# SPDX-License-Identifier: MIT
# SocketCAN HAL tests on vcan (tests/vm/hal/test_vcan_*.cpp) in the VM.
# modules: can can-raw vcan
# binaries: jacobid-vcan-link test_hal_vcan
set -e
jacobid-vcan-link add vcan0 --mtu 16
jacobid-vcan-link add vcan1 --mtu 72
ip -o link show type vcan 2>/dev/null || ip -o link
test_hal_vcan --gtest_color=no
