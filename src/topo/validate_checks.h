// The validator's checks, one per file. Each appends violations naming ids.
#pragma once

#include <string>
#include <vector>

#include "cellforge/topo/validate.h"

namespace cellforge::inline topo::checks {

using Violations = std::vector<Violation>;

// validate_records.cpp: every reference names a live entity (run first; the other
// checks assume it passed).
void records(const Model& m, Violations& out);
// validate_cycles.cpp: vertex cycles, radial cycles (with angular order), loops.
void vertex_cycles(const Model& m, Violations& out);
void radial_cycles(const Model& m, Violations& out);
void loops(const Model& m, Violations& out);
// validate_groups.cpp: the group index lists every live element once, under the
// group its records give it, and its counts agree.
void groups(const Model& m, Violations& out);
// validate_records.cpp, after the loops passed: each face mark is set where the
// face's loops need it, and outside an edit only there.
void face_marks(const Model& m, Violations& out);
// validate_wedges.cpp: around each edge, the two face sides facing each wedge
// between radially consecutive faces name the same volume (this is also what makes
// the faces of a solid consistently oriented).
void wedges(const Model& m, Violations& out);
// validate_euler.cpp: the Euler-Poincare relations.
void euler(const Model& m, Violations& out);

}  // namespace cellforge::inline topo::checks
