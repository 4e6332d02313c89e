// Integral properties in closed form (row and slab sums over similar hubs) against the brute-force sum over
// every hub, in one process, side by side; the 24-pattern 10^4 x 10^4 x 10^4 lattice; density targeting.
// Lattices: the octet truss (4 nodes, 24 beam patterns, beams meeting only at nodes), explicit radii.
//   regular      U, V, W translations: every interior hub is a copy (O(1) shapes)
//   cylindrical  W rotates the slabs about an axis along V's translation (a bent panel): O(u) shapes
//   bent-graded  W = translation o swirl across the slabs (bent and graded stack): O(uv) shapes
// Usage: bench_properties [--long]
#include <cstdio>
#include <string>

#include "bench_common.hpp"
#include "steady/query/hub_overlaps.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "steady/properties/radius_scaling.hpp"
#include "brick_definition.hpp"

using namespace steady;

namespace {

enum class Kind { Regular, Cylindrical, BentGraded };
const char* name(Kind k) { return k == Kind::Regular ? "regular" : k == Kind::Cylindrical ? "cylindrical" : "bent-graded"; }

Lattice octet(std::int64_t n, Kind kind, double beam_radius = 0.04, bool hull = false) {
  test::BrickDefinition d;
  const Vec3 p[4] = {{0, 0, 0}, {0.5, 0.5, 0}, {0.5, 0, 0.5}, {0, 0.5, 0.5}};
  for (const Vec3& q : p) d.nodes.push_back({q, 0.1});
  // Every pair of nodes sqrt(2)/2 apart (the FCC nearest neighbours), once.
  for (int a = 0; a < 4; ++a)
    for (int b = 0; b < 4; ++b)
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj)
          for (int dk = -1; dk <= 1; ++dk) {
            if (std::abs(glm::length(p[b] + Vec3(di, dj, dk) - p[a]) - std::sqrt(0.5)) > 1e-9) continue;
            const bool forward = di > 0 || (di == 0 && (dj > 0 || (dj == 0 && (dk > 0 || (dk == 0 && a < b)))));
            if (!forward) continue;
            BeamPattern bp{a, di, dj, dk, b};
            if (!hull) {
              bp.from_radius = beam_radius;
              bp.to_radius = beam_radius;
            }
            d.beams.push_back(bp);
          }
  d.counts = {n, n, n};
  const double radius_of_curvature = 10.0 * static_cast<double>(n);  // the bend turns the stack by 0.1 rad
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  if (kind == Kind::Regular) d.w = {Similarity::translation({0, 0, 1})};
  if (kind == Kind::Cylindrical)
    d.w = {Similarity::rotation(-1.0 / radius_of_curvature, {0, 1, 0}, {-radius_of_curvature, 0, 0})};
  if (kind == Kind::BentGraded)
    d.w = {Similarity::translation({0, 0, 1}) *
           Similarity::swirl(-1.0 / radius_of_curvature, {0, 1, 0}, {0, 0, 0}, std::exp(0.2 / static_cast<double>(n)))};
  return Lattice(d);
}

LatticePropertiesOptions no_check() {
  LatticePropertiesOptions o;
  o.check_clean = false;
  return o;
}

double max_abs(const Mat3& m) {
  double v = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) v = std::max(v, std::abs(m[i][j]));
  return v;
}

double difference(const LatticeProperties& a, const LatticeProperties& b) {
  const double size = std::sqrt((a.inertia[0][0] + a.inertia[1][1] + a.inertia[2][2]) / a.volume);
  double d = std::abs(a.volume - b.volume) / a.volume;
  d = std::max(d, std::abs(a.area - b.area) / a.area);
  d = std::max(d, glm::length(a.centroid - b.centroid) / size);
  return std::max(d, max_abs(a.inertia - b.inertia) / max_abs(a.inertia));
}

void closed_form_against_brute_force(bool full) {
  std::printf("\n[1] closed form vs brute force (every hub built and summed), octet, 24 patterns, explicit radii\n");
  std::printf("%-12s %-8s %12s %14s %12s %12s %10s %10s\n", "lattice", "groups", "balls", "beams", "closed (s)",
              "brute (s)", "speed-up", "rel.diff");
  struct Row {
    Kind kind;
    std::int64_t n;
  };
  // 100^3 (the brute force takes two minutes per lattice) and the larger bent-graded lattices: --long.
  std::vector<Row> rows = {{Kind::Regular, 20},     {Kind::Regular, 50},     {Kind::Cylindrical, 20},
                           {Kind::Cylindrical, 50}, {Kind::BentGraded, 10},  {Kind::BentGraded, 20}};
  if (full) {
    rows.insert(rows.begin() + 2, {Kind::Regular, 100});
    rows.insert(rows.begin() + 5, {Kind::Cylindrical, 100});
    rows.push_back({Kind::BentGraded, 50});
  }
  for (const Row& r : rows) {
    const Lattice lat = octet(r.n, r.kind);
    LatticeProperties fast, brute;
    const double t_fast = bench::median_seconds(r.kind == Kind::BentGraded ? 3 : 7, [&] { fast = lattice_properties(lat, no_check()); });
    const double t_brute = bench::median_seconds(1, [&] { brute = lattice_properties_brute_force(lat); });
    std::printf("%-12s %-8s %12lld %14lld %12.5f %12.3f %9.0fx %10.1e\n", name(r.kind),
                (std::to_string(r.n) + "^3").c_str(), static_cast<long long>(lat.ball_count()),
                static_cast<long long>(lat.beam_count()), t_fast, t_brute, t_brute / t_fast, difference(brute, fast));
  }
}

