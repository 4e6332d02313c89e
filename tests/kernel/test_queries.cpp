// Point membership, distance, rays and voxels against brute force over every element of the lattice.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

#include "sample_lattices.hpp"
#include "steady/core/errors.hpp"
#include "steady/query/filtered_lattice.hpp"
#include "steady/query/interference.hpp"
#include "steady/query/queries.hpp"

namespace steady {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

struct Elements {
  std::vector<Ball> balls;
  std::vector<BeamGeometry> beams;
  explicit Elements(const Lattice& lat) {
    lat.for_each_ball([&](std::int64_t, const NodeId&, const Ball& b) { balls.push_back(b); });
    lat.for_each_beam([&](std::int64_t, const BeamId&, const BeamGeometry& g) { beams.push_back(g); });
  }
  double distance(const Vec3& p) const {
    double d = kInf;
    for (const Ball& b : balls) d = std::min(d, distance_to_ball(p, b));
    for (const BeamGeometry& g : beams) d = std::min(d, distance_to_beam(p, g));
    return std::max(0.0, d);
  }
  double ray(const Vec3& o, const Vec3& dir) const {
    double t = kInf;
    for (const Ball& b : balls) t = std::min(t, ray_enters_ball(o, dir, b));
    for (const BeamGeometry& g : beams) t = std::min(t, ray_enters_beam(o, dir, g));
    return t;
  }
};

std::vector<Vec3> sample_points(const Lattice& lat, const Ball& bound, std::mt19937_64& rng, int n) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i) {
    if (i % 3 == 0 || lat.ball_count() == 0) {
      pts.push_back(bound.center + test::random_vec(rng, bound.radius));
    } else {
      const Ball e = lat.ball(lat.ball_id(static_cast<std::int64_t>(u01(rng) * lat.ball_count())));
      pts.push_back(e.center + test::random_vec(rng, 3.0 * e.radius));
    }
  }
  return pts;
}

std::vector<Lattice> lattices(std::mt19937_64& rng) {
  std::vector<Lattice> out = {test::regular_bcc({4, 3, 5}), test::cylindrical_bcc({3, 12, 4}),
                              test::bent_twisted_tapered({5, 4, 6}), test::sheared_cubic({4, 4, 3})};
  for (int l = 0; l < 40; ++l) out.push_back(test::random_lattice(rng, l));
  return out;
}

TEST(Queries, ContainsAndDistanceMatchBruteForce) {
  std::mt19937_64 rng(8);
  long points = 0, inside = 0;
  for (const Lattice& lat : lattices(rng)) {
    const LatticeQuery lq(lat);
    const LatticeSource src(lq);
    const Elements all(lat);
    const std::vector<Vec3> pts = sample_points(lat, lq.bound(), rng, 300);
    std::vector<std::uint8_t> in(pts.size());
    std::vector<double> dist(pts.size()), far(pts.size());
    contains(src, &pts[0].x, pts.size(), in.data());
    const double bound = 0.5 * lq.bound().radius;
    distance(src, &pts[0].x, pts.size(), bound, dist.data());
    distance(src, &pts[0].x, pts.size(), 1e300, far.data());
    for (std::size_t i = 0; i < pts.size(); ++i) {
      const double d = all.distance(pts[i]);
      ++points;
      inside += d == 0.0;
      EXPECT_EQ(in[i] != 0, d == 0.0) << i;
      EXPECT_NEAR(far[i], d, 1e-12 * (1 + d));
      if (d <= bound)
        EXPECT_NEAR(dist[i], d, 1e-12 * (1 + d));
      else
        EXPECT_EQ(dist[i], kInf);
    }
  }
  EXPECT_GT(inside, 1000);
  std::printf("[ queries ] %ld points, %ld inside\n", points, inside);
}

// Far from the lattice the search visits nearer blocks first and prunes by the best distance so far (it used
// to grow a query ball until it held a large part of the lattice: 28 s for one point 250 cells from a 300^3
// lattice). The answers must stay exact, also beyond the lattice's bounding ball and for a lattice whose
// filter keeps nothing.
TEST(Queries, FarPointsAndEmptyLatticesGetTheirDistance) {
  std::mt19937_64 rng(81);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<Lattice> lats = {test::bent_twisted_tapered({40, 40, 40}), test::cylindrical_bcc({6, 24, 10})};
  for (int l = 0; l < 10; ++l) lats.push_back(test::random_lattice(rng, 100 + l));
  long points = 0;
  for (const Lattice& lat : lats) {
    const LatticeQuery lq(lat);
    const LatticeSource src(lq);
    const Elements all(lat);
    for (int q = 0; q < 20; ++q) {
      const Vec3 p = lq.bound().center + test::random_unit(rng) * lq.bound().radius * (1.0 + 40.0 * u01(rng) * u01(rng));
      double d = 0.0;
      distance(src, &p.x, 1, kInf, &d);
      const double truth = all.distance(p);
      EXPECT_NEAR(d, truth, 1e-12 * (1 + truth));
      double bounded = 0.0;
      distance(src, &p.x, 1, 0.99 * truth, &bounded);
      EXPECT_EQ(bounded, kInf);
      ++points;
    }
  }
  // A filter that keeps no node: every distance is infinite, whatever the bound.
  const FilteredLattice none(test::regular_bcc({4, 4, 4}), negate(index_stencil({1}, 1, 1, 1)));
  const Vec3 p(0.3, 0.2, 0.1);
  double d = 0.0;
  distance(none, &p.x, 1, kInf, &d);
  EXPECT_EQ(d, kInf);
  std::printf("[ queries ] %ld far points\n", points);
}

