// The planar COTS map against the oracles of spec/cots-maps.md section 17 (numbers checked there in double
// precision), against numerical references (quadrature, finite differences) and over random quads.
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <random>
#include <string>

#include "cots_test_support.hpp"
#include "steady/core/errors.hpp"
#include "steady/cots/cots_map.hpp"

namespace {

using steady::CotsMap;
using steady::CotsPreimage;
using steady::InvalidInput;
using steady::ParameterBox;
using steady::Vec2;
using Complex = std::complex<double>;
using cots_test::kPi;

Complex cx(const Vec2& p) { return {p.x, p.y}; }
double dist(const Vec2& p, const Vec2& q) { return glm::length(p - q); }

// Standard case P1 of the spec.
const Vec2 kA{0.0, 0.0}, kB{0.1, 1.0}, kC{1.3, 1.2}, kD{1.0, 0.0};

// The smallest distance from (x, y) to the pre-images of M(x, y): 0 when the round trip is exact.
double round_trip_error(const CotsMap& m, double x, double y) {
  double best = INFINITY;
  for (const CotsPreimage& p : m.inverse(m.map(x, y))) best = std::min(best, dist(p.uv, {x, y}));
  return best;
}

// Signed area by Gauss-Legendre quadrature of the Jacobian, the derivatives by finite differences of map().
double numerical_area(const CotsMap& m, double x0 = 0.0, double x1 = 1.0, double y0 = 0.0, double y1 = 1.0) {
  const double speed = std::max({1.0, std::abs(m.log_u()), std::abs(m.log_v())});
  const double h = 1e-3 / speed;
  return (x1 - x0) * (y1 - y0) * cots_test::integrate_square([&](double s, double t) {
           const double x = x0 + s * (x1 - x0), y = y0 + t * (y1 - y0);
           const Vec2 mx = cots_test::derivative<Vec2>([&](double u) { return m.map(u, y); }, x, h);
           const Vec2 my = cots_test::derivative<Vec2>([&](double v) { return m.map(x, v); }, y, h);
           return mx.x * my.y - mx.y * my.x;
         });
}

TEST(CotsMap, P1CornersFixedPointAndMultipliers) {
  const CotsMap m(kA, kB, kC, kD);
  EXPECT_LT(dist(m.map(0, 0), kA), 1e-14);
  EXPECT_LT(dist(m.map(0, 1), kB), 1e-14);
  EXPECT_LT(dist(m.map(1, 1), kC), 1e-14);
  EXPECT_LT(dist(m.map(1, 0), kD), 1e-14);
  ASSERT_TRUE(m.fixed_point().has_value());
  EXPECT_LT(dist(*m.fixed_point(), {-2.75, -2.25}), 1e-14);
  const Complex u = std::exp(m.log_u()), v = std::exp(m.log_v());
  EXPECT_LT(std::abs(u - Complex(1.2178217821782178, -0.1782178217821783)), 1e-15);
  EXPECT_LT(std::abs(v - Complex(1.2, 0.2)), 1e-15);
  EXPECT_NEAR(std::abs(u), 1.2307930309960788, 1e-15);
  EXPECT_NEAR(m.log_u().imag(), -0.14531001063570217, 1e-15);
  EXPECT_NEAR(std::abs(v), 1.2165525060596438, 1e-15);
  EXPECT_NEAR(m.log_v().imag(), 0.1651486774146268, 1e-15);
  EXPECT_NEAR(m.determinant(), 0.06277838000663953, 1e-15);
  // Label-swap regression (erratum 2): the paper's literal labels put V's multiplier on x, which reaches b at (1,0).
  const Complex f = cx(*m.fixed_point());
  EXPECT_LT(std::abs(f + std::exp(m.log_v()) * (cx(kA) - f) - cx(kB)), 1e-14);
  EXPECT_GT(dist(m.map(1, 0), kB), 0.5);
}

TEST(CotsMap, FixedPointInvariancesAndCorrectedEquation8) {
  const Vec2 f = *CotsMap(kA, kB, kC, kD).fixed_point();
  EXPECT_LT(dist(*CotsMap(kB, kC, kD, kA).fixed_point(), f), 1e-13);  // cyclic
  EXPECT_LT(dist(*CotsMap(kA, kD, kC, kB).fixed_point(), f), 1e-13);  // opposite corners swapped
  const Vec2 swapped = *CotsMap(kB, kA, kC, kD).fixed_point();      // consecutive corners swapped: f moves
  EXPECT_NEAR(swapped.x, 0.5392, 1e-4);
  EXPECT_NEAR(swapped.y, 0.5844, 1e-4);
  // Eq. 8 corrected: f = a + <w.p, w x p>/|w|^2, w = (lambda cos alpha - 1, lambda sin alpha), p = a - d.
  const CotsMap m(kA, kB, kC, kD);
  const double lambda = std::exp(m.log_u().real()), alpha = m.log_u().imag();
  const Vec2 w{lambda * std::cos(alpha) - 1.0, lambda * std::sin(alpha)}, p = kA - kD;
  const Vec2 eq8 = kA + Vec2(glm::dot(w, p), w.x * p.y - w.y * p.x) / glm::dot(w, w);
  EXPECT_LT(dist(eq8, f), 1e-13);
}

TEST(CotsMap, P1ValuesTranSimilarityAndBorders) {
  const CotsMap m(kA, kB, kC, kD);
  EXPECT_LT(dist(m.map(0.5, 0.5), {0.5875679672498948, 0.5364601084552767}), 1e-15);
  EXPECT_LT(dist(m.map(0.25, 0.75), {0.3524276879323667, 0.7780330587143229}), 1e-15);
  EXPECT_LT(dist(m.map(0.5, 0.0), {0.4740317939131349, 0.01812279388986049}), 1e-15);
  // TS identity (oracle 9): M(x + t x', y + t y') = f + exp(t (x' Lu + y' Lv)) (M(x, y) - f).
  const Complex f = cx(*m.fixed_point());
  const double x = 0.2, y = 0.3, xp = 0.5, yp = -0.25, t = 0.7;
  const Complex ts = f + std::exp(t * (xp * m.log_u() + yp * m.log_v())) * (cx(m.map(x, y)) - f);
  EXPECT_LT(std::abs(cx(m.map(x + t * xp, y + t * yp)) - ts), 2e-15);
  // ... and through the similarity objects: U^x' V^y' moves M(x, y) to M(x + x', y + y').
  EXPECT_LT(dist(m.field(xp, yp).apply(m.map(x, y)), m.map(x + xp, y + yp)), 1e-15);
  EXPECT_LT(dist(m.u_similarity().apply(kA), kD), 1e-15);
  EXPECT_LT(dist(m.u_similarity().apply(kB), kC), 1e-15);
  EXPECT_LT(dist(m.v_similarity().apply(kA), kB), 1e-15);
  EXPECT_LT(dist(m.v_similarity().apply(kD), kC), 1e-15);
  // Log-spiral border (oracle 11): |M(x,0) - f| / |a - f| = lambda_u^x, angle grows by x alpha_u.
  EXPECT_NEAR(std::abs(cx(kA) - f), 3.5531676008879747, 1e-14);
  for (double s : {0.1, 0.37, 0.8}) {
    const Complex r = (cx(m.map(s, 0.0)) - f) / (cx(kA) - f);
    EXPECT_NEAR(std::abs(r), std::exp(s * m.log_u().real()), 1e-15);
    EXPECT_NEAR(std::arg(r), s * m.log_u().imag(), 1e-15);
  }
  // Tile angle (oracle 10): arg(Lv/Lu) at the (i,j) corner of every tile, measured from the isocurves' tangents.
  EXPECT_NEAR(m.tile_angle() * 180.0 / kPi, 75.09685994663232, 1e-12);
  for (auto [x0, y0] : {std::pair{0.0, 0.0}, std::pair{0.5, 0.25}, std::pair{0.75, 0.75}}) {
    const auto dm = m.derivatives(x0, y0);
    EXPECT_NEAR(std::arg(cx(dm[1]) / cx(dm[0])), m.tile_angle(), 1e-14);
  }
}

TEST(CotsMap, TilesAreSimilarCopiesOfTheFirst) {
  const CotsMap m(kA, kB, kC, kD);
  const int n = 4;
  auto corner = [&](int i, int j, int c) {
    const int di[4] = {0, 0, 1, 1}, dj[4] = {0, 1, 1, 0};
    return m.map(double(i + di[c]) / n, double(j + dj[c]) / n);
  };
  double worst = 0.0;
  for (auto [i, j] : {std::pair{1, 0}, std::pair{2, 3}, std::pair{3, 3}, std::pair{0, 2}}) {
    const auto s = m.tile_similarity(i, j, n, n);
    for (int c = 0; c < 4; ++c) worst = std::max(worst, dist(s.apply(corner(0, 0, c)), corner(i, j, c)));
    // inner points too: M((i + s)/n, (j + t)/n) = S_ij M(s/n, t/n)
    worst = std::max(worst, dist(s.apply(m.map(0.3 / n, 0.8 / n)), m.map((i + 0.3) / n, (j + 0.8) / n)));
  }
  EXPECT_LT(worst, 2e-15);
  cots_test::report("P1 tile similarity, largest corner error", worst);
}

TEST(CotsMap, P1AreasInClosedFormMatchNumericalOnes) {
  const CotsMap m(kA, kB, kC, kD);
  EXPECT_NEAR(m.area(), 1.2029619035875445, 1e-14);
  EXPECT_NEAR(m.tile_area(0, 0, 4, 4), 0.054842766786164246, 1e-15);
  EXPECT_NEAR(m.area() / m.tile_area(0, 0, 4, 4), 21.934741335680172, 1e-12);
  // The corrected geometric sums (erratum 3: lambda^2 - 1, not lambda^{2n} - 1).
  const double qu = std::exp(2.0 * m.log_u().real()), qv = std::exp(2.0 * m.log_v().real());
  const double tac = (qu - 1.0) / (std::pow(qu, 0.25) - 1.0) * (qv - 1.0) / (std::pow(qv, 0.25) - 1.0);
  EXPECT_NEAR(tac, 21.934741335680172, 1e-12);
  EXPECT_NEAR(numerical_area(m), m.area(), 1e-12);
  EXPECT_NEAR(numerical_area(m, 0.0, 0.25, 0.0, 0.25), m.tile_area(0, 0, 4, 4), 1e-13);
  double sum = 0.0;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) sum += m.tile_area(i, j, 4, 4);
  EXPECT_NEAR(sum, m.area(), 1e-14);
}

