#pragma once
// The steady kernel without OpenCASCADE: similarities, lattices and their layouts, queries and properties.
// B-rep parts (OpenCASCADE) are in steady/brep.hpp. Link steady_core + steady_query (+ steady_properties).

#include "steady/core/ball.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/frame.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/core/progress.hpp"
#include "steady/core/similarity.hpp"
#include "steady/core/similarity2d.hpp"
#include "steady/core/tolerance.hpp"
#include "steady/core/vec.hpp"

#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/broad_phase.hpp"
#include "steady/lattice/convex_distance.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/hub.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/lattice/lattice_io.hpp"

#include "steady/query/block_bounds.hpp"
#include "steady/query/clean_check.hpp"
#include "steady/query/filtered_lattice.hpp"
#include "steady/query/filters.hpp"
#include "steady/query/hub_overlaps.hpp"
#include "steady/query/interference.hpp"
#include "steady/query/lattice_query.hpp"
#include "steady/query/queries.hpp"
#include "steady/query/query_tolerance.hpp"
#include "steady/query/rangefinder.hpp"

#include "steady/properties/hub_properties.hpp"
#include "steady/properties/hub_union.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "steady/properties/mass_moments.hpp"
#include "steady/properties/radius_scaling.hpp"
#include "steady/properties/similar_copies.hpp"
