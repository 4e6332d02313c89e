#include "steady/lattice/flat_lattice.hpp"

#include <tbb/parallel_for.h>

#include <cmath>
#include <string>

#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/core/progress.hpp"

namespace steady {

namespace {

// Bytes per listed element: the ball or beam itself plus its share of the incidence arrays.
constexpr std::uint64_t kBytesPerBall = sizeof(Ball) + sizeof(std::int64_t);
constexpr std::uint64_t kBytesPerBeam = sizeof(FlatBeam) + 2 * sizeof(std::int64_t);

void build_incidence(FlatLattice& f) {
  const std::int64_t n = f.ball_count();
  f.incidence_offsets.assign(n + 1, 0);
  for (const FlatBeam& b : f.beams) {
    ++f.incidence_offsets[b.a + 1];
    ++f.incidence_offsets[b.b + 1];
  }
  for (std::int64_t i = 0; i < n; ++i) f.incidence_offsets[i + 1] += f.incidence_offsets[i];
  f.incidence.resize(f.incidence_offsets[n]);
  std::vector<std::int64_t> fill(f.incidence_offsets.begin(), f.incidence_offsets.end() - 1);
  // Beams are visited in increasing index, so every ball's list comes out sorted.
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    f.incidence[fill[f.beams[e].a]++] = e;
    f.incidence[fill[f.beams[e].b]++] = e;
  }
}

}  // namespace

FlatLattice flatten(const Lattice& lattice) {
  const std::int64_t nb = lattice.ball_count(), ne = lattice.beam_count();
  require_memory(static_cast<std::uint64_t>(nb) * kBytesPerBall + static_cast<std::uint64_t>(ne) * kBytesPerBeam,
                 "listing the lattice's " + std::to_string(nb) + " balls and " + std::to_string(ne) + " beams",
                 "query a region (query_ball), use the closed-form properties, or list a filtered part");
  FlatLattice f;
  {
    std::vector<double> centers(3 * nb), radii(nb);
    lattice.balls(centers.data(), radii.data());
    poll_progress();  // each step takes a second or more per 10^7 elements: Ctrl-C between them
    f.balls.resize(nb);
    tbb::parallel_for(std::int64_t(0), nb, [&](std::int64_t i) {
      f.balls[i] = {{centers[3 * i], centers[3 * i + 1], centers[3 * i + 2]}, radii[i]};
    });
  }
  {
    std::vector<std::int64_t> a(ne), b(ne);
    std::vector<double> ra(ne), rb(ne);
    lattice.beams(a.data(), b.data(), ra.data(), rb.data());
    poll_progress();
    f.beams.resize(ne);
    tbb::parallel_for(std::int64_t(0), ne, [&](std::int64_t e) { f.beams[e] = {a[e], b[e], ra[e], rb[e]}; });
  }
  poll_progress();
  build_incidence(f);
  return f;
}

FlatLattice make_flat_lattice(std::vector<Ball> balls, std::vector<FlatBeam> beams) {
  const std::int64_t nb = static_cast<std::int64_t>(balls.size());
  for (std::int64_t i = 0; i < nb; ++i) {
    const std::string field = "balls[" + std::to_string(i) + "]";
    require_finite(balls[i].center.x, field + ".center");
    require_finite(balls[i].center.y, field + ".center");
    require_finite(balls[i].center.z, field + ".center");
    require_positive(balls[i].radius, field + ".radius");
  }
  for (std::size_t e = 0; e < beams.size(); ++e) {
    const std::string field = "beams[" + std::to_string(e) + "]";
    const FlatBeam& b = beams[e];
    if (b.a < 0 || b.a >= nb || b.b < 0 || b.b >= nb)
      fail_input(field, "ball index out of range [0, " + std::to_string(nb) + ")");
    if (b.a == b.b) fail_input(field, "joins ball " + std::to_string(b.a) + " to itself");
    require_positive(b.ra, field + ".ra");
    require_positive(b.rb, field + ".rb");
    if (b.ra > balls[b.a].radius) fail_input(field + ".ra", "exceeds the radius of its node ball");
    if (b.rb > balls[b.b].radius) fail_input(field + ".rb", "exceeds the radius of its node ball");
  }
  FlatLattice f;
  f.balls = std::move(balls);
  f.beams = std::move(beams);
  build_incidence(f);
  return f;
}

}  // namespace steady
