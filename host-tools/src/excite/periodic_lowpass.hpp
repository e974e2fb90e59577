// SPDX-License-Identifier: MIT
#pragma once
// identify's decimation filter F_p as the excitation optimizer can see it (docs/excite.md, "The criterion and
// the limits", `--decimation-cutoff`): identify filters both sides of its equations with a Butterworth of order
// `order` run forward and backward (filtfilt: zero phase, amplitude gain g(f) = |H(f)|^2 = 1 / (1 + (f / fc)^(2
// order))), and the design is periodic: on N samples of one period T
// that filter is the symmetric circulant matrix F with F_ab = (1 / N) sum_k g(k / T) cos(2 pi k (a - b) / N), k
// over the N frequencies of the discrete Fourier transform (|k| <= N / 2). F W filters each regressor column along
// time as identify's F_p does once the periods play back to back (the ends of a log aside).
#include <Eigen/Core>

namespace jacobid::excite {

// F above (samples x samples). std::invalid_argument for samples < 2, period <= 0, cutoff_hz <= 0 or order < 1.
Eigen::MatrixXd periodic_lowpass(int samples, double period, double cutoff_hz, int order = 4);

}  // namespace jacobid::excite