TEST(Queries, RaysMatchBruteForce) {
  std::mt19937_64 rng(9);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  long rays = 0, hits = 0;
  for (const Lattice& lat : lattices(rng)) {
    const LatticeQuery lq(lat);
    const LatticeSource src(lq);
    const Elements all(lat);
    const Ball b = lq.bound();
    std::vector<Vec3> o, d;
    for (int r = 0; r < 100; ++r) {
      // From outside and from inside the bound, toward an element or anywhere.
      o.push_back(b.center + test::random_unit(rng) * (b.radius * (r % 2 ? 1.5 : 0.5 * u01(rng))));
      Vec3 target = b.center + test::random_vec(rng, b.radius);
      if (r % 3 != 0 && lat.ball_count() > 0) target = lat.ball(lat.ball_id(static_cast<std::int64_t>(u01(rng) * lat.ball_count()))).center;
      d.push_back((target - o.back()) * (0.5 + u01(rng)));
    }
    std::vector<double> t(o.size()), t_short(o.size());
    raycast(src, &o[0].x, &d[0].x, o.size(), kInf, t.data());
    raycast(src, &o[0].x, &d[0].x, o.size(), 0.3 * b.radius, t_short.data());
    for (std::size_t i = 0; i < o.size(); ++i) {
      const double expect = all.ray(o[i], glm::normalize(d[i]));
      ++rays;
      if (expect == kInf) {
        EXPECT_EQ(t[i], kInf);
      } else {
        ++hits;
        EXPECT_NEAR(t[i], expect, 1e-9 * (1 + expect));
      }
      if (expect <= 0.3 * b.radius * (1 - 1e-9)) EXPECT_NEAR(t_short[i], expect, 1e-9 * (1 + expect));
      if (expect > 0.3 * b.radius * (1 + 1e-9)) EXPECT_EQ(t_short[i], kInf);
    }
  }
  EXPECT_GT(hits, 1500);
  std::printf("[ queries ] %ld rays, %ld hits\n", rays, hits);
}

TEST(Queries, VoxelsArePointMembershipAtCenters) {
  const Lattice lat = test::regular_bcc({3, 3, 2});
  const LatticeQuery lq(lat);
  const LatticeSource src(lq);
  const Vec3 lo(-0.2, -0.2, -0.2), hi(2.2, 2.2, 1.2);
  const std::int64_t shape[3] = {17, 13, 11};
  std::vector<std::uint8_t> vox(17 * 13 * 11);
  voxelize(src, lo, hi, shape, vox.data());
  const Elements all(lat);
  int filled = 0;
  for (int x = 0; x < 17; ++x)
    for (int y = 0; y < 13; ++y)
      for (int z = 0; z < 11; ++z) {
        const Vec3 p = lo + (Vec3(x, y, z) + 0.5) * (hi - lo) / Vec3(17, 13, 11);
        EXPECT_EQ(vox[(x * 13 + y) * 11 + z] != 0, all.distance(p) == 0.0);
        filled += vox[(x * 13 + y) * 11 + z];
      }
  EXPECT_GT(filled, 20);
}

TEST(Queries, BadInput) {
  const Lattice lat = test::regular_bcc({2, 2, 2});
  const LatticeQuery lq(lat);
  const LatticeSource src(lq);
  const double nan = std::nan("");
  double p[3] = {0, nan, 0}, d[3] = {0, 0, 0}, out[1];
  std::uint8_t in[1];
  EXPECT_THROW(contains(src, p, 1, in), InvalidInput);
  p[1] = 0;
  EXPECT_THROW(distance(src, p, 1, -1.0, out), InvalidInput);
  EXPECT_THROW(raycast(src, p, d, 1, kInf, out), InvalidInput);
  const std::int64_t bad_shape[3] = {2, 0, 2};
  std::uint8_t v[8];
  EXPECT_THROW(voxelize(src, Vec3(0), Vec3(1), bad_shape, v), InvalidInput);
  const std::int64_t shape[3] = {2, 2, 2};
  EXPECT_THROW(voxelize(src, Vec3(1), Vec3(0), shape, v), InvalidInput);
}

}  // namespace
}  // namespace steady
