#pragma once
// Sets of unit directions up to a rotation: a frame fixed by the set itself, and the rotation (if any) that
// carries one set onto another whatever the order of their elements. The hub catalog (hub_catalog.hpp) relies on
// the order of a hub's stumps, which similar hubs of one steady row share; connectors of a cubic grid's corners
// list their beams in different orders, so they are matched as unordered sets.
#include <cstddef>
#include <vector>

#include "steady/core/vec.hpp"

namespace steady {

// A frame of the set: z along directions[0], x along the part of the first direction not parallel to it (sine of
// the angle above kDirectionFrameSine) orthogonal to z. `second` is that direction's index, or -1 when every
// direction lies on the axis of the first (the set is then symmetric about it, and x is any perpendicular).
struct DirectionFrame {
  Mat3 rotation{1.0};  // columns: the world images of canonical x, y, z
  int second = -1;
};

// Two directions this far from parallel (sine of their angle) fix a frame to about tolerance / 1e-3.
constexpr double kDirectionFrameSine = 1e-3;

DirectionFrame direction_frame(const std::vector<Vec3>& directions);

// The sum of the pairwise dot products: equal (to degree^2 * tolerance) for sets that match up to a rotation, so
// candidate sets are looked up by it before they are matched.
double pairwise_dot_sum(const std::vector<Vec3>& directions);

// Finds a proper rotation R with { R c } = { world } to `tolerance` (radians, about the angle between matched
// directions), given the canonical set (frame of direction_frame: c[0] = +z, c[second] in the xz-plane). Tries
// each pair of world directions at the angle of (c[0], c[second]). Returns false when none fits.
bool match_direction_set(const std::vector<Vec3>& canonical, int second, const std::vector<Vec3>& world,
                         double tolerance, Mat3& rotation);

}  // namespace steady
