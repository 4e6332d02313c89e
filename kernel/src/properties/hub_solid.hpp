#pragma once
// Internal to the exact union of overlapping hubs (hub_union.cpp), shown to the tests.
#include <TopoDS_Shape.hxx>

#include "steady/core/vec.hpp"
#include "steady/lattice/hub.hpp"

namespace steady {

// One hub as an OpenCASCADE solid, translated by -origin: its ball fused with its stumps' frustums up to the
// cuts (the union's clusters fuse these pieces), in the first layout of the pieces whose Fuse encloses the hub's
// exact volume (and its ball's caps beyond its cuts) to 1e-6; throws std::runtime_error when none does.
TopoDS_Shape hub_solid(const Hub& hub, const Vec3& origin);

}  // namespace steady
