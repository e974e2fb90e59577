// SPDX-License-Identifier: MIT
#pragma once
// Convenience header: the whole real-time core.
#include "jacobid/batch_differentiate.hpp"
#include "jacobid/differentiator_bank.hpp"
#include "jacobid/frequency_response.hpp"
#include "jacobid/jacobi_polynomial.hpp"
#include "jacobid/kernel.hpp"
#include "jacobid/kernel_design.hpp"
#include "jacobid/kernel_params.hpp"
#include "jacobid/ring_window.hpp"
#include "jacobid/span.hpp"
