#pragma once
// The core of a hub whose stumps overlap near its ball (not clean): the ball and its stumps up to a collar
// circle per stump, beyond which the stumps no longer meet. Built once per distinct hub shape in the hub's
// canonical frame (unit ball at the origin) and placed as similar copies; the beams then run from collar to
// collar like the beams of clean hubs run between exit circles.
//
// Hull model (every beam tangent to the ball): no Boolean. A cone tangent to the unit sphere along the circle
// where d.x = s (s = sin phi, c = cos phi) satisfies |x|^2 - 1 = w(x)^2 with the linear function
// w(x) = (d.x - s)/c, which equals the distance v along the cone's generators from the tangent circle. So two
// such cones meet where w_i = +-w_j: in plane conics (the hint of the issue, checked numerically in the tests),
// and the boundary of ball U stumps is a maximization diagram: a point of cone i is on it iff w_i >= max(0, w_j)
// for all j, a point of the sphere iff every w_j <= 0. Each face is a quadric cut by planes: along a generator
// of cone i every constraint is linear in v, so the face is bounded below by an envelope of conic arcs (shared
// with the neighbouring cones) and tangent circle arcs (shared with the sphere), and above by its collar.
// No Boolean ever sees the tangent contact of a cone with the sphere.
//
// Transversal (explicit end radii thinner than the node, exit circles overlapping): one Boolean Fuse of the
// ball with the stumps truncated at their collars; every contact is transversal.
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>

#include <memory>
#include <vector>

#include "steady/core/vec.hpp"
#include "lattice/hub_collars.hpp"

namespace steady {

struct HubCore {
  CoreKind kind = CoreKind::Hull;
  TopoDS_Compound faces;              // the core's faces: an open shell bounded by the collar circles
  std::vector<TopoDS_Edge> collars;   // per stump: its collar circle, one closed edge
  std::vector<double> collar_position;  // per stump: axial position of the collar (canonical)
  std::int64_t face_count = 0;
};

// Builds the core. Throws InvalidInput ("hub") for configurations outside the supported class (a stump swallowed
// by its neighbours, a conic through a cone's apex, a sphere region the seam cannot avoid).
std::shared_ptr<const HubCore> build_hub_core(const std::vector<CoreStump>& stumps, CoreKind kind,
                                              const std::vector<double>& collars);

}  // namespace steady
