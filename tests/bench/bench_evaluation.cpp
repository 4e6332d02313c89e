// Direct O(1) evaluation of a steady lattice's balls (closed-form powers of U, V, W, as in Eq. 7 of the
// steady-lattices paper) against the naive construction that iterates the similarities (U applied i times,
// then V j times, then W k times for every ball), on a bent, twisted, tapered lattice. Both run in one process,
// side by side; medians of repeats. Usage: bench_evaluation [--long]
#include <cstdio>

#include "bench_common.hpp"
#include "steady/lattice/lattice.hpp"
#include "brick_definition.hpp"

using namespace steady;

namespace {

Lattice bent_twisted_tapered(std::int64_t n) {
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, 0.2}};
  d.beams = {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}};
  d.counts = {n, n, n};
  d.u = {Similarity::swirl(0.01, {0, 0, 1}, {0, -80, 0}, 1.002)};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::screw(0.01, {0, 0, 1}, {0, 0, 0}, 1.0)};
  return Lattice(d);
}

// The naive twin: every ball by iterated application, O(i + j + k) per ball.
double naive_checksum(const Lattice& lat) {
  const auto& d = lat.definition();
  const Counts& c = lat.counts();
  const SteadyBrick& brick = *lat.layout().steady_brick();
  double sum = 0.0;
  for (std::int64_t k = 0; k < c.w; ++k)
    for (std::int64_t j = 0; j < c.v; ++j)
      for (std::int64_t i = 0; i < c.u; ++i) {
        Vec3 p = d.nodes[0].center;
        for (std::int64_t r = 0; r < i; ++r) p = brick.step_along(0).apply_point(p);
        for (std::int64_t r = 0; r < j; ++r) p = brick.step_along(1).apply_point(p);
        for (std::int64_t r = 0; r < k; ++r) p = brick.step_along(2).apply_point(p);
        sum += p.x + p.y + p.z;
      }
  return sum;
}

}  // namespace

int main(int argc, char** argv) {
  const bool full = bench::long_run(argc, argv);
  std::printf("%-10s %12s %14s %14s %10s %12s\n", "groups", "balls", "naive (s)", "direct (s)", "speed-up",
              "diff/ball");
  for (std::int64_t n : full ? std::vector<std::int64_t>{20, 50, 100, 200} : std::vector<std::int64_t>{20, 50, 100}) {
    const Lattice lat = bent_twisted_tapered(n);
    std::vector<double> centers(3 * lat.ball_count()), radii(lat.ball_count());
    const double direct = bench::median_seconds(5, [&] { lat.balls(centers.data(), radii.data()); });
    double checksum = 0.0;
    const double naive = bench::median_seconds(n >= 100 ? 1 : 3, [&] { checksum = naive_checksum(lat); });
    double direct_sum = 0.0;
    for (double c : centers) direct_sum += c;
    std::printf("%-10s %12lld %14.4f %14.4f %9.0fx %12.2e\n", (std::to_string(n) + "^3").c_str(),
                static_cast<long long>(lat.ball_count()), naive, direct, naive / direct,
                std::abs(checksum - direct_sum) / lat.ball_count());
  }
  return 0;
}
