// The Boolean-free B-rep: validity (BRepCheck_Analyzer), one closed shell per component, and its volume
// (BRepGProp) against the exact volume computed here in closed form, independently of the kernel's frustum code.
#include <gtest/gtest.h>
#include <optional>
#include <BRepPrimAPI_MakeSphere.hxx>

#include <random>

#include "steady/lattice/beam_frustum.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "brep/sphere_layout.hpp"
#include "occ_reference.hpp"
#include "test_lattices.hpp"
#include "test_support.hpp"

namespace steady {
namespace {

// Exact volume of a clean lattice: the balls, plus for each beam the frustum between the planes where its cone
// leaves the two node spheres, minus the two spherical caps beyond those planes (which lie inside the balls).
// The exit plane solves x^2 + rho(x)^2 = R^2 with rho(x) = (r - x s) / c the cone radius at distance x from the
// node center (s = sin of the half-angle toward the other end, c = cos), taking the larger root.
double exact_volume(const FlatLattice& f, const std::vector<char>& skip_ball = {}) {
  double v = 0.0;
  for (std::int64_t i = 0; i < f.ball_count(); ++i)
    if (skip_ball.empty() || !skip_ball[i]) v += 4.0 / 3.0 * M_PI * std::pow(f.balls[i].radius, 3);
  for (const FlatBeam& b : f.beams) {
    const Ball &A = f.balls[b.a], &B = f.balls[b.b];
    const double L = glm::length(B.center - A.center);
    if (std::abs(b.ra - b.rb) >= L) continue;  // one end ball contains the other: nothing outside the nodes
    const double s = (b.ra - b.rb) / L, c = std::sqrt(1 - s * s);
    // x^2 + ((r - x s)/c)^2 = R^2  <=>  x^2 - 2 r s x + r^2 - R^2 c^2 = 0
    auto exit_at = [&](double r, double sgn, double R) { return r * sgn * s + std::sqrt(r * r * s * s - r * r + R * R * c * c); };
    const double xa = exit_at(b.ra, 1, A.radius), xb = exit_at(b.rb, -1, B.radius);
    if (xa + xb >= L) continue;
    const double r1 = (b.ra - xa * s) / c, r2 = (b.rb + xb * s) / c, h = L - xa - xb;
    const double ha = A.radius - xa, hb = B.radius - xb;
    v += M_PI * h * (r1 * r1 + r1 * r2 + r2 * r2) / 3.0 - M_PI * ha * ha * (3 * A.radius - ha) / 3.0 -
         M_PI * hb * hb * (3 * B.radius - hb) / 3.0;
  }
  return v;
}

void expect_valid_solid(const TopoDS_Shape& shape, std::int64_t solids, double exact, const std::string& what) {
  ASSERT_FALSE(shape.IsNull()) << what;
  EXPECT_TRUE(is_valid(shape)) << what << ":\n" << validity_report(shape);
  EXPECT_EQ(solid_count(shape), solids) << what;
  const double v = shape_volume(shape);
  EXPECT_NEAR(v / exact, 1.0, 1e-7) << what << ": volume " << v << " exact " << exact;
}

TEST(SphereLayout, RolesAndArcsAreConsistent) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int straddles = 0, poles = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // Random disjoint caps: rejection sampling.
    std::vector<SphereCap> caps;
    const int want = 1 + trial % 14;
    for (int attempt = 0; attempt < 500 && static_cast<int>(caps.size()) < want; ++attempt) {
      const SphereCap c{test::random_unit(rng), std::cos(0.1 + 0.6 * u01(rng))};
      bool ok = true;
      for (const SphereCap& d : caps) {
        const double gap = std::acos(std::clamp(glm::dot(c.direction, d.direction), -1.0, 1.0)) - std::acos(c.exit) -
                           std::acos(d.exit);
        ok = ok && gap > 0.02;
      }
      if (ok) caps.push_back(c);
    }
    const SphereLayout L = layout_sphere(caps, trial % 2 ? SeamPreference::MostCrossings : SeamPreference::FewestCrossings);
    EXPECT_GE(L.margin, kMinimumLayoutMargin);
    for (std::size_t i = 0; i < L.circles.size(); ++i) {
      const CircleLayout& c = L.circles[i];
      // Arcs partition the window; u is continuous along each arc and stays in [0, 2 pi].
      ASSERT_FALSE(c.arcs.empty());
      EXPECT_NEAR(c.arcs.front().t0, c.window, 1e-12);
      EXPECT_NEAR(c.arcs.back().t1, c.window + 2 * M_PI, 1e-12);
      for (const CircleArc& a : c.arcs) {
        double prev[2];
        L.uv(static_cast<int>(i), a.branch, a.t0, prev);
        for (int k = 1; k <= 200; ++k) {
          double uv[2];
          L.uv(static_cast<int>(i), a.branch, a.t0 + (a.t1 - a.t0) * k / 200.0, uv);
          EXPECT_GE(uv[0], -1e-9);
          EXPECT_LE(uv[0], 2 * M_PI + 1e-9);
          EXPECT_LT(std::abs(uv[0] - prev[0]), 3.0) << "u wraps on an arc";
          prev[0] = uv[0];
        }
        // Derivatives against finite differences.
        const double t = 0.5 * (a.t0 + a.t1), h = 1e-6;
        double p[2], m[2], d1[2], d2[2], p2[2], m2[2];
        L.uv(static_cast<int>(i), a.branch, t + h, p);
        L.uv(static_cast<int>(i), a.branch, t - h, m);
        L.uv(static_cast<int>(i), a.branch, t, d1, 1);
        L.uv(static_cast<int>(i), a.branch, t + h, p2, 1);
        L.uv(static_cast<int>(i), a.branch, t - h, m2, 1);
        L.uv(static_cast<int>(i), a.branch, t, d2, 2);
        for (int k = 0; k < 2; ++k) {
          EXPECT_NEAR(d1[k], (p[k] - m[k]) / (2 * h), 1e-5 * (1 + std::abs(d1[k])));
          EXPECT_NEAR(d2[k], (p2[k] - m2[k]) / (2 * h), 1e-4 * (1 + std::abs(d2[k])));
        }
      }
      if (c.role == CircleRole::Straddle) {
        ++straddles;
        // The left arc (u near 0) comes first and rises; the right arc falls (see brep_builder.cpp).
        EXPECT_EQ(c.arcs[0].branch, ArcBranch::Left);
        EXPECT_EQ(c.arcs[1].branch, ArcBranch::Right);
        EXPECT_LT(c.crossing_v[0], c.crossing_v[1]);
      }
      if (c.role == CircleRole::North || c.role == CircleRole::South) ++poles;
    }
  }
  EXPECT_GT(straddles, 10);
  EXPECT_GT(poles, 10);
}

