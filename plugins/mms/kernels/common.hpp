#pragma once
// What every mms kernel shares with the other equation plugins: the ghost refresh handed in by the
// caller and the compile-time variants of a sweep (core's scalar_sweep.hpp).
#include "bhnsid/interfaces/scalar_sweep.hpp"

namespace bhnsid::mms::kernels {

using stencil::Mirror;
using stencil::with_variants;

}  // namespace bhnsid::mms::kernels
