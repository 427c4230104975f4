// The drafts behind the sweeps, shared with the primitives that are sweeps
// (make_prism, make_torus). The region must already be checked and oriented.
#pragma once

#include "shape/draft.h"
#include "cellforge/shape/sweep.h"

namespace cellforge::shape {

Result<Draft> extrude_draft(const Region& region, const LinearExtrudeOptions& options);
Result<Draft> revolve_draft(const Region& region, const RotateExtrudeOptions& options);

}  // namespace cellforge::shape
