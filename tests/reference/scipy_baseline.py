#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""scipy reference values for the Butterworth + Euler baseline of the real-time core.

The C++ tests (tests/unit/test_butterworth.cpp, test_filtfilt.cpp, test_decimate.cpp) run this script
with Debian's /usr/bin/python3 (python3-scipy) and compare the core against what it prints. Output: one
array per line, "<name> <v0> <v1> ...", every number with %.17g so that doubles round-trip exactly.

Commands (frequencies in Hz unless noted):
  butter ORDERS CUTOFF FS                 sos_<N> = butter(N, CUTOFF, fs=FS, output='sos'), N in ORDERS
  cheby1 ORDERS RP WN                     sos_<N> = cheby1(N, RP, WN, output='sos') (WN normalized, 1 = Nyquist)
  filter ORDER CUTOFF FS LENGTH SEED      sos = butter(...), x = test signal, sosfilt, zi, sosfiltfilt
  filtfilt_accepts ORDER CUTOFF FS LENGTHS
                                          accepted: 1 where sosfiltfilt(butter(...), x) accepts len(x), 0 where
                                          it raises ValueError (x shorter than or equal to padlen)
  decimate Q LENGTH SEED                  x, sos = the default cheby1 low-pass, y = decimate(x, Q)
  decimate_butter Q ORDER CUTOFF FS LENGTH SEED
                                          x, sos = butter(...), y = decimate(x, Q, ftype=dlti(butter zpk))
ORDERS and LENGTHS are comma-separated lists.
"""
import sys

import numpy as np
from scipy import signal

SIGNAL_SAMPLE_RATE_HZ = 1000.0


def emit(name, values):
    values = np.atleast_1d(np.asarray(values, dtype=float)).ravel()
    print(name, " ".join("%.17g" % v for v in values))


def int_list(text):
    return [int(item) for item in text.split(",")]


def test_signal(length, seed):
    """The paper's section III test motion and noise (1 kHz), plus an offset and a slope so that both ends
    of the signal are far from zero and the edge handling of the filters matters."""
    t = np.arange(length) / SIGNAL_SAMPLE_RATE_HZ
    rng = np.random.default_rng(seed)
    motion = np.sin(2 * np.pi * 4 * t) + np.sin(2 * np.pi * 9 * t) + np.sin(2 * np.pi * 15 * t)
    noise = (0.2 * rng.standard_normal(length) + 0.2 * np.sin(2 * np.pi * 200 * t)
             + 0.2 * rng.poisson(0.1, length))
    return 0.7 + 0.3 * t + motion + noise


def command_butter(orders, cutoff, fs):
    for order in int_list(orders):
        emit("sos_%d" % order, signal.butter(order, float(cutoff), fs=float(fs), output="sos"))


def command_cheby1(orders, ripple_db, normalized_cutoff):
    for order in int_list(orders):
        emit("sos_%d" % order, signal.cheby1(order, float(ripple_db), float(normalized_cutoff), output="sos"))


def command_filter(order, cutoff, fs, length, seed):
    sos = signal.butter(int(order), float(cutoff), fs=float(fs), output="sos")
    x = test_signal(int(length), int(seed))
    emit("sos", sos)
    emit("x", x)
    emit("sosfilt", signal.sosfilt(sos, x))
    emit("zi", signal.sosfilt_zi(sos))
    emit("sosfiltfilt", signal.sosfiltfilt(sos, x))


def command_filtfilt_accepts(order, cutoff, fs, lengths):
    sos = signal.butter(int(order), float(cutoff), fs=float(fs), output="sos")
    accepted = []
    for length in int_list(lengths):
        try:
            signal.sosfiltfilt(sos, test_signal(length, 0))
            accepted.append(1)
        except ValueError:
            accepted.append(0)
    emit("accepted", accepted)


def command_decimate(factor, length, seed):
    q = int(factor)
    x = test_signal(int(length), int(seed))
    emit("x", x)
    # The low-pass scipy.signal.decimate designs for ftype='iir' (see its source).
    emit("sos", signal.cheby1(8, 0.05, 0.8 / q, output="sos"))
    emit("y", signal.decimate(x, q, ftype="iir", zero_phase=True))


def command_decimate_butter(factor, order, cutoff, fs, length, seed):
    x = test_signal(int(length), int(seed))
    zeros, poles, gain = signal.butter(int(order), float(cutoff), fs=float(fs), output="zpk")
    emit("x", x)
    emit("sos", signal.butter(int(order), float(cutoff), fs=float(fs), output="sos"))
    emit("y", signal.decimate(x, int(factor), ftype=signal.dlti(zeros, poles, gain), zero_phase=True))


COMMANDS = {
    "butter": command_butter,
    "cheby1": command_cheby1,
    "filter": command_filter,
    "filtfilt_accepts": command_filtfilt_accepts,
    "decimate": command_decimate,
    "decimate_butter": command_decimate_butter,
}


def main(argv):
    if len(argv) < 2 or argv[1] not in COMMANDS:
        sys.stderr.write(__doc__)
        return 2
    COMMANDS[argv[1]](*argv[2:])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
