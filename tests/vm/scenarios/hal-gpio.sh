# SPDX-License-Identifier: MIT
# jacobid::hal's libgpiod lines on the aarch64 virt machine's PL061 (gpiochip0).
# modules:
# binaries: test_hal_gpio_chardev
set -e
ls /dev/gpiochip*
cat /sys/bus/gpio/devices/gpiochip*/of_node/compatible 2>/dev/null | tr '\0' ' ' || true
echo
test_hal_gpio_chardev --gtest_color=no
