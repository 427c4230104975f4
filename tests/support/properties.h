// Property tables of every stored value type on a model, with the values that
// files and databases find hard (signed zeros, NaN, infinities, subnormals, the
// ends of every integer range, escapes and non-ASCII text), and the check that two
// models hold the same tables bit for bit.
#pragma once

#include <cstdint>

#include "cellforge/topo/model.h"

namespace cellforge::testing {

// Adds to m a table of each PropertyType (spread over vertices, edges, faces and
// cells, values on a seeded random half of the elements, the hard values first)
// and one of a type that stays in memory only ("scratch", a face property).
void add_every_property_type(Model& m, std::uint32_t seed);

// Fails the test unless a and b hold the same stored property tables: the same
// names, types and defaults, and the same value on every element (by dense key),
// compared bit for bit.
void expect_same_properties(const Model& a, const Model& b);

}  // namespace cellforge::testing
