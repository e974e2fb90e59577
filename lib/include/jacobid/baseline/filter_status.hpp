// SPDX-License-Identifier: MIT
#pragma once
// Outcome of the baseline (Butterworth + Euler) functions. The core has no exceptions, so every function
// that can refuse its input returns one of these; where scipy would raise, we return the matching value.

namespace jacobid {

enum class FilterStatus {
    Ok,
    InvalidOrder,        // filter order < 1
    CapacityExceeded,    // the design needs more second-order sections than the cascade can hold
    InvalidSampling,     // sample rate / sample period not finite and > 0
    InvalidCutoff,       // cutoff not in (0, fs/2)
    InvalidRipple,       // Chebyshev pass-band ripple not finite and > 0 dB
    InvalidCascade,      // section count above capacity, or a section whose a0 is not 1
    InvalidFactor,       // decimation factor < 1
    OutputSizeMismatch,  // output span does not have the size the function documents
    SignalTooShort,      // too few samples (sosfiltfilt: not longer than padlen; differences: fewer than 3)
    WorkspaceTooSmall,   // caller-supplied workspace smaller than the documented size
};

// One line for logs and error messages.
constexpr const char* describe(FilterStatus status) noexcept {
    switch (status) {
        case FilterStatus::Ok:
            return "ok";
        case FilterStatus::InvalidOrder:
            return "invalid filter order: it must be at least 1";
        case FilterStatus::CapacityExceeded:
            return "filter order needs more second-order sections than the cascade capacity";
        case FilterStatus::InvalidSampling:
            return "invalid sampling: sample rate and sample period must be finite and greater than 0";
        case FilterStatus::InvalidCutoff:
            return "invalid cutoff: it must lie strictly between 0 and half the sample rate";
        case FilterStatus::InvalidRipple:
            return "invalid pass-band ripple: it must be finite and greater than 0 dB";
        case FilterStatus::InvalidCascade:
            return "invalid second-order-section cascade: section count above capacity or a0 != 1";
        case FilterStatus::InvalidFactor:
            return "invalid decimation factor: it must be at least 1";
        case FilterStatus::OutputSizeMismatch:
            return "output buffer size does not match the size required for this input";
        case FilterStatus::SignalTooShort:
            return "signal too short: forward-backward filtering needs more than padlen samples, "
                   "central differences at least 3";
        case FilterStatus::WorkspaceTooSmall:
            return "workspace too small: see the matching *_workspace_size() function";
    }
    return "unknown filter status value";
}

}  // namespace jacobid
