// SPDX-License-Identifier: MIT
#include "signal/fft_convolver.hpp"

#include "signal/fftw_planner.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cstring>
#include <mutex>
#include <new>

namespace jacobid::signal {
namespace {

template <typename T>
struct FftwBuffer {
    T* data = nullptr;
    explicit FftwBuffer(std::size_t count) : data(static_cast<T*>(fftw_malloc(sizeof(T) * count))) {
        if (data == nullptr) throw std::bad_alloc();
    }
    ~FftwBuffer() { fftw_free(data); }
    FftwBuffer(const FftwBuffer&) = delete;
    FftwBuffer& operator=(const FftwBuffer&) = delete;
};

}  // namespace

struct FftConvolver::Impl {
    std::size_t taps = 0;
    std::size_t n = 0;  // FFT size
    fftw_plan forward = nullptr;
    fftw_plan backward = nullptr;
    fftw_complex* spectrum = nullptr;  // FFT of the reversed, zero-padded kernel, divided by n

    ~Impl() {
        const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
        if (forward != nullptr) fftw_destroy_plan(forward);
        if (backward != nullptr) fftw_destroy_plan(backward);
        fftw_free(spectrum);
    }
};

std::size_t FftConvolver::default_fft_size(std::size_t taps) noexcept {
    // n >= 8 taps / sqrt(2)  <=>  n^2 >= 32 taps^2
    std::size_t n = 64;
    while (n * n < 32 * taps * taps) n *= 2;
    return n;
}

FftConvolver::FftConvolver(Span<const double> weights, std::size_t fft_size, FftPlanning planning)
    : impl_(std::make_unique<Impl>()) {
    Impl& p = *impl_;
    p.taps = weights.size();
    if (p.taps == 0) return;
    p.n = (fft_size < p.taps) ? default_fft_size(p.taps) : fft_size;
    const std::size_t bins = p.n / 2 + 1;
    const int n = static_cast<int>(p.n);

    FftwBuffer<double> real(p.n);
    p.spectrum = static_cast<fftw_complex*>(fftw_malloc(sizeof(fftw_complex) * bins));
    if (p.spectrum == nullptr) throw std::bad_alloc();
    {
        const unsigned flags = planning == FftPlanning::Measure ? FFTW_MEASURE : FFTW_ESTIMATE;
        const std::lock_guard<std::mutex> lock(fftw_planner_mutex());
        // Planned on fftw_malloc'ed arrays: correlate() runs the plans on other arrays from fftw_malloc,
        // which have the same (SIMD) alignment, as fftw_execute_dft_* requires.
        p.forward = fftw_plan_dft_r2c_1d(n, real.data, p.spectrum, flags);
        p.backward = fftw_plan_dft_c2r_1d(n, p.spectrum, real.data, flags);
    }
    if (p.forward == nullptr || p.backward == nullptr) throw std::bad_alloc();

    // Spectrum of h[m] = w[L-1-m] (correlation as convolution), with the 1/n of the inverse folded in.
    const double scale = 1.0 / static_cast<double>(p.n);
    std::fill(real.data, real.data + p.n, 0.0);
    for (std::size_t m = 0; m < p.taps; ++m) real.data[m] = weights[p.taps - 1 - m] * scale;
    fftw_execute_dft_r2c(p.forward, real.data, p.spectrum);
}

FftConvolver::~FftConvolver() = default;
FftConvolver::FftConvolver(FftConvolver&&) noexcept = default;
FftConvolver& FftConvolver::operator=(FftConvolver&&) noexcept = default;

std::size_t FftConvolver::taps() const noexcept { return impl_ ? impl_->taps : 0; }
std::size_t FftConvolver::fft_size() const noexcept { return impl_ ? impl_->n : 0; }
std::size_t FftConvolver::block_outputs() const noexcept { return taps() == 0 ? 0 : impl_->n - impl_->taps + 1; }

BatchStatus FftConvolver::correlate(Span<const double> x, Span<double> y) const {
    const std::size_t taps = this->taps();
    if (taps == 0) return BatchStatus::EmptyKernel;
    if (x.size() < taps) return BatchStatus::SignalShorterThanWindow;
    const std::size_t outputs = batch_output_size(x.size(), taps);
    if (y.size() < outputs) return BatchStatus::OutputTooSmall;

    const Impl& p = *impl_;
    const std::size_t n = p.n;
    const std::size_t bins = n / 2 + 1;
    const std::size_t step = n - taps + 1;
    // Per-call scratch: correlate() stays const and safe to call from several threads.
    FftwBuffer<double> real(n);
    FftwBuffer<fftw_complex> freq(bins);
    const double* h = &p.spectrum[0][0];
    double* f = &freq.data[0][0];

    for (std::size_t s = 0; s < outputs; s += step) {
        // Input block x[s .. s+n), zero-padded past the end of the record.
        const std::size_t available = std::min(n, x.size() - s);
        std::memcpy(real.data, x.data() + s, available * sizeof(double));
        if (available < n) std::fill(real.data + available, real.data + n, 0.0);
        fftw_execute_dft_r2c(p.forward, real.data, freq.data);
        for (std::size_t b = 0; b < bins; ++b) {
            const double re = f[2 * b] * h[2 * b] - f[2 * b + 1] * h[2 * b + 1];
            const double im = f[2 * b] * h[2 * b + 1] + f[2 * b + 1] * h[2 * b];
            f[2 * b] = re;
            f[2 * b + 1] = im;
        }
        fftw_execute_dft_c2r(p.backward, freq.data, real.data);  // destroys freq, which is scratch
        // Circular outputs taps-1 .. n-1 have no wrap-around: they are y[s .. s+step).
        const std::size_t count = std::min(step, outputs - s);
        std::memcpy(y.data() + s, real.data + (taps - 1), count * sizeof(double));
    }
    return BatchStatus::Ok;
}

BatchStatus differentiate_batch(Span<const double> weights, Span<const double> x, Span<double> y) {
    const std::size_t taps = weights.size();
    const std::size_t outputs = batch_output_size(x.size(), taps);
    if (taps < kFftCrossoverTaps || outputs * taps < kFftMinimumWork) return differentiate_direct(weights, x, y);
    // Errors are reported before any planning.
    if (y.size() < outputs) return BatchStatus::OutputTooSmall;
    // A record shorter than the default block needs no larger transform than the record itself.
    std::size_t record_block = 1;
    while (record_block < x.size()) record_block *= 2;
    return FftConvolver(weights, std::min(FftConvolver::default_fft_size(taps), record_block)).correlate(x, y);
}

}  // namespace jacobid::signal