TEST(CotsMap, P1MatrixOfDisksTotalAreaAndCentroid) {
  // Oracles 15 and 16: disks at M((i + .5)/n, (j + .5)/n), n = 5, each the similar copy of the template disk.
  const CotsMap m(kA, kB, kC, kD);
  const int n = 5;
  const Vec2 c0 = m.map(0.1, 0.1);
  const double r0 = 0.3 * dist(m.map(0.2, 0.0), kA);
  EXPECT_LT(dist(c0, {0.10862984222853544, 0.09836189039960397}), 1e-15);
  EXPECT_NEAR(r0, 0.055168917304841955, 1e-15);
  double total = 0.0;
  Vec2 moment{0.0};
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const auto s = m.tile_similarity(i, j, n, n);
      const Vec2 c = s.apply(c0);
      EXPECT_LT(dist(c, m.map((i + 0.5) / n, (j + 0.5) / n)), 1e-15);
      const double area = kPi * r0 * r0 * s.scale() * s.scale();
      total += area;
      moment += area * c;
    }
  EXPECT_NEAR(total, 0.33449522352684197, 1e-14);
  EXPECT_LT(dist(moment / total, {0.6342557519680101, 0.5784870021543567}), 1e-14);
  // s r / t: template area times area(R) / area(T_00).
  EXPECT_NEAR(kPi * r0 * r0 * m.area() / m.tile_area(0, 0, n, n), total, 1e-14);
}

