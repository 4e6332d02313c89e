#pragma once
// One distinct hub shape as triangles, in its canonical frame (unit ball at the origin, hub_catalog.hpp): the
// template that lattice_mesh places as similar copies.
//
// Clean hub: the sphere minus its exit caps. Points spread evenly over the sphere (away from the caps) and the
// vertices of the exit circles all lie on the unit sphere, so their convex hull is the sphere's Delaunay
// triangulation; its faces with all three corners on one circle are exactly the cap's polygon (every other point
// lies strictly outside the cap), and dropping them leaves the patch with one hole per beam, bounded by the
// circle's own vertices. No constrained triangulation and no Boolean.
//
// Crowded hub (exit circles overlap): the ball and its stumps up to their collars (hub_collars.hpp) form a solid
// that is star-shaped from the ball's center, so its boundary is a radial graph over the sphere of directions:
// along w it lies at max(1, stump_reach of every stump). The directions are triangulated as above, with points
// placed on the crease curves where the farthest piece changes (found by bisection on a finer triangulation, the
// triple points by Newton) and the collar circles' directions as holes; each direction then goes to its point on
// the boundary. The radial image of a triangulated sphere is embedded (each triangle keeps its own cone of
// directions), so the template has no self-intersection by construction, and no Boolean is involved.
#include <cstdint>
#include <vector>

#include "lattice/hub_catalog.hpp"
#include "lattice/hub_collars.hpp"
#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

struct HubTemplate {
  std::vector<Vec3> vertices;       // canonical
  std::vector<Triangle> triangles;  // outward
  // Per stump (in the hub's stump order): the vertices of the circle where its beam starts, counterclockwise
  // about the stump's direction, and that circle's axial position and radius (canonical).
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<double> loop_position;
  std::vector<double> loop_radius;
};

// Templates are made at relative tolerances 2^(-level/2): a hub of radius R meshed to `tolerance` uses the level
// of tolerance / R rounded down, so copies of one shape at scales within half an octave share a template.
int tolerance_level(double relative_tolerance);
double level_tolerance(int level);

// How many points a whole unit sphere's template spreads at relative tolerance `tolerance` (a hub's template has
// at most these, less its holes, plus its circles): for estimates made before any template (mesh_estimate.cpp).
double sphere_point_count(double tolerance);

// Segments of a circle of radius `radius` (unit-ball units) at relative tolerance `tolerance`: the chord error
// radius (1 - cos(pi / n)) within the tolerance, and edges no longer than the sphere's point spacing.
int circle_segments(double radius, double tolerance);

HubTemplate tessellate_clean_hub(const std::vector<SphereCap>& caps, double tolerance);
HubTemplate tessellate_crowded_hub(const std::vector<CoreStump>& stumps, const std::vector<double>& collars,
                                   double tolerance);

}  // namespace steady
