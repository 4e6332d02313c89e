#include "mesh/band_sides.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Side_of_triangle_mesh.h>

#include <algorithm>
#include <cmath>

#include "mesh/cgal_mesh.hpp"

namespace steady {

namespace {

using Point = CgalKernel::Point_3;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<CgalMesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<CgalKernel, Primitive>>;

// A hub's reach: a ball around its center holding the ball and its half-beams.
double hub_reach(const MeshPlan& plan, std::size_t h) {
  const FlatLattice& f = *plan.lattice;
  double reach = f.balls[plan.hubs[h].ball].radius;
  for (const auto& [e, end] : plan.hubs[h].stumps)
    reach = std::max(reach, 0.5 * plan.frustums[e].cone.length + std::max(f.beams[e].ra, f.beams[e].rb));
  return reach;
}

// The ball around the axis-aligned box of some points (it holds their convex hull).
struct Bound {
  Vec3 lo{HUGE_VAL}, hi{-HUGE_VAL};
  void add(const Vec3& p) { lo = glm::min(lo, p), hi = glm::max(hi, p); }
  Vec3 center() const { return 0.5 * (lo + hi); }
  double radius() const { return 0.5 * glm::length(hi - lo); }
};

class Surface {
 public:
  explicit Surface(const TriangleMesh& m) : mesh_(to_half_edge_mesh<CgalMesh>(m)), tree_(faces(mesh_).first, faces(mesh_).second, mesh_), side_(tree_) {
    tree_.accelerate_distance_queries();
  }
  // The side of a ball of radius r around c: Crossing unless clear of the surface (with a relative margin for
  // the rounding of the distance).
  Side of(const Vec3& c, double r) const {
    const Point p(c.x, c.y, c.z);
    const double reach = r * (1.0 + 1e-6);
    if (tree_.squared_distance(p) <= reach * reach) return Side::Crossing;
    return side_(p) == CGAL::ON_BOUNDED_SIDE ? Side::Inside : Side::Outside;
  }

 private:
  CgalMesh mesh_;
  Tree tree_;
  CGAL::Side_of_triangle_mesh<CgalMesh, CgalKernel> side_;
};

Side patch_side(const MeshPlan& plan, const Surface& s, std::size_t h) {
  const HubTemplate& t = plan.templates[plan.hubs[h].templ];
  Bound b;
  for (std::uint32_t v = 0; v < t.vertices.size(); ++v) b.add(placed_vertex(plan, h, v));
  return s.of(b.center(), b.radius());
}

Side strip_side(const MeshPlan& plan, const Surface& s, std::int64_t e) {
  Bound b;
  for (int end = 0; end < 2; ++end) {
    const MeshBeamEnd& be = plan.ends[2 * e + end];
    for (std::uint32_t v : plan.templates[plan.hubs[be.hub].templ].loops[be.slot]) b.add(placed_vertex(plan, be.hub, v));
  }
  return s.of(b.center(), b.radius());
}

}  // namespace

BandSides classify_band(const MeshPlan& plan, const TriangleMesh& surface) {
  const Surface s(surface);
  const FlatLattice& f = *plan.lattice;
  BandSides out;
  std::vector<Side> hubs(plan.hubs.size());
  out.patches.resize(plan.hubs.size());
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) {
    hubs[h] = s.of(f.balls[plan.hubs[h].ball].center, hub_reach(plan, h));
    // A hub in reach may still have its sphere patch clear of the surface.
    out.patches[h] = hubs[h] == Side::Crossing ? patch_side(plan, s, h) : hubs[h];
    ++(hubs[h] == Side::Inside ? out.inside_hubs : hubs[h] == Side::Crossing ? out.crossing_hubs : out.outside_hubs);
  }
  out.strips.assign(static_cast<std::size_t>(f.beam_count()), Side::Outside);
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!plan.frustums[e].exists) continue;
    const Side a = hubs[plan.ends[2 * e].hub], b = hubs[plan.ends[2 * e + 1].hub];
    // Each half of a beam lies in its hub's reach: two hubs on one side put the whole strip there.
    out.strips[e] = a == b && a != Side::Crossing ? a : strip_side(plan, s, e);
  }
  return out;
}

}  // namespace steady
