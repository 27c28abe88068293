#pragma once
// The star's fields for the output plugins in HydroBase's names (rho, press, eps, vel[i], w_lorentz).
#include <memory>

#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "fluid.hpp"

namespace bhnsid::star {

std::shared_ptr<FieldExport> matter_export(Grid& grid, const Eos& eos, const StarFluid& fluid);

}  // namespace bhnsid::star