void huge_lattice() {
  std::printf("\n[2] 10^4 x 10^4 x 10^4 octet (24 patterns): volume, area, centroid, inertia in closed form\n");
  std::printf("    (steady-lattices paper, Fig. 13: volume of the beams of such a lattice in under 10 minutes)\n");
  std::printf("%-12s %14s %16s %12s %22s %14s\n", "lattice", "balls", "beams", "time (s)", "volume", "hub shapes");
  for (Kind kind : {Kind::Regular, Kind::Cylindrical}) {
    const Lattice lat = octet(10000, kind);
    LatticeProperties p;
    const double t = bench::median_seconds(3, [&] { p = lattice_properties(lat, no_check()); });
    std::printf("%-12s %14.3e %16.3e %12.3f %22.15e %14lld\n", name(kind), static_cast<double>(lat.ball_count()),
                static_cast<double>(lat.beam_count()), t, p.volume, static_cast<long long>(p.hub_shapes));
  }
  std::printf("    (the clean check does not run at this size: the slab window would hold 4e8 hubs; the same design\n"
              "     is checked clean at 100^3 below)\n");
}

void density_targeting() {
  std::printf("\n[3] density targeting at 100^3 (octet): radius scale for 1.3 x the volume, to 1e-10 relative\n");
  std::printf("%-12s %12s %12s %14s %14s %10s %12s %14s\n", "lattice", "model (s)", "evals", "rel.error",
              "naive (s)", "speed-up", "clean (s)", "verdict");
  for (Kind kind : {Kind::Regular, Kind::Cylindrical}) {
    const Lattice lat = octet(100, kind);
    const double target = 1.3 * lattice_properties(lat, no_check()).volume;
    RadiusScaleOptions o;
    o.check_clean = false;
    RadiusScaleSolution sol;
    const double t_model = bench::median_seconds(7, [&] { sol = radius_scale_for_volume(lat, target, o); });
    const double achieved = lattice_properties(with_radius_scale(lat, sol.scale), no_check()).volume;
    // Baseline: the same secant-style search, each step the full closed form of the scaled lattice.
    double naive_scale = 0.0;
    const double t_naive = bench::median_seconds(3, [&] {
      double lo = 0.5, hi = 2.0;
      auto volume = [&](double s) { return lattice_properties(with_radius_scale(lat, s), no_check()).volume; };
      double vlo = volume(lo), vhi = volume(hi);
      for (int it = 0; it < 100 && hi - lo > 1e-11 * hi; ++it) {  // regula falsi in log-log
        const double x = std::log(lo) + (std::log(target) - std::log(vlo)) * (std::log(hi) - std::log(lo)) /
                                             (std::log(vhi) - std::log(vlo));
        const double s = std::exp(x), v = volume(s);
        if (std::abs(v - target) <= 1e-10 * target) {
          lo = hi = s;
          break;
        }
        if (v < target) {
          lo = s;
          vlo = v;
        } else {
          hi = s;
          vhi = v;
        }
      }
      naive_scale = 0.5 * (lo + hi);
    });
    HubOverlapReport report;
    const double t_clean = bench::median_seconds(1, [&] { report = check_hub_overlaps(with_radius_scale(lat, sol.scale)); });
    std::printf("%-12s %12.5f %12d %14.2e %14.4f %9.0fx %12.2f %14s\n", name(kind), t_model, sol.evaluations,
                std::abs(achieved - target) / target, t_naive, t_naive / t_model, t_clean,
                report.clean() ? "clean" : (report.verified ? "NOT clean" : "unverified"));
    (void)naive_scale;
  }
}

void hull_model(bool full) {
  std::printf("\n[4] hull model (beam radius = node radius: every hub's stumps overlap, integrated by quadrature)\n");
  std::printf("%-12s %-8s %12s %12s %10s %14s %10s\n", "lattice", "groups", "closed (s)", "brute (s)", "speed-up",
              "quadratures", "rel.diff");
  for (std::int64_t n : full ? std::vector<std::int64_t>{6, 12} : std::vector<std::int64_t>{6}) {
    const Lattice lat = octet(n, Kind::Cylindrical, 0.0, true);
    LatticeProperties fast, brute;
    const double t_fast = bench::median_seconds(1, [&] { fast = lattice_properties(lat, no_check()); });
    const double t_brute = bench::median_seconds(1, [&] { brute = lattice_properties_brute_force(lat); });
    std::printf("%-12s %-8s %12.3f %12.3f %9.0fx %14lld %10.1e\n", name(Kind::Cylindrical),
                (std::to_string(n) + "^3").c_str(), t_fast, t_brute, t_brute / t_fast,
                static_cast<long long>(fast.overlapping_hub_shapes), difference(brute, fast));
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool full = bench::long_run(argc, argv);
  std::printf("bench_properties%s: medians of repeats; both sides of every ratio measured in this run\n",
              full ? " --long" : "");
  closed_form_against_brute_force(full);
  huge_lattice();
  density_targeting();
  hull_model(full);
  return 0;
}
