// The size of a lattice mesh before any template is made: from the balls' radii, the tolerance and the beams
// alone, so that a tolerance far below the radii is refused at once instead of tessellating for minutes and then
// failing (issue 16, docs/reliability.md).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "mesh/hub_tessellation.hpp"
#include "mesh/mesh_plan.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/core/progress.hpp"
#include "steady/mesh/lattice_mesh.hpp"
#include "steady/mesh/triangle_mesh.hpp"

namespace steady {
namespace {

// At most how many segments a hub's circle gets at relative tolerance `tau`: circle_segments at the largest
// radius (the unit ball's), in double so that any tolerance gives a number (infinity at worst), never an
// overflowing int.
double loop_bound(double tau) {
  const double chord = tau < 1.0 ? M_PI / std::acos(1.0 - tau) : 6.0;
  const double spacing = std::sqrt(8.0 * M_PI / (std::sqrt(3.0) * sphere_point_count(tau)));
  return std::max({6.0, std::ceil(chord), std::ceil(2.0 * M_PI / spacing)});
}

std::string g(double v) {
  std::ostringstream os;
  os.precision(3);
  os << v;
  return os.str();
}

}  // namespace

double template_point_bound(double tau, std::size_t stumps) {
  return sphere_point_count(tau) + 2.0 * static_cast<double>(stumps) * loop_bound(tau);
}

MeshEstimate estimate_lattice_mesh(const FlatLattice& f, double tolerance) {
  // A clean hub is its ball's sphere with one hole per beam, closed by the hole's circle: by Euler's formula it has
  // at most 2 (sphere points + circle points) - (circle points) triangles; each beam's strip has as many triangles
  // as its two circles have points. A crowded hub (or the hull model's) also has each stump's collar circle and the
  // band up to it, refined at the creases: counted as a second circle per stump, so two circles per beam end, four
  // triangles per circle point. The template of a hub is made at the tolerance level of tolerance / radius.
  if (!std::isfinite(tolerance) || tolerance <= 0.0)
    fail_input("tolerance", "must be a finite length > 0 (got " + g(tolerance) + ")");
  MeshEstimate e;
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    if ((i & 4095) == 0) poll_progress();
    const double tau = level_tolerance(tolerance_level(tolerance / f.balls[i].radius));
    const double points = template_point_bound(tau, static_cast<std::size_t>(f.degree(i)));
    e.vertices += points;
    e.triangles += 2.0 * points;  // the hub's triangles, and its circles' share of the strips
  }
  e.bytes = e.vertices * sizeof(Vec3) + e.triangles * sizeof(Triangle);
  return e;
}

void require_mesh_memory(const FlatLattice& f, double tolerance, const std::string& what) {
  const MeshEstimate e = estimate_lattice_mesh(f, tolerance);
  if (e.bytes <= static_cast<double>(memory_budget_bytes())) return;
  // The smallest tolerance (within 10 %) whose mesh fits, by bisection on the estimate (it falls as the tolerance
  // grows), up to the largest tolerance the lattice allows (a quarter of its smallest radius).
  double smallest_radius = INFINITY;
  for (const Ball& b : f.balls) smallest_radius = std::min(smallest_radius, b.radius);
  double lo = tolerance, hi = 0.2499 * smallest_radius;
  std::string suggestion;
  if (hi > lo && estimate_lattice_mesh(f, hi).bytes <= static_cast<double>(memory_budget_bytes())) {
    while (hi > 1.1 * lo) {
      const double mid = std::sqrt(lo * hi);
      (estimate_lattice_mesh(f, mid).bytes <= static_cast<double>(memory_budget_bytes()) ? hi : lo) = mid;
    }
    suggestion = "a tolerance of " + g(hi) + " or more fits";
  } else {
    suggestion = "no tolerance the balls allow fits";
  }
  require_memory(static_cast<std::uint64_t>(std::min(e.bytes, 1.8e19)),
                 what + ": about " + g(e.triangles) + " triangles (estimated from the tolerance " + g(tolerance) +
                     " and the balls' radii, before any is made)",
                 suggestion + "; or write STL (streamed: the mesh is never held), or a 3MF beam lattice "
                              "(write_3mf(beam_lattice=True): a few bytes per beam)");
}

}  // namespace steady
