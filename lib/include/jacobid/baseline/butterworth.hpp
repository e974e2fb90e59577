// SPDX-License-Identifier: MIT
#pragma once
// Digital low-pass IIR design, section for section as scipy.signal.butter / scipy.signal.cheby1 with
// output='sos' (scipy 1.10): analog prototype with cutoff 1 rad/s, prewarped cutoff, bilinear transform,
// then zpk2sos with scipy's default 'nearest' pole/zero pairing and section order. Butterworth is the
// paper's baseline pre-filter; Chebyshev I (cheby1(8, 0.05, 0.8/q)) is the low-pass scipy.signal.decimate
// uses. Both prototypes have no finite zeros, so every digital zero is real (-1, plus the 0 scipy adds for
// odd orders); the pairing below reproduces scipy's algorithm for exactly that case.
#include <array>
#include <cmath>
#include <complex>
#include <cstddef>

#include "jacobid/baseline/filter_status.hpp"
#include "jacobid/baseline/sos.hpp"

namespace jacobid {
namespace lowpass_design_detail {

using Complex = std::complex<double>;
constexpr double kPi = 3.141592653589793238462643383279502884;
// scipy's _cplxreal treats a number as real when |imag| <= 100 * eps * |z|.
constexpr double kRealTolerance = 100.0 * 2.220446049250313080847263336181640625e-16;

// Analog low-pass prototype (cutoff 1 rad/s) without finite zeros: poles in scipy's order, index
// m = -N+1, -N+3, ..., N-1 (m < 0 is the member of a conjugate pair with positive imaginary part).
template <std::size_t MaxSections>
struct AnalogPrototype {
    std::array<Complex, 2 * MaxSections> poles{};
    std::size_t order = 0;
    double gain = 1.0;
};

// Angle pi m / (2N) of the prototype's pole with index m (scipy: theta = pi * m / (2 * N)).
inline double prototype_pole_angle(std::size_t pole_index, std::size_t order) noexcept {
    const double m = static_cast<double>(2 * pole_index + 1) - static_cast<double>(order);
    return kPi * m / static_cast<double>(2 * order);
}

// scipy.signal.buttap: poles -exp(j pi m / (2N)) on the unit circle, gain 1.
template <std::size_t MaxSections>
AnalogPrototype<MaxSections> butterworth_prototype(std::size_t order) noexcept {
    AnalogPrototype<MaxSections> prototype;
    prototype.order = order;
    for (std::size_t i = 0; i < order; ++i) {
        const double angle = prototype_pole_angle(i, order);
        prototype.poles[i] = Complex(-std::cos(angle), -std::sin(angle));
    }
    return prototype;
}

// scipy.signal.cheb1ap: poles -sinh(mu + j theta) on an ellipse; the gain makes the DC gain 1 for odd
// orders and 10^(-rp/20) (the bottom of the ripple band) for even orders.
template <std::size_t MaxSections>
AnalogPrototype<MaxSections> chebyshev1_prototype(std::size_t order, double ripple_db) noexcept {
    AnalogPrototype<MaxSections> prototype;
    prototype.order = order;
    const double epsilon = std::sqrt(std::pow(10.0, 0.1 * ripple_db) - 1.0);
    const double mu = 1.0 / static_cast<double>(order) * std::asinh(1.0 / epsilon);
    Complex product_of_negated_poles(1.0, 0.0);
    for (std::size_t i = 0; i < order; ++i) {
        prototype.poles[i] = -std::sinh(Complex(mu, prototype_pole_angle(i, order)));
        product_of_negated_poles *= -prototype.poles[i];
    }
    prototype.gain = product_of_negated_poles.real();
    if (order % 2 == 0) prototype.gain /= std::sqrt(1.0 + epsilon * epsilon);
    return prototype;
}

// One entry of scipy's pole list after _cplxreal: a complex pole stands for its conjugate pair.
// Entries are flagged when paired instead of deleted: the others keep their order, as with np.delete.
struct DigitalPole {
    Complex value;
    bool is_real = false;
    bool paired = false;
};

struct DigitalZero {
    double value = 0.0;
    bool paired = false;
};

// The order of scipy's _cplxreal output: complex poles by real part, then |imag|; then real poles
// ascending. It only decides ties below, but ties are resolved by this order in scipy.
inline bool precedes_in_scipy_order(const DigitalPole& a, const DigitalPole& b) noexcept {
    if (a.is_real != b.is_real) return !a.is_real;
    if (a.value.real() != b.value.real()) return a.value.real() < b.value.real();
    return std::abs(a.value.imag()) < std::abs(b.value.imag());
}

// scipy's idx_worst for digital filters: the unpaired pole closest to the unit circle, the first one on
// ties; marks it paired. A real pole is only asked for when one is left (real poles come in twos once
// the padding pole is added); otherwise the origin is returned.
template <std::size_t N>
DigitalPole pair_pole_closest_to_unit_circle(std::array<DigitalPole, N>& poles, bool real_only) noexcept {
    DigitalPole* best = nullptr;
    double best_distance = 0.0;
    for (DigitalPole& pole : poles) {
        if (pole.paired || (real_only && !pole.is_real)) continue;
        const double distance = std::abs(1.0 - std::abs(pole.value));
        if (best == nullptr || distance < best_distance) {
            best = &pole;
            best_distance = distance;
        }
    }
    if (best == nullptr) return DigitalPole{Complex(0.0, 0.0), true, true};
    best->paired = true;
    return *best;
}

// scipy's _nearest_real_complex_idx over real zeros: the unpaired zero closest to the pole, the first
// one on ties; marks it paired. There are as many zeros as poles, so one is always left.
template <std::size_t N>
double pair_zero_nearest(std::array<DigitalZero, N>& zeros, Complex pole) noexcept {
    DigitalZero* best = nullptr;
    double best_distance = 0.0;
    for (DigitalZero& zero : zeros) {
        if (zero.paired) continue;
        const double distance = std::abs(Complex(zero.value - pole.real(), -pole.imag()));
        if (best == nullptr || distance < best_distance) {
            best = &zero;
            best_distance = distance;
        }
    }
    if (best == nullptr) return 0.0;
    best->paired = true;
    return best->value;
}

// Prototype -> digital low-pass SOS: lp2lp_zpk to the prewarped cutoff, bilinear_zpk, zpk2sos.
// normalized_cutoff is scipy's Wn in (0, 1), 1 = Nyquist; the caller has validated it and the capacity.
template <std::size_t MaxSections>
void design_lowpass_sos(const AnalogPrototype<MaxSections>& prototype, double normalized_cutoff,
                        SosCascade<MaxSections>& sos) noexcept {
    const std::size_t order = prototype.order;
    // scipy designs on fs = 2: warped = 2 fs tan(pi Wn / fs), and the bilinear transform uses 2 fs.
    const double warped = 4.0 * std::tan(kPi * normalized_cutoff / 2.0);
    constexpr double kTwiceFs = 4.0;

    // Room for N/2 complex pairs plus the real pole and the padding pole of an odd order; unused
    // entries are marked paired so that the pairing never sees them.
    std::array<DigitalPole, MaxSections + 1> poles{};
    for (DigitalPole& pole : poles) pole.paired = true;
    std::size_t pole_count = 0;
    Complex denominator_product(1.0, 0.0);
    for (std::size_t i = 0; i < order; ++i) {
        const Complex analog = prototype.poles[i] * warped;
        denominator_product *= kTwiceFs - analog;
        const Complex digital = (kTwiceFs + analog) / (kTwiceFs - analog);
        if (std::abs(digital.imag()) <= kRealTolerance * std::abs(digital)) {
            poles[pole_count++] = {Complex(digital.real(), 0.0), true, false};
        } else if (digital.imag() > 0.0) {
            // Conjugate prototype poles are exact mirror images (cos, sin and the transform are
            // symmetric), so scipy's averaging of a pair changes nothing: keep the upper one.
            poles[pole_count++] = {digital, false, false};
        }
    }
    // The analog zeros at infinity all map to z = -1; the gain compensates for the moved poles.
    const double gain = prototype.gain * std::pow(warped, static_cast<double>(order)) *
                        (Complex(1.0, 0.0) / denominator_product).real();

    // Zeros in scipy's (ascending) order; unused entries marked paired.
    std::array<DigitalZero, 2 * MaxSections> zeros{};
    for (std::size_t i = 0; i < zeros.size(); ++i) zeros[i] = {-1.0, i >= order};
    if (order % 2 == 1) {
        // scipy's 'nearest' pairing adds a pole and a zero at the origin so every section is second order.
        poles[pole_count++] = {Complex(0.0, 0.0), true, false};
        zeros[order] = {0.0, false};
    }
    for (std::size_t i = 1; i < pole_count; ++i) {  // stable insertion sort into scipy's order
        const DigitalPole moving = poles[i];
        std::size_t j = i;
        for (; j > 0 && precedes_in_scipy_order(moving, poles[j - 1]); --j) poles[j] = poles[j - 1];
        poles[j] = moving;
    }

    // Sections are built from the last to the first, so the poles closest to the unit circle (the most
    // resonant) end up in the last sections, each paired with the zeros nearest to it.
    const std::size_t section_count = (order + 1) / 2;
    for (std::size_t si = section_count; si-- > 0;) {
        const DigitalPole p1 = pair_pole_closest_to_unit_circle(poles, false);
        double a1 = 0.0;
        double a2 = 0.0;
        if (p1.is_real) {
            const DigitalPole p2 = pair_pole_closest_to_unit_circle(poles, true);
            a1 = -(p1.value.real() + p2.value.real());
            a2 = p1.value.real() * p2.value.real();
        } else {
            const double re = p1.value.real();
            const double im = p1.value.imag();
            a1 = -2.0 * re;
            a2 = re * re + im * im;
        }
        const double z1 = pair_zero_nearest(zeros, p1.value);
        const double z2 = pair_zero_nearest(zeros, p1.value);
        sos.sections[si] = {1.0, -(z1 + z2), z1 * z2, 1.0, a1, a2};
    }
    for (std::size_t j = 0; j < 3; ++j) sos.sections[0][j] *= gain;  // scipy puts the gain in section 0
    sos.count = section_count;
}

// Checks shared by the designs; on success normalized_cutoff holds scipy's Wn = 2 cutoff / fs.
template <std::size_t MaxSections>
FilterStatus check_lowpass_request(int order, double cutoff_hz, double sample_rate_hz,
                                   double& normalized_cutoff) noexcept {
    if (order < 1) return FilterStatus::InvalidOrder;
    if ((static_cast<std::size_t>(order) + 1) / 2 > MaxSections) return FilterStatus::CapacityExceeded;
    if (!(sample_rate_hz > 0.0) || !std::isfinite(sample_rate_hz)) return FilterStatus::InvalidSampling;
    normalized_cutoff = 2.0 * cutoff_hz / sample_rate_hz;
    if (!(normalized_cutoff > 0.0 && normalized_cutoff < 1.0)) return FilterStatus::InvalidCutoff;
    return FilterStatus::Ok;
}

}  // namespace lowpass_design_detail

// Order-`order` Butterworth low-pass, -3 dB at cutoff_hz, as
// scipy.signal.butter(order, cutoff_hz, fs=sample_rate_hz, output='sos'). Needs (order + 1) / 2 sections.
// Errors: InvalidOrder, CapacityExceeded, InvalidSampling, InvalidCutoff (cutoff not in (0, fs/2));
// `sos` is left unchanged on error.
template <std::size_t MaxSections>
FilterStatus butterworth_lowpass(int order, double cutoff_hz, double sample_rate_hz,
                                 SosCascade<MaxSections>& sos) noexcept {
    double normalized_cutoff = 0.0;
    const FilterStatus status =
        lowpass_design_detail::check_lowpass_request<MaxSections>(order, cutoff_hz, sample_rate_hz, normalized_cutoff);
    if (status != FilterStatus::Ok) return status;
    lowpass_design_detail::design_lowpass_sos(
        lowpass_design_detail::butterworth_prototype<MaxSections>(static_cast<std::size_t>(order)), normalized_cutoff,
        sos);
    return FilterStatus::Ok;
}

// Order-`order` Chebyshev type I low-pass with ripple_db of pass-band ripple, whose gain first drops
// below -ripple_db at cutoff_hz, as scipy.signal.cheby1(order, ripple_db, cutoff_hz, fs=sample_rate_hz,
// output='sos'). scipy's normalized form cheby1(N, rp, Wn) is sample_rate_hz = 2, cutoff_hz = Wn.
// Errors: those of butterworth_lowpass, then InvalidRipple; `sos` is left unchanged on error.
template <std::size_t MaxSections>
FilterStatus chebyshev1_lowpass(int order, double ripple_db, double cutoff_hz, double sample_rate_hz,
                                SosCascade<MaxSections>& sos) noexcept {
    double normalized_cutoff = 0.0;
    const FilterStatus status =
        lowpass_design_detail::check_lowpass_request<MaxSections>(order, cutoff_hz, sample_rate_hz, normalized_cutoff);
    if (status != FilterStatus::Ok) return status;
    if (!(ripple_db > 0.0) || !std::isfinite(ripple_db)) return FilterStatus::InvalidRipple;
    lowpass_design_detail::design_lowpass_sos(
        lowpass_design_detail::chebyshev1_prototype<MaxSections>(static_cast<std::size_t>(order), ripple_db),
        normalized_cutoff, sos);
    return FilterStatus::Ok;
}

}  // namespace jacobid