TEST(CotsMap, P1RoundTripsAndTileLookup) {
  const CotsMap m(kA, kB, kC, kD);
  for (auto [x, y] : {std::pair{0.3, 0.7}, std::pair{0.5, 0.5}, std::pair{0.9, 0.1}, std::pair{0.0, 1.0},
                      std::pair{1.0, 1.0}, std::pair{1.0, 0.0}}) {
    const auto found = m.inverse(m.map(x, y));
    ASSERT_EQ(found.size(), 1u) << x << " " << y;
    EXPECT_EQ(found[0].branch, 0);
    EXPECT_LT(dist(found[0].uv, {x, y}), 1e-14);
  }
  // Outside the range: no pre-image in [0,1]^2, but one in a box that extends the map.
  const Vec2 outside = m.map(1.3, -0.2);
  EXPECT_TRUE(m.inverse(outside).empty());
  const auto extended = m.inverse(outside, ParameterBox{-1.0, 2.0, -1.0, 2.0});
  ASSERT_EQ(extended.size(), 1u);
  EXPECT_LT(dist(extended[0].uv, {1.3, -0.2}), 1e-14);
  EXPECT_TRUE(m.inverse(*m.fixed_point()).empty());
  const auto tiles = m.tiles_of(m.map(0.55, 0.95), 4, 5);
  ASSERT_EQ(tiles.size(), 1u);
  EXPECT_EQ(tiles[0][0], 2);
  EXPECT_EQ(tiles[0][1], 4);
  const auto corner_tile = m.tiles_of(kC, 4, 5);  // x = y = 1 belongs to the last tile
  ASSERT_EQ(corner_tile.size(), 1u);
  EXPECT_EQ(corner_tile[0][0], 3);
  EXPECT_EQ(corner_tile[0][1], 4);
}