TEST(BrepBuilder, DumbbellAndLoneBall) {
  FlatLattice f = make_flat_lattice({{{0, 0, 0}, 1.0}, {{3, 0.5, 0.2}, 0.8}, {{-5, 1, 2}, 0.7}}, {{0, 1, 0.4, 0.3}});
  const LatticeBrep b = build_lattice_brep(f);
  expect_valid_solid(b.shape, 2, exact_volume(f), "dumbbell and lone ball");
  EXPECT_EQ(face_count(b.shape), 4);
}

TEST(BrepBuilder, CylindricalBeamsAndWideCaps) {
  // Equal end radii give a cylinder; a beam almost as wide as its node gives a cap wider than a hemisphere on the
  // node when the cone widens toward it.
  FlatLattice f = make_flat_lattice({{{2, -2, 0}, 0.5}, {{2, 0, 0}, 0.5}, {{2, 3, 0}, 2.1}},
                                    {{0, 1, 0.3, 0.3}, {1, 2, 0.49, 1.99}});
  const BeamFrustum wide = beam_frustum(f.balls[1], f.balls[2], 0.49, 1.99);
  ASSERT_LT(wide.exit_a, 0.0) << "the exit circle on ball 1 should lie behind its center";
  for (SeamPreference p : {SeamPreference::FewestCrossings, SeamPreference::MostCrossings})
    expect_valid_solid(build_lattice_brep(f, p).shape, 1, exact_volume(f), "cylinder and wide cone");
}

TEST(BrepBuilder, RandomCleanStrutLattices) {
  std::mt19937_64 rng(99);
  for (int trial = 0; trial < 8; ++trial) {
    const test::StepKind kind = test::StepKind(trial % 4);
    const Lattice lat = test::strut_lattice(rng, kind, {3, 3, 2}, 0.2 + 0.05 * (trial % 3));
    const FlatLattice f = flatten(lat);
    // Odd trials put the seams across as many circles as they can: straddling and pole circles.
    const LatticeBrep b = build_lattice_brep(f, trial % 2 ? SeamPreference::MostCrossings : SeamPreference::FewestCrossings);
    expect_valid_solid(b.shape, 1, exact_volume(f), "strut lattice kind " + std::to_string(int(kind)));
    if (trial % 2) EXPECT_GT(b.stats.seam_crossing_circles, 0);
    EXPECT_EQ(face_count(b.shape), f.ball_count() + f.beam_count());
  }
}

TEST(BrepBuilder, BccLatticeSharesHubShapes) {
  std::mt19937_64 rng(3);
  const FlatLattice f = flatten(test::bcc_lattice(rng, {3, 3, 3}));
  const LatticeBrep b = build_lattice_brep(f);
  expect_valid_solid(b.shape, 1, exact_volume(f), "bcc");
  // Translations: corner hubs differ only by which of their 8 beams exist (boundary), centre hubs all alike.
  EXPECT_LT(b.stats.distinct_hubs, 30);
  EXPECT_GT(b.stats.balls, 50);
}

