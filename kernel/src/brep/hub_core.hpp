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
// Transversal stumps of one end radius rho < 1 (explicit beam radii, the same for every beam at this node): the
// same construction. Every cone is tangent to the sphere of radius rho inside the ball, so scaled by 1 / rho it
// is the hull model's arrangement with the ball's sphere at v = sqrt(1 / rho^2 - 1) instead of v = 0 along the
// generators; still no Boolean.
//
// Other transversal hubs (end radii that differ): one Boolean Fuse of the ball with the stumps truncated at their
// collars; every contact is transversal. It is also the fallback where the arrangement refuses a hub.
#include <Geom_Circle.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Solid.hxx>

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
  bool fused = false;                 // built by the Boolean Fuse (else by the envelope arrangement)
};

// Builds the core with the given collars (core_collars) and checks that it encloses, with its collar disks, the
// exact volume of its hub cut at those collars (hub_properties, 1e-6 relative): no core is handed out unmeasured.
// Transversal stumps of one end radius go through the arrangement first; a core it refuses or OpenCASCADE finds invalid (tangent exit caps) is fused instead, with
// place_collars' collars (or those 6 or 12 % farther out, where the Fuse split a collar): the core's collar_position
// says which were used. Throws InvalidInput ("hub") for
// configurations outside the supported class (a stump swallowed by its neighbours, a conic through a cone's apex,
// a collar touched by the Fuse).
// `fit` says which collars those are (core_collars' fit), so the arrangement checks its envelope with the same
// clearance.
std::shared_ptr<const HubCore> build_hub_core(const std::vector<CoreStump>& stumps, CoreKind kind,
                                              const std::vector<double>& collars, CollarFit fit = CollarFit::Roomy);

// The circle bounding `face` when it is a planar disk (one non-degenerate edge, a circle), else null: how a
// collar disk is recognised in a Fuse's result, by its geometry (the Fuse's history has reported untouched disks
// as deleted).
Handle(Geom_Circle) disk_circle(const TopoDS_Face& face);

// The core closed by a disk at every collar: the solid the hub is up to its collars (the build measures it against
// the exact properties before handing the core out; the tests check its validity).
TopoDS_Solid closed_core(const HubCore& core);

// The Boolean construction of a transversal core alone: the slow twin of the arrangement in the tests.
std::shared_ptr<const HubCore> build_transversal_core(const std::vector<CoreStump>& stumps,
                                                      const std::vector<double>& collars);

}  // namespace steady
