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

double distance2(const Vec3& a, const Vec3& b) { return glm::dot(a - b, a - b); }

}  // namespace

struct TrimSurface::Queries {
  explicit Queries(const TriangleMesh& m)
      : mesh(to_half_edge_mesh<CgalMesh>(m)), tree(faces(mesh).first, faces(mesh).second, mesh), side(tree) {
    tree.accelerate_distance_queries();
  }
  // The side of a ball of radius r around c: Crossing unless clear of the surface (with a relative margin for
  // the rounding of the distance).
  Side of(const Vec3& c, double r) const {
    const Point p(c.x, c.y, c.z);
    const double reach = r * (1.0 + 1e-6);
    if (tree.squared_distance(p) <= reach * reach) return Side::Crossing;
    return side(p) == CGAL::ON_BOUNDED_SIDE ? Side::Inside : Side::Outside;
  }

  CgalMesh mesh;
  Tree tree;
  CGAL::Side_of_triangle_mesh<CgalMesh, CgalKernel> side;
};

namespace {

// A hub's patch lies in the ball around its center through its farthest vertex (its triangles are chords of a
// star-shaped surface, and the caps of its loops are flat fans between its vertices).
Side patch_side(const MeshPlan& plan, const TrimSurface::Queries& s, std::size_t h) {
  const HubTemplate& t = plan.templates[plan.hubs[h].templ];
  const Vec3 c = plan.lattice->balls[plan.hubs[h].ball].center;
  double r2 = 0.0;
  for (std::uint32_t v = 0; v < t.vertices.size(); ++v) r2 = std::max(r2, distance2(placed_vertex(plan, h, v), c));
  return s.of(c, std::sqrt(r2));
}

// A strip, and the caps of its loops, lie in the convex hull of its two loops: in the cylinder about the line
// through the loops' centroids that holds their vertices. That cylinder is covered by a row of balls, each over a
// piece of it no longer than its radius; a strip is clear when every ball is (then all are on one side, the row
// being connected).
Side strip_side(const MeshPlan& plan, const TrimSurface::Queries& s, std::int64_t e) {
  std::vector<Vec3> points;
  Vec3 centroid[2];
  for (int end = 0; end < 2; ++end) {
    const MeshBeamEnd& be = plan.ends[2 * e + end];
    const std::vector<std::uint32_t>& loop = plan.templates[plan.hubs[be.hub].templ].loops[be.slot];
    centroid[end] = Vec3(0.0);
    for (std::uint32_t v : loop) points.push_back(placed_vertex(plan, be.hub, v)), centroid[end] += points.back();
    centroid[end] /= static_cast<double>(loop.size());
  }
  const Vec3 axis = glm::normalize(centroid[1] - centroid[0]);
  double t0 = HUGE_VAL, t1 = -HUGE_VAL, rho2 = 0.0;
  for (const Vec3& p : points) {
    const double t = glm::dot(p - centroid[0], axis);
    t0 = std::min(t0, t), t1 = std::max(t1, t);
    rho2 = std::max(rho2, distance2(p, centroid[0] + t * axis));
  }
  const double rho = std::sqrt(rho2), length = t1 - t0;
  const int pieces = std::max(1, static_cast<int>(std::ceil(length / std::max(rho, 1e-300))));
  const double piece = length / pieces, radius = std::sqrt(rho2 + 0.25 * piece * piece);
  Side side = Side::Crossing;
  for (int k = 0; k < pieces; ++k) {
    const Side here = s.of(centroid[0] + (t0 + (k + 0.5) * piece) * axis, radius);
    if (here == Side::Crossing) return here;
    side = here;
  }
  return side;
}

}  // namespace

TrimSurface::TrimSurface(const TriangleMesh& surface) : queries_(std::make_unique<Queries>(surface)) {}
TrimSurface::~TrimSurface() = default;

std::vector<Side> TrimSurface::hubs(const MeshPlan& plan) const {
  std::vector<Side> out(plan.hubs.size());
  for (std::size_t h = 0; h < plan.hubs.size(); ++h)
    out[h] = queries_->of(plan.lattice->balls[plan.hubs[h].ball].center, hub_reach(plan, h));
  return out;
}

std::vector<std::pair<std::size_t, Vec3>> TrimSurface::clear_places(const std::vector<Vec3>& points, double gap) const {
  const Queries& s = *queries_;
  std::vector<std::pair<std::size_t, Vec3>> moved;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Point p(points[i].x, points[i].y, points[i].z);
    // A point within `gap` of a triangle has that triangle in its box of half-width gap (twice that, for the
    // rounding): a box query answers the far points, nearly all of them, many times faster than a closest point.
    const double box = 2.0 * gap;
    if (!s.tree.do_intersect(
            CGAL::Bbox_3(p.x() - box, p.y() - box, p.z() - box, p.x() + box, p.y() + box, p.z() + box)))
      continue;
    const auto [closest, face] = s.tree.closest_point_and_primitive(p);
    const Vec3 c(closest.x(), closest.y(), closest.z());
    const double d = std::sqrt(distance2(points[i], c));
    if (d >= gap) continue;
    Vec3 away = points[i] - c;
    if (d < 1e-3 * gap) {  // on the surface, or too near for the direction to mean anything: its face's normal
      const auto h = s.mesh.halfedge(face);
      const Point& a = s.mesh.point(s.mesh.source(h));
      const Point& b = s.mesh.point(s.mesh.target(h));
      const Point& e = s.mesh.point(s.mesh.target(s.mesh.next(h)));
      const auto n = CGAL::cross_product(b - a, e - a);
      away = Vec3(n.x(), n.y(), n.z());
    }
    moved.emplace_back(i, c + gap * glm::normalize(away));
  }
  return moved;
}

std::vector<char> hubs_needed(const MeshPlan& plan, const std::vector<Side>& hubs) {
  std::vector<char> out(plan.hubs.size(), 0);
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) out[h] = hubs[h] != Side::Outside;
  for (std::size_t e = 0; 2 * e < plan.ends.size(); ++e) {
    if (!plan.frustums[e].exists) continue;
    const std::int64_t a = plan.ends[2 * e].hub, b = plan.ends[2 * e + 1].hub;
    if (hubs[a] != Side::Outside || hubs[b] != Side::Outside) out[a] = out[b] = 1;
  }
  return out;
}

BandSides TrimSurface::elements(const MeshPlan& plan, const std::vector<Side>& hubs) const {
  const Queries& s = *queries_;
  const FlatLattice& f = *plan.lattice;
  BandSides out;
  out.patches.resize(plan.hubs.size());
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) {
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