TEST(BrepBuilder, AbsorbedBallsAndDegenerateBeams) {
  // Ball 1 sits inside ball 0 through a degenerate beam; ball 0 has another, normal beam.
  FlatLattice f = make_flat_lattice({{{0, 0, 0}, 1.0}, {{0.3, 0, 0}, 0.5}, {{5, 0, 0}, 1.0}},
                                    {{0, 1, 0.9, 0.4}, {0, 2, 0.3, 0.3}});
  const LatticeBrep b = build_lattice_brep(f);
  expect_valid_solid(b.shape, 1, exact_volume(f, {0, 1, 0}), "absorbed ball");
  EXPECT_EQ(face_count(b.shape), 3);
}

// Two beams crossing at right angles with the same radius r and their axes meeting (a square's diagonals): they
// meet foreign elements, so their four hubs are built as one group. The union of two such cylinders overlaps in a
// Steinmetz solid of volume 16 r^3 / 3, and its intersection curves cross each other where the two cylinders are
// tangent: the hardest contact two beams can have.
TEST(BrepBuilder, CrossingBeamsOfDifferentNodesAreBuiltAsOne) {
  const double r = 0.1;
  const FlatLattice f = make_flat_lattice({{{0, 0, 0}, 0.2}, {{3, 0, 0}, 0.2}, {{3, 3, 0}, 0.2}, {{0, 3, 0}, 0.2}},
                                          {{0, 2, r, r}, {1, 3, r, r}});
  const LatticeBrep b = build_lattice_brep(f);
  expect_valid_solid(b.shape, 1, exact_volume(f) - 16.0 / 3.0 * r * r * r, "crossing beams");
  EXPECT_EQ(b.stats.foreign_groups, 1);
  EXPECT_EQ(b.stats.foreign_hubs, 4);
}

// Foreign contacts of every kind in one lattice, against OpenCASCADE's Fuse of all its balls and beams (the slow,
// obviously right twin): a ball touching a beam of other nodes, two skew beams passing through each other, two
// balls of different nodes overlapping; and a clean part beside them that keeps its own hubs.
TEST(BrepBuilder, ForeignContactsOfEveryKindMatchABruteForceFuse) {
  const FlatLattice f = make_flat_lattice(
      {{{0, 0, 0}, 0.3}, {{4, 0, 0}, 0.3}, {{2, -2, 0.12}, 0.25}, {{2, 2, 0.12}, 0.25},  // skew crossing
       {{2, 0.15, 0.45}, 0.3},                                                               // a lone ball on beam 1
       {{6, 0, 0}, 0.28}, {{6.45, 0.1, 0}, 0.3}, {{6.45, 3, 0}, 0.3},                      // overlapping balls
       {{-3, 0, 0}, 0.3}, {{-3, 3, 0}, 0.3}},                                                // a clean beam
      {{0, 1, 0.15, 0.15}, {2, 3, 0.12, 0.18}, {1, 5, 0.15, 0.15}, {6, 7, 0.15, 0.15}, {8, 9, 0.12, 0.12},
       {0, 8, 0.15, 0.12}});
  const std::optional<TopoDS_Shape> brute = test::occ_lattice_union(f);
  ASSERT_TRUE(brute.has_value());
  const double reference = test::occ_properties(*brute).volume;
  const LatticeBrep b = build_lattice_brep(f);
  ASSERT_TRUE(is_valid(b.shape)) << validity_report(b.shape);
  EXPECT_EQ(solid_count(b.shape), 1);
  EXPECT_NEAR(shape_volume(b.shape) / reference, 1.0, 1e-7) << shape_volume(b.shape) << " against " << reference;
  EXPECT_EQ(b.stats.foreign_hubs, 7) << "the balls of the clean beams at x = -3 keep their own hubs";
  EXPECT_EQ(b.stats.foreign_groups, 2);
}

// A group of any size is built: a row of 300 balls, each overlapping the next (no beams), is one group of 300
// hubs (more than the 256 a group was limited to before its Fuse could be cancelled). One valid solid whose volume
// is the union's in closed form: the balls less 299 lenses pi (4r + d)(2r - d)^2 / 12.
TEST(BrepBuilder, ForeignContactsOverMoreThan256HubsAreBuiltAsOneGroup) {
  const int n = 300;
  const double r = 0.3, d = 0.5;
  std::vector<Ball> balls;
  for (int i = 0; i < n; ++i) balls.push_back({{d * i, 0, 0}, r});
  const FlatLattice f = make_flat_lattice(balls, {});
  const LatticeBrep b = build_lattice_brep(f);
  const double lens = M_PI * (4.0 * r + d) * (2.0 * r - d) * (2.0 * r - d) / 12.0;
  expect_valid_solid(b.shape, 1, exact_volume(f) - (n - 1) * lens, "a row of 300 overlapping balls");
  EXPECT_EQ(b.stats.foreign_groups, 1);
  EXPECT_EQ(b.stats.foreign_hubs, n);
}

}  // namespace
}  // namespace steady