TEST(CotsMap, BranchCaseNeedsTheNextTurn) {
  // Oracle 18: f = 0, a = 1, Lu = 0.1 + 2.5i, Lv = 0.3 + 0.8i.
  const CotsMap spiral = CotsMap::from_spiral({1, 0}, {0, 0}, {0.1, 2.5}, {0.3, 0.8});
  EXPECT_LT(dist(spiral.b(), {0.9404556879095657, 0.9683294374690128}), 1e-15);
  EXPECT_LT(dist(spiral.c(), {-1.4731467091711636, -0.23532892246946358}), 1e-15);
  EXPECT_LT(dist(spiral.d(), {-0.8854006251044485, 0.661414008942071}), 1e-15);
  const CotsMap m(spiral.a(), spiral.b(), spiral.c(), spiral.d());  // rebuilt from its corners, principal branches
  EXPECT_LT(std::abs(m.log_u() - Complex(0.1, 2.5)), 1e-14);
  EXPECT_LT(std::abs(m.log_v() - Complex(0.3, 0.8)), 1e-14);
  EXPECT_LT(glm::length(*m.fixed_point()), 1e-14);
  EXPECT_NEAR(m.determinant(), -0.67, 1e-14);
  const Vec2 q = m.map(0.95, 1.0);
  EXPECT_LT(dist(q, {-1.4835559438781272, -0.049580113350173795}), 1e-15);
  EXPECT_NEAR(std::arg(cx(q)), -3.1082, 1e-4);
  const auto found = m.inverse(q);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].branch, 1);
  EXPECT_LT(dist(found[0].uv, {0.95, 1.0}), 1e-14);
}

