// Key functions of the core-declared service interfaces: defining each destructor here anchors the
// class's type information and vtable in the core library, so that every plugin shares them.
#include "bhnsid/interfaces/elliptic.hpp"
#include "bhnsid/interfaces/eos.hpp"
#include "bhnsid/interfaces/export.hpp"
#include "bhnsid/interfaces/flow.hpp"
#include "bhnsid/interfaces/grid.hpp"
#include "bhnsid/interfaces/horizon.hpp"
#include "bhnsid/interfaces/lapse.hpp"
#include "bhnsid/interfaces/spacetime.hpp"
#include "bhnsid/interfaces/tov_family.hpp"

namespace bhnsid {

Grid::~Grid() = default;
GridLayout::~GridLayout() = default;
EllipticEquation::~EllipticEquation() = default;
Eos::~Eos() = default;
TovFamily::~TovFamily() = default;
Fluid::~Fluid() = default;
Flow::~Flow() = default;
Puncture::~Puncture() = default;
FieldExport::~FieldExport() = default;
Lapse::~Lapse() = default;
ApparentHorizon::~ApparentHorizon() = default;

}  // namespace bhnsid