TEST(CotsMap, SelfOverlapHasTwoPreimagesAndTwoTiles) {
  // Oracle 19: Lu = 0.15 + 7i winds past a full turn (branch_u = 1 from the corners).
  const CotsMap spiral = CotsMap::from_spiral({1, 0}, {0, 0}, {0.15, 7.0}, {0.5, 1.0});
  const CotsMap m(spiral.a(), spiral.b(), spiral.c(), spiral.d(), 1, 0);
  EXPECT_LT(std::abs(m.log_u() - Complex(0.15, 7.0)), 1e-14);
  EXPECT_NEAR(m.determinant(), -3.35, 1e-14);
  const auto found = m.inverse(m.map(0.95, 0.3));
  ASSERT_EQ(found.size(), 2u);
  EXPECT_EQ(found[0].branch, 0);
  EXPECT_NEAR(found[0].uv.x, 0.012211148, 1e-9);
  EXPECT_NEAR(found[0].uv.y, 0.581336656, 1e-9);
  EXPECT_EQ(found[1].branch, 1);
  EXPECT_LT(dist(found[1].uv, {0.95, 0.3}), 1e-14);
  for (const auto& p : found) EXPECT_LT(dist(m.map(p.uv), m.map(0.95, 0.3)), 1e-14);
  EXPECT_EQ(m.tiles_of(m.map(0.95, 0.3), 4, 4).size(), 2u);
  // The area counts the overlap twice: closed form against quadrature.
  EXPECT_NEAR(numerical_area(m), m.area(), 1e-10 * std::abs(m.area()));
}

TEST(CotsMap, SymmetricKiteAndRightAngleMaps) {
  // Oracle 20: a = 0, d = 1 + 0.4i, b = conj(d), c = 1.6: f = 2.9 on the line ac, Lv = conj(Lu).
  const CotsMap kite({0, 0}, {1, -0.4}, {1.6, 0}, {1, 0.4});
  EXPECT_LT(dist(*kite.fixed_point(), {2.9, 0.0}), 1e-14);
  EXPECT_LT(std::abs(kite.log_v() - std::conj(kite.log_u())), 1e-15);
  EXPECT_NEAR(kite.log_u().real(), -0.40117323626246865, 1e-15);
  EXPECT_NEAR(std::abs(kite.log_u().imag()), 0.20749622643520263, 1e-15);
  // Oracle 21: f = 0, a = 1, Lu = 0.3 (1 + i), Lv = conj(Lu): right angles, and conformal (symmetric).
  const CotsMap right = CotsMap::from_spiral({1, 0}, {0, 0}, {0.3, 0.3}, {0.3, -0.3});
  EXPECT_LT(dist(right.b(), {1.2895693740449359, -0.39891055377848983}), 1e-15);
  EXPECT_LT(dist(right.c(), {1.8221188003905089, 0.0}), 1e-15);
  EXPECT_LT(dist(right.d(), {1.2895693740449359, 0.39891055377848983}), 1e-15);
  EXPECT_NEAR(std::abs(right.tile_angle()), kPi / 2, 1e-15);
  auto diagonal_angle = [](const CotsMap& m) {  // angle at which the images of the square's diagonals cross
    const double h = 1e-4;
    const Vec2 d1 = cots_test::derivative<Vec2>([&](double t) { return m.map(t, t); }, 0.5, h);
    const Vec2 d2 = cots_test::derivative<Vec2>([&](double t) { return m.map(t, 1.0 - t); }, 0.5, h);
    return std::abs(std::arg(cx(d2) / cx(d1))) * 180.0 / kPi;
  };
  EXPECT_NEAR(diagonal_angle(right), 90.0, 1e-8);
  // Right-angle but not symmetric (Lv = 2i Lu): still right-angled tiles, not conformal.
  const Complex lu(0.3, 0.3);
  const CotsMap skew = CotsMap::from_spiral({1, 0}, {0, 0}, lu, Complex(0, 2) * lu);
  EXPECT_NEAR(std::abs(skew.tile_angle()), kPi / 2, 1e-15);
  EXPECT_NEAR(diagonal_angle(skew), 126.87, 0.01);
}

TEST(CotsMap, ParallelogramIsTheAffineMap) {
  const Vec2 a{0.25, -0.125}, b{0.5, 1.0}, d{1.5, 0.25};  // dyadic: a - b + c - d is exactly 0
  const Vec2 c = b + d - a;
  const CotsMap m(a, b, c, d);
  ASSERT_TRUE(m.is_affine());
  EXPECT_FALSE(m.fixed_point().has_value());
  EXPECT_EQ(m.log_u(), Complex(0.0));
  EXPECT_LT(dist(m.map(0.3, 0.6), a + 0.3 * (d - a) + 0.6 * (b - a)), 1e-15);
  const auto found = m.inverse(m.map(0.3, 0.6));
  ASSERT_EQ(found.size(), 1u);
  EXPECT_LT(dist(found[0].uv, {0.3, 0.6}), 1e-15);
  const double cross = (d - a).x * (b - a).y - (d - a).y * (b - a).x;
  EXPECT_NEAR(m.area(), cross, 1e-15);
  EXPECT_NEAR(m.tile_area(2, 1, 3, 4), cross / 12.0, 1e-15);
  EXPECT_EQ(m.u_similarity().kind(), steady::Similarity2Kind::Translation);
  EXPECT_LT(dist(m.tile_similarity(1, 2, 3, 4).apply(a), m.map(1.0 / 3, 0.5)), 1e-15);
  EXPECT_THROW(CotsMap(a, b, c, d, 1, 0), InvalidInput);  // translations have no windings
}

TEST(CotsMap, NearParallelogramsAreContinuousWithTheAffineMap) {
  // Oracle 17: c = (1.1, 1) + eps (1, 2), b = (0.1, 1); the f-based formula loses ~1e-4 at eps = 1e-12.
  const Vec2 a{0, 0}, b{0.1, 1}, d{1, 0};
  double worst_inverse = 0.0;
  for (double eps : {1e-15, 1e-12, 1e-9, 1e-6, 1e-3}) {
    const Vec2 c = Vec2(1.1, 1.0) + eps * Vec2(1, 2);
    const CotsMap m(a, b, c, d);
    double worst = 0.0;
    for (double x : {0.0, 0.3, 0.7, 1.0})
      for (double y : {0.0, 0.45, 1.0}) {
        worst = std::max(worst, dist(m.map(x, y), a + x * (d - a) + y * (b - a)));
        worst_inverse = std::max(worst_inverse, round_trip_error(m, x, y));
      }
    EXPECT_LT(worst, 3.0 * eps + 1e-15) << eps;  // ||COTS_eps - affine|| = O(eps)
    EXPECT_NEAR(m.area(), numerical_area(m), 1e-12);
  }
  EXPECT_LT(worst_inverse, 1e-10);
  cots_test::report("near-parallelogram round trip, largest error", worst_inverse);
}

TEST(CotsMap, TrapezoidAndEqualOppositeSides) {
  // Trapezoid (ab parallel to dc, |ab| != |dc|): U is a pure dilation about the apex of the legs ad and bc.
  const CotsMap trap({0, 0}, {0, 1}, {2, 1.5}, {2, -0.5});
  EXPECT_NEAR(trap.log_u().imag(), 0.0, 1e-15);
  EXPECT_EQ(trap.u_similarity().kind(), steady::Similarity2Kind::Dilation);
  const Vec2 f = *trap.fixed_point();
  const auto on_line = [](Vec2 p, Vec2 q, Vec2 r) { return (q - p).x * (r - p).y - (q - p).y * (r - p).x; };
  EXPECT_NEAR(on_line({0, 0}, {2, -0.5}, f), 0.0, 1e-13);
  EXPECT_NEAR(on_line({0, 1}, {2, 1.5}, f), 0.0, 1e-13);
  EXPECT_LT(round_trip_error(trap, 0.4, 0.6), 1e-14);
  EXPECT_NEAR(trap.area(), numerical_area(trap), 1e-12);
  // |ab| = |dc|: U is a pure rotation (ln lambda_u = 0); the tile areas along x are equal.
  const Vec2 d{1.0, 0.3};
  const CotsMap rot({0, 0}, {0, 1}, d + Vec2(std::sin(0.3), std::cos(0.3)), d);
  EXPECT_NEAR(rot.log_u().real(), 0.0, 1e-15);
  EXPECT_EQ(rot.u_similarity().kind(), steady::Similarity2Kind::Rotation);
  EXPECT_NEAR(rot.tile_area(0, 1, 3, 3), rot.tile_area(2, 1, 3, 3), 1e-15);
  EXPECT_LT(round_trip_error(rot, 0.25, 0.5), 1e-14);
  EXPECT_NEAR(rot.area(), numerical_area(rot), 1e-12);
}

TEST(CotsMap, FoldedQuadsGiveAMapThatNeverFolds) {
  // A self-crossing (bow-tie) corner quad: the bilinear map would fold; the COTS map keeps one Jacobian sign.
  const CotsMap m({0, 0}, {1.2, 1}, {0, 1.3}, {1, 0});
  EXPECT_LT(dist(m.map(1, 1), {0, 1.3}), 1e-15);
  int positive = 0, negative = 0;
  for (int i = 0; i <= 10; ++i)
    for (int j = 0; j <= 10; ++j) {
      const auto dm = m.derivatives(i / 10.0, j / 10.0);
      (dm[0].x * dm[1].y - dm[0].y * dm[1].x > 0 ? positive : negative)++;
    }
  EXPECT_TRUE(positive == 0 || negative == 0);
  EXPECT_EQ(positive > 0 ? 1 : -1, m.orientation());
  EXPECT_LT(round_trip_error(m, 0.3, 0.8), 1e-13);
  EXPECT_NEAR(m.area(), numerical_area(m), 1e-12);
}

TEST(CotsMap, BranchesFromCornersRecoverWoundSpirals) {
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  double worst = 0.0;
  for (int trial = 0; trial < 300; ++trial) {
    const int ku = trial % 5 - 2, kv = (trial / 5) % 3 - 1;  // windings -2..2 and -1..1
    const Complex lu(0.4 * unit(rng), 2 * kPi * ku + 0.9 * kPi * unit(rng));
    const Complex lv(0.4 * unit(rng), 2 * kPi * kv + 0.9 * kPi * unit(rng));
    std::optional<CotsMap> spiral;
    try {
      spiral = CotsMap::from_spiral({unit(rng), unit(rng)}, {unit(rng), unit(rng)}, lu, lv);
    } catch (const InvalidInput&) {
      continue;
    }
    const CotsMap m(spiral->a(), spiral->b(), spiral->c(), spiral->d(), ku, kv);
    worst = std::max({worst, std::abs(m.log_u() - lu), std::abs(m.log_v() - lv),
                      dist(m.map(0.4, 0.7), spiral->map(0.4, 0.7))});
  }
  EXPECT_LT(worst, 1e-12);
}

TEST(CotsMap, BadInputNamesTheCorners) {
  const double nan = std::nan("");
  EXPECT_NE(cots_test::message_of([&] { CotsMap({nan, 0}, kB, kC, kD); }).find("corner a"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { CotsMap(kA, kB, kC, {1, INFINITY}); }).find("corner d"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { CotsMap(kA, kA, kC, kD); }).find("corners a, b"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { CotsMap(kA, kB, kC, kC); }).find("corners c, d"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { CotsMap(kA, kA, kA, kA); }).find("same point"), std::string::npos);
  // Collinear corners: a flat parallelogram and a flat spiral quad collapse to a curve.
  const std::string flat = cots_test::message_of([&] { CotsMap({0, 0}, {1, 1}, {3, 3}, {2, 2}); });
  EXPECT_NE(flat.find("corners a, b, c, d"), std::string::npos) << flat;
  EXPECT_NE(flat.find("collapses to a curve"), std::string::npos) << flat;
  EXPECT_NE(cots_test::message_of([&] { CotsMap({0, 0}, {1, 0}, {3, 0}, {2, 0}); }).find("collapses"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { CotsMap::from_spiral({1, 0}, {0, 0}, {0.2, 0.1}, {0.4, 0.2}); }).find("collapses"),
            std::string::npos);
  // A full turn of U brings d back onto a (and c onto b).
  EXPECT_NE(cots_test::message_of([&] { CotsMap::from_spiral({1, 0}, {0, 0}, {0.0, 2 * kPi}, {0.4, 0.2}); }).find("coincide"),
            std::string::npos);
  // The symmetric bow-tie is two quarter and half turns about one centre: its range is an arc.
  EXPECT_NE(cots_test::message_of([&] { CotsMap({0, 0}, {1, 1}, {0, 1}, {1, 0}); }).find("collapses"), std::string::npos);
  const CotsMap m(kA, kB, kC, kD);
  EXPECT_THROW(m.inverse({nan, 0.0}), InvalidInput);
  EXPECT_THROW(m.tiles_of({0.5, 0.5}, 0, 3), InvalidInput);
  EXPECT_THROW(CotsMap(kA, kB, kC, kD, 1 << 30, 0), InvalidInput);
}

// Random maps: corners in the unit square (any quad the constructor accepts, self-crossing ones included) with
// windings in -1..1, and spirals with large windings (ranges that overlap themselves several times).
TEST(CotsMap, RandomQuadsRoundTripAndMatchTheirAreas) {
  std::mt19937_64 rng(20261125);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), param(0.0, 1.0);
  std::uniform_int_distribution<int> branch(-1, 1);
  int maps = 0, refused = 0, points = 0, overlapping_points = 0;
  double worst_trip = 0.0, worst_image = 0.0, worst_area = 0.0, worst_corner = 0.0;
  for (int trial = 0; trial < 3000; ++trial) {
    std::optional<CotsMap> m;
    try {
      if (trial % 3 == 2)
        m = CotsMap::from_spiral({unit(rng), unit(rng)}, {unit(rng), unit(rng)}, {0.6 * unit(rng), 12.0 * unit(rng)},
                                 {0.6 * unit(rng), 12.0 * unit(rng)});
      else
        m = CotsMap({unit(rng), unit(rng)}, {unit(rng), unit(rng)}, {unit(rng), unit(rng)}, {unit(rng), unit(rng)},
                    branch(rng), branch(rng));
    } catch (const InvalidInput&) {
      ++refused;
      continue;
    }
    // Keep maps whose inverse is reasonably conditioned (isocurves crossing at more than 1e-3 rad).
    if (std::abs(std::sin(m->tile_angle())) < 1e-3) continue;
    ++maps;
    const double size = std::max({1.0, glm::length(m->a() - m->c()), glm::length(m->b() - m->d())});
    worst_corner = std::max({worst_corner, dist(m->map(0, 1), m->b()) / size, dist(m->map(1, 1), m->c()) / size,
                             dist(m->map(1, 0), m->d()) / size});
    for (int k = 0; k < 20; ++k) {
      const double x = param(rng), y = param(rng);
      const Vec2 q = m->map(x, y);
      const auto found = m->inverse(q);
      double best = INFINITY;
      for (const auto& p : found) {
        best = std::min(best, dist(p.uv, {x, y}));
        worst_image = std::max(worst_image, dist(m->map(p.uv), q) / std::max(1.0, glm::length(q)));
      }
      worst_trip = std::max(worst_trip, best);
      overlapping_points += found.size() > 1;
      ++points;
    }
    if (maps % 10 == 0) {
      const double numeric = numerical_area(*m);
      worst_area = std::max(worst_area, std::abs(numeric - m->area()) / std::max(1e-3, std::abs(m->area())));
    }
  }
  EXPECT_GT(maps, 2000);
  EXPECT_GT(overlapping_points, 1000);
  EXPECT_LT(worst_trip, 1e-10);
  EXPECT_LT(worst_image, 1e-10);
  EXPECT_LT(worst_corner, 1e-10);
  EXPECT_LT(worst_area, 1e-10);
  std::printf("[ measured ] random planar maps: %d maps (%d refused), %d points, %d with several pre-images\n", maps,
              refused, points, overlapping_points);
  cots_test::report("random planar maps, largest round-trip error in (x, y)", worst_trip);
  cots_test::report("random planar maps, largest |M(pre-image) - q| / max(1, |q|)", worst_image);
  cots_test::report("random planar maps, largest corner error (relative)", worst_corner);
  cots_test::report("random planar maps, largest relative area error (closed form vs quadrature)", worst_area);
}

}  // namespace
