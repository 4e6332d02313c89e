// The BeCOTS map against the oracles of spec/constructive-lattice-geometry.md (chapter 4 and test oracles 8 to 14),
// against numerical references and over random corners and random fields.
#include <gtest/gtest.h>

#include <algorithm>
#include <complex>
#include <optional>
#include <random>
#include <string>

#include "cots_test_support.hpp"
#include "steady/core/errors.hpp"
#include "steady/cots/becots_map.hpp"

namespace {

using steady::BecotsMap;
using steady::CotsMap;
using steady::CotsPreimage;
using steady::InvalidInput;
using steady::Similarity;
using steady::Vec2;
using steady::Vec3;
using Complex = std::complex<double>;
using cots_test::kPi;

double dist(const Vec3& p, const Vec3& q) { return glm::length(p - q); }

double round_trip_error(const BecotsMap& m, double x, double y) {
  double best = INFINITY;
  for (const CotsPreimage& p : m.inverse(m.map(x, y))) best = std::min(best, glm::length(p.uv - Vec2(x, y)));
  return best;
}

// The area of the range by Gauss-Legendre quadrature of |dM/dx x dM/dy|, derivatives by finite differences.
double numerical_area(const BecotsMap& m) {
  const double speed = std::max({1.0, std::abs(m.log_u()), std::abs(m.log_v())});
  const double h = 1e-3 / speed;
  return cots_test::integrate_square([&](double x, double y) {
    const Vec3 mx = cots_test::derivative<Vec3>([&](double u) { return m.map(u, y); }, x, h);
    const Vec3 my = cots_test::derivative<Vec3>([&](double v) { return m.map(x, v); }, y, h);
    return glm::length(glm::cross(mx, my));
  });
}

// A field with apex, axis and windings from the generator (the maps the tests build corners from).
BecotsMap random_field(std::mt19937_64& rng, double max_angle) {
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  const Vec3 apex{unit(rng), unit(rng), unit(rng)};
  const Vec3 axis{unit(rng), unit(rng), unit(rng)};
  const Vec3 a = apex + Vec3(unit(rng), unit(rng), unit(rng)) * 2.0;
  return BecotsMap::from_field(apex, axis, a, {0.5 * unit(rng), max_angle * unit(rng)},
                               {0.5 * unit(rng), max_angle * unit(rng)});
}

TEST(BecotsMap, RandomCornersGiveOneCommutingFieldOnACone) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), param(0.0, 1.0);
  int maps = 0, refused = 0;
  double worst_corner = 0.0, worst_field = 0.0, worst_commute = 0.0, worst_cone = 0.0, worst_axis = 0.0;
  for (int trial = 0; trial < 1000; ++trial) {
    const Vec3 a{unit(rng), unit(rng), unit(rng)}, b{unit(rng), unit(rng), unit(rng)};
    const Vec3 c{unit(rng), unit(rng), unit(rng)}, d{unit(rng), unit(rng), unit(rng)};
    std::optional<BecotsMap> m;
    try {
      m = BecotsMap(a, b, c, d);
    } catch (const InvalidInput&) {
      ++refused;
      continue;
    }
    ++maps;
    ASSERT_FALSE(m->is_flat());
    const double size = std::max({1.0, dist(a, c), dist(b, d)});
    // Oracle 8: corners, U(A) = D, U(B) = C, V(A) = B, V(D) = C, a common fixed point, U V = V U.
    worst_corner = std::max({worst_corner, dist(m->map(0, 1), b) / size, dist(m->map(1, 1), c) / size,
                             dist(m->map(1, 0), d) / size});
    const Similarity U = m->u_similarity(), V = m->v_similarity();
    worst_field = std::max({worst_field, dist(U.apply_point(a), d) / size, dist(U.apply_point(b), c) / size,
                            dist(V.apply_point(a), b) / size, dist(V.apply_point(d), c) / size});
    worst_commute = std::max(worst_commute, (U * V).map_distance(V * U) / size);
    // The dissertation's four-point construction turns V about -T (erratum): both rotate about the one axis here.
    worst_axis = std::max({worst_axis, glm::length(glm::cross(U.rotation_vector(), m->axis())),
                           glm::length(glm::cross(V.rotation_vector(), m->axis()))});
    EXPECT_NEAR(glm::dot(U.rotation_vector(), m->axis()), m->log_u().imag(), 1e-12);
    EXPECT_NEAR(glm::dot(V.rotation_vector(), m->axis()), m->log_v().imag(), 1e-12);
    // Oracle 11: every point of the range sees the axis at the same angle from the apex.
    const std::optional<Vec3> f = m->apex();
    ASSERT_TRUE(f.has_value());
    const double apex_scale = std::max(1.0, glm::length(*f - a));
    worst_field = std::max({worst_field, dist(U.apply_point(*f), *f) / apex_scale,
                            dist(V.apply_point(*f), *f) / apex_scale});
    for (int k = 0; k < 5; ++k) {
      const double x = param(rng), y = param(rng);
      const Vec3 p = m->map(x, y);
      const Vec3 fp = p - *f;
      worst_cone = std::max(worst_cone, std::abs(std::atan2(glm::length(glm::cross(fp, m->axis())),
                                                            glm::dot(fp, m->axis())) -
                                                 m->bend_angle()));
      // M(x,y) = S(x,y)(A), and the TS identity M(x + dx, y + dy) = S(dx, dy) M(x, y).
      worst_field = std::max(worst_field, dist(m->field(x, y).apply_point(a), p) / size);
      worst_field = std::max(worst_field, dist(m->field(0.3, -0.2).apply_point(p), m->map(x + 0.3, y - 0.2)) / size);
    }
  }
  EXPECT_GT(maps, 900);
  EXPECT_LT(worst_corner, 1e-10);
  EXPECT_LT(worst_field, 1e-10);
  EXPECT_LT(worst_commute, 1e-10);
  EXPECT_LT(worst_axis, 1e-12);
  EXPECT_LT(worst_cone, 1e-10);
  std::printf("[ measured ] random BeCOTS corners: %d maps, %d refused\n", maps, refused);
  cots_test::report("random BeCOTS corners, largest corner error (relative)", worst_corner);
  cots_test::report("random BeCOTS corners, largest U/V/field/TS error (relative)", worst_field);
  cots_test::report("random BeCOTS corners, largest |UV - VU| (relative)", worst_commute);
  cots_test::report("random BeCOTS corners, largest cone-angle deviation (rad)", worst_cone);
}

TEST(BecotsMap, RandomMapsRoundTripWithEveryPreimage) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), param(0.0, 1.0);
  int maps = 0, points = 0, overlapping = 0, off_found = 0;
  double worst_trip = 0.0, worst_image = 0.0;
  for (int trial = 0; trial < 1500; ++trial) {
    std::optional<BecotsMap> m;
    try {
      if (trial % 2 == 0)
        m = BecotsMap({unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)},
                      {unit(rng), unit(rng), unit(rng)}, {unit(rng), unit(rng), unit(rng)});
      else
        m = random_field(rng, 10.0);  // windings: ranges that overlap themselves on their cone
    } catch (const InvalidInput&) {
      continue;
    }
    const Complex lu = m->log_u(), lv = m->log_v();
    const double sine = std::abs(lu.real() * lv.imag() - lu.imag() * lv.real()) / (std::abs(lu) * std::abs(lv));
    if (sine < 1e-3) continue;  // keep the inverse reasonably conditioned
    ++maps;
    for (int k = 0; k < 20; ++k) {
      const double x = param(rng), y = param(rng);
      const Vec3 q = m->map(x, y);
      const auto found = m->inverse(q);
      double best = INFINITY;
      for (const auto& p : found) {
        best = std::min(best, glm::length(p.uv - Vec2(x, y)));
        worst_image = std::max(worst_image, dist(m->map(p.uv), q) / std::max(1.0, glm::length(q)));
      }
      worst_trip = std::max(worst_trip, best);
      overlapping += found.size() > 1;
      ++points;
      // A point moved off the cone along its normal has no pre-image.
      const Vec3 mx = cots_test::derivative<Vec3>([&](double u) { return m->map(u, y); }, x, 1e-4);
      const Vec3 my = cots_test::derivative<Vec3>([&](double v) { return m->map(x, v); }, y, 1e-4);
      const Vec3 normal = glm::normalize(glm::cross(mx, my));
      off_found += !m->inverse(q + 1e-3 * std::max(1.0, glm::length(q)) * normal).empty();
    }
  }
  EXPECT_GT(maps, 1000);
  EXPECT_GT(overlapping, 500);
  EXPECT_LT(worst_trip, 1e-10);
  EXPECT_LT(worst_image, 1e-10);
  EXPECT_EQ(off_found, 0);
  std::printf("[ measured ] random BeCOTS maps: %d maps, %d points, %d with several pre-images\n", maps, points,
              overlapping);
  cots_test::report("random BeCOTS maps, largest round-trip error in (x, y)", worst_trip);
  cots_test::report("random BeCOTS maps, largest |M(pre-image) - q| / max(1, |q|)", worst_image);
}

TEST(BecotsMap, AreasAndTilesInClosedForm) {
  std::mt19937_64 rng(5);
  double worst_area = 0.0, worst_tiles = 0.0, worst_similar = 0.0;
  int maps = 0;
  for (int trial = 0; trial < 200; ++trial) {
    std::optional<BecotsMap> m;
    try {
      m = random_field(rng, 6.0);
    } catch (const InvalidInput&) {
      continue;
    }
    ++maps;
    worst_area = std::max(worst_area, std::abs(numerical_area(*m) - m->area()) / m->area());
    const int nu = 3, nv = 4;
    double sum = 0.0;
    for (int i = 0; i < nu; ++i)
      for (int j = 0; j < nv; ++j) sum += m->tile_area(i, j, nu, nv);
    worst_tiles = std::max(worst_tiles, std::abs(sum - m->area()) / m->area());
    // Tiles are similar (oracle 10): tile (i, j) = S(i/nu, j/nv) tile (0, 0), corners and inner points.
    const double size = std::max(1.0, dist(m->a(), m->c()));
    for (auto [i, j] : {std::pair{1, 0}, std::pair{2, 3}, std::pair{0, 2}}) {
      const Similarity s = m->tile_similarity(i, j, nu, nv);
      for (auto [x, y] : {std::pair{0.0, 0.0}, std::pair{1.0, 0.0}, std::pair{1.0, 1.0}, std::pair{0.4, 0.7}})
        worst_similar = std::max(worst_similar, dist(s.apply_point(m->map(x / nu, y / nv)),
                                                     m->map((i + x) / nu, (j + y) / nv)) / size);
    }
  }
  EXPECT_GT(maps, 150);
  EXPECT_LT(worst_area, 1e-10);
  EXPECT_LT(worst_tiles, 1e-12);
  EXPECT_LT(worst_similar, 1e-12);
  cots_test::report("random BeCOTS fields, largest relative area error (closed form vs quadrature)", worst_area);
  cots_test::report("random BeCOTS fields, largest tile-similarity error (relative)", worst_similar);
}

TEST(BecotsMap, RaiseAndProject) {
  std::mt19937_64 rng(3);
  const BecotsMap m = random_field(rng, 2.0);
  const BecotsMap flat = m.projected();
  EXPECT_TRUE(flat.is_flat());
  EXPECT_NEAR(flat.height(), 0.0, 1e-15);
  EXPECT_LT(dist(*flat.apex(), *m.apex()), 1e-12);
  // Oracle 12: Raise changes only heights: M_z(x,y) = M(x,y) + z m_u^x m_v^y T, the same shadow.
  const double z = 0.7;
  const BecotsMap raised = flat.raised(z);
  double worst = 0.0;
  for (double x : {0.0, 0.4, 1.0})
    for (double y : {0.0, 0.6, 1.0}) {
      const double scale = std::exp(x * m.log_u().real() + y * m.log_v().real());
      worst = std::max(worst, dist(raised.map(x, y), flat.map(x, y) + z * scale * flat.axis()));
      worst = std::max(worst, dist(flat.raised(m.height()).map(x, y), m.map(x, y)));  // raise the projection back
      worst = std::max(worst, dist(raised.projected().map(x, y), flat.map(x, y)));
    }
  EXPECT_LT(worst, 1e-12);
  EXPECT_NEAR(raised.height(), z, 1e-12);
  // The flat map is the planar COTS map of its corners (written in the plane's own coordinates).
  const Vec3 o = flat.a(), ex = flat.plane_x(), ey = flat.plane_y();
  auto in_plane = [&](const Vec3& p) { return Vec2(glm::dot(p - o, ex), glm::dot(p - o, ey)); };
  const CotsMap planar(in_plane(flat.a()), in_plane(flat.b()), in_plane(flat.c()), in_plane(flat.d()));
  EXPECT_LT(glm::length(in_plane(flat.map(0.3, 0.8)) - planar.map(0.3, 0.8)), 1e-13);
  EXPECT_NEAR(flat.area(), std::abs(planar.area()), 1e-12 * flat.area());
}

TEST(BecotsMap, BendAndUnbendKeepGeodesics) {
  // The flat P1 map of the COTS paper, in a tilted plane, bent onto cones (oracle 13).
  const Vec3 e1 = glm::normalize(Vec3(1, 0.2, -0.3)), e3 = glm::normalize(glm::cross(e1, Vec3(0, 1, 0.5)));
  const Vec3 e2 = glm::cross(e3, e1), o{0.3, -1.0, 2.0};
  auto place = [&](double x, double y) { return o + x * e1 + y * e2; };
  const BecotsMap flat(place(0, 0), place(0.1, 1), place(1.3, 1.2), place(1, 0));
  ASSERT_TRUE(flat.is_flat());
  EXPECT_NEAR(flat.bend_angle(), kPi / 2, 1e-15);
  const Vec3 f = *flat.apex();
  const Vec3 fa = flat.a() - f;
  // beta = pi/2 is the identity.
  const BecotsMap same = flat.bent(kPi / 2);
  EXPECT_LT(dist(same.map(0.4, 0.9), flat.map(0.4, 0.9)), 1e-13);
  for (double beta : {1.2, 0.6, 0.2, 2.5}) {
    const BecotsMap bent = flat.bent(beta);
    EXPECT_LT(dist(bent.a(), flat.a()), 1e-15);
    EXPECT_LT(dist(*bent.apex(), f), 1e-12);
    EXPECT_NEAR(bent.bend_angle(), beta, 1e-12);
    const double axis_to_fa =
        std::atan2(glm::length(glm::cross(bent.axis(), fa)), glm::dot(bent.axis(), fa));
    EXPECT_NEAR(axis_to_fa, beta, 1e-12);
    const BecotsMap back = bent.unbent();
    double worst = 0.0, worst_geodesic = 0.0;
    for (double x : {0.0, 0.3, 1.0})
      for (double y : {0.0, 0.5, 1.0}) {
        const Vec3 p = bent.map(x, y);
        EXPECT_NEAR(glm::length(p - f), glm::length(flat.map(x, y) - f), 1e-12);  // distances from the apex kept
        worst = std::max(worst, dist(back.map(x, y), flat.map(x, y)));
        // Geodesic from A on the cone = straight distance on the sheet: unroll by the azimuth times sin(beta).
        const Vec3 t = bent.axis();
        auto across = [&](const Vec3& v) { return v - t * glm::dot(v, t); };
        const Vec3 pa = across(fa), pp = across(p - f);
        const double azimuth = std::atan2(glm::dot(glm::cross(pa, pp), t), glm::dot(pa, pp));
        const double ra = glm::length(fa), rp = glm::length(p - f), unrolled = azimuth * std::sin(beta);
        const double geodesic = std::sqrt(ra * ra + rp * rp - 2 * ra * rp * std::cos(unrolled));
        worst_geodesic = std::max(worst_geodesic, std::abs(geodesic - glm::length(flat.map(x, y) - flat.a())));
      }
    EXPECT_LT(worst, 1e-12) << beta;
    EXPECT_LT(worst_geodesic, 1e-12) << beta;
    EXPECT_NEAR(bent.area(), flat.area(), 1e-12);  // the sheet keeps its area
    EXPECT_LT(std::abs(back.log_u() - flat.log_u()), 1e-14);
  }
}

TEST(BecotsMap, BentFarEnoughTheRangeOverlapsItself) {
  const BecotsMap flat({0, 0, 0}, {0.1, 1, 0}, {1.3, 1.2, 0}, {1, 0, 0});
  const BecotsMap wound = flat.bent(0.03);  // angles grow 33-fold: the sheet wraps more than once around the cone
  const double wu = wound.log_u().imag(), wv = wound.log_v().imag();
  ASSERT_GT(std::max({0.0, wu, wv, wu + wv}) - std::min({0.0, wu, wv, wu + wv}), 2 * kPi);
  int several = 0;
  double worst = 0.0;
  for (int i = 0; i <= 20; ++i)
    for (int j = 0; j <= 20; ++j) {
      const Vec3 q = wound.map(i / 20.0, j / 20.0);
      const auto found = wound.inverse(q);
      several += found.size() > 1;
      bool has_own = false;
      for (const auto& p : found) {
        worst = std::max(worst, dist(wound.map(p.uv), q));
        has_own |= glm::length(p.uv - Vec2(i / 20.0, j / 20.0)) < 1e-10;
      }
      EXPECT_TRUE(has_own) << i << " " << j;
    }
  EXPECT_GT(several, 20);
  EXPECT_LT(worst, 1e-12);
  std::printf("[ measured ] P1 bent to beta = 0.03: %d of 441 grid points have several pre-images\n", several);
}

TEST(BecotsMap, NearCylindersStayAccurateAndExactCylindersAreRefused) {
  // Two coaxial screws: M(x,y) = Rot_z(x wu + y wv)(A) + (x tu + y tv) z, so |AB| = |CD| and |AD| = |BC|. A family of
  // such fields (cylinders of different axes) passes through the four corners: refused, naming them.
  const double wu = 0.7, wv = -0.4, tu = 0.2, tv = 0.5;
  auto helix = [&](double x, double y) {
    const double t = x * wu + y * wv;
    return Vec3(1.3 * std::cos(t), 1.3 * std::sin(t), x * tu + y * tv);
  };
  const std::string refused = cots_test::message_of([&] { BecotsMap(helix(0, 0), helix(0, 1), helix(1, 1), helix(1, 0)); });
  EXPECT_NE(refused.find("corners A, B, C, D"), std::string::npos) << refused;
  EXPECT_NE(refused.find("axis"), std::string::npos) << refused;
  // Nearly a cylinder: a small dilation about an apex far down the axis. The map is evaluated without the apex, and
  // its corners give back the same field.
  double worst = 0.0, worst_trip = 0.0;
  for (double l : {1e-2, 1e-3, 1e-4}) {
    const Vec3 apex{0.0, 0.0, -0.3 / l};
    const BecotsMap field = BecotsMap::from_field(apex, {0, 0, 1}, {1.3, 0, 0}, {l, wu}, {0.5 * l, wv});
    const BecotsMap m(field.a(), field.b(), field.c(), field.d());
    for (double x : {0.0, 0.25, 0.5, 0.9})
      for (double y : {0.1, 0.6, 1.0}) {
        worst = std::max(worst, dist(m.map(x, y), field.map(x, y)));
        worst_trip = std::max(worst_trip, round_trip_error(m, x, y));
      }
    EXPECT_LT(dist(*m.apex(), apex) / glm::length(apex), 1e-6) << l;
    EXPECT_NEAR(m.area(), numerical_area(m), 1e-10) << l;
  }
  EXPECT_LT(worst, 1e-10);
  EXPECT_LT(worst_trip, 1e-10);
  cots_test::report("near-cylinders (dilation 1e-2..1e-4), largest map error from rebuilt corners", worst);
  cots_test::report("near-cylinders, largest round-trip error", worst_trip);
}

TEST(BecotsMap, EqualOppositeSidesOnlyMakeUAPureRotation) {
  const BecotsMap field = BecotsMap::from_field({0.2, -0.1, 0.4}, {0.3, 0.1, 1.0}, {1.5, 0.3, 0.9}, {0.0, 0.8},
                                                {0.2, 0.5});
  EXPECT_NEAR(dist(field.a(), field.b()), dist(field.c(), field.d()), 1e-12);
  const BecotsMap m(field.a(), field.b(), field.c(), field.d());
  EXPECT_NEAR(m.log_u().real(), 0.0, 1e-13);
  double worst = 0.0;
  for (double x : {0.0, 0.3, 0.8})
    for (double y : {0.2, 0.7}) {
      worst = std::max(worst, dist(m.map(x, y), field.map(x, y)));
      worst = std::max(worst, round_trip_error(m, x, y));
    }
  EXPECT_LT(worst, 1e-12);
  EXPECT_LT(dist(*m.apex(), Vec3(0.2, -0.1, 0.4)), 1e-11);
}

TEST(BecotsMap, CoplanarCornersAreThePlanarMap) {
  const Vec3 o{1, 2, 3}, ex = glm::normalize(Vec3(1, 1, 0)), ey = glm::normalize(Vec3(-1, 1, 1.5));
  const Vec3 ey_orth = glm::normalize(ey - ex * glm::dot(ex, ey));
  auto place = [&](Vec2 p) { return o + p.x * ex + p.y * ey_orth; };
  // A parallelogram (affine) and a self-crossing quad, both in a tilted plane.
  for (auto corners : {std::array<Vec2, 4>{Vec2(0, 0), Vec2(0.5, 1), Vec2(1.5, 1.25), Vec2(1, 0.25)},
                       std::array<Vec2, 4>{Vec2(0, 0), Vec2(1.2, 1), Vec2(0, 1.3), Vec2(1, 0)}}) {
    const BecotsMap m(place(corners[0]), place(corners[1]), place(corners[2]), place(corners[3]));
    const CotsMap planar(corners[0], corners[1], corners[2], corners[3]);
    EXPECT_TRUE(m.is_flat());
    EXPECT_NEAR(m.area(), std::abs(planar.area()), 1e-13);
    EXPECT_LT(dist(m.map(0.3, 0.6), place(planar.map(0.3, 0.6))), 1e-13);
    EXPECT_LT(round_trip_error(m, 0.3, 0.6), 1e-13);
    EXPECT_TRUE(m.inverse(m.map(0.3, 0.6) + 1e-3 * glm::cross(ex, ey_orth)).empty());
  }
}

TEST(BecotsMap, BranchesFromCornersRecoverWoundFields) {
  // A field that turns more than a half turn along x: its corners give it back with one more turn about the axis
  // (+1 or -1, depending on whether the constructor's axis points like the field's).
  std::mt19937_64 rng(19);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  int rebuilt = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 apex{unit(rng), unit(rng), unit(rng)}, axis{unit(rng), unit(rng), unit(rng)};
    const Vec3 a = apex + 2.0 * Vec3(unit(rng), unit(rng), unit(rng));
    const double wu = (kPi + 0.2) + 1.5 * (unit(rng) + 1.0), wv = 0.8 * unit(rng);  // wu in (pi, 2 pi + ...)
    std::optional<BecotsMap> field;
    try {
      field = BecotsMap::from_field(apex, axis, a, {0.3 * unit(rng), wu}, {0.3 * unit(rng), wv});
    } catch (const InvalidInput&) {
      continue;
    }
    const BecotsMap principal(field->a(), field->b(), field->c(), field->d());
    const int k = glm::dot(principal.axis(), field->axis()) > 0 ? 1 : -1;
    const BecotsMap m(field->a(), field->b(), field->c(), field->d(), wu > 3 * kPi ? 2 * k : k, 0);
    double err = 0.0;
    for (double x : {0.2, 0.5, 0.8}) err = std::max(err, dist(m.map(x, 0.5), field->map(x, 0.5)));
    worst = std::max(worst, err / std::max(1.0, dist(field->a(), *field->apex())));
    ++rebuilt;
  }
  EXPECT_GT(rebuilt, 150);
  EXPECT_LT(worst, 1e-10);
  cots_test::report("wound BeCOTS fields rebuilt from corners with branches, largest map error", worst);
}

TEST(BecotsMap, ContinuousAcrossTheCoplanarThreshold) {
  // C lifted by eps off the plane of P1: flat below 1e-12 (relative volume), a cone above; the maps move by O(eps).
  const Vec3 a{0, 0, 0}, b{0.1, 1, 0}, c{1.3, 1.2, 0}, d{1, 0, 0};
  const BecotsMap flat(a, b, c, d);
  double worst_ratio = 0.0, worst_trip = 0.0;
  for (double eps : {1e-14, 1e-12, 1e-11, 1e-9, 1e-6, 1e-3}) {
    const BecotsMap m(a, b, c + Vec3(0, 0, eps), d);
    EXPECT_EQ(m.is_flat(), eps <= 1e-12) << eps;
    for (double x : {0.0, 0.3, 0.8})
      for (double y : {0.2, 0.9}) {
        worst_ratio = std::max(worst_ratio, dist(m.map(x, y), flat.map(x, y)) / eps);
        worst_trip = std::max(worst_trip, round_trip_error(m, x, y));
      }
  }
  EXPECT_LT(worst_ratio, 2.0);
  EXPECT_LT(worst_trip, 1e-14);
}

TEST(BecotsMap, BadInputNamesTheCorners) {
  const double nan = std::nan("");
  const Vec3 a{0, 0, 0}, b{0.1, 1, 0.2}, c{1.3, 1.2, -0.3}, d{1, 0, 0.1};
  EXPECT_NE(cots_test::message_of([&] { BecotsMap({nan, 0, 0}, b, c, d); }).find("corner A"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { BecotsMap(a, b, {0, INFINITY, 0}, d); }).find("corner C"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { BecotsMap(a, a, c, d); }).find("corners A, B"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { BecotsMap(a, b, c, a); }).find("corners A, D"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { BecotsMap(a, {1, 1, 1}, {3, 3, 3}, {2, 2, 2}); }).find("one line"), std::string::npos);
  // A parallelogram lifted at one corner: a family of cones passes through it, the axis is undetermined.
  const std::string axis = cots_test::message_of([&] { BecotsMap(a, {0, 1, 0}, {1, 1, 1e-3}, {1, 0, 0}); });
  EXPECT_NE(axis.find("corners A, B, C, D"), std::string::npos) << axis;
  EXPECT_NE(axis.find("axis"), std::string::npos) << axis;
  const BecotsMap m(a, b, c, d);
  EXPECT_NE(cots_test::message_of([&] { m.bent(0.0); }).find("beta"), std::string::npos);
  EXPECT_NE(cots_test::message_of([&] { m.bent(kPi); }).find("beta"), std::string::npos);
  EXPECT_THROW(m.inverse({nan, 0, 0}), InvalidInput);
  EXPECT_THROW(m.raised(nan), InvalidInput);
  EXPECT_THROW(BecotsMap::from_field({0, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0.1, 0.2}, {0.3, 0.4}), InvalidInput);
  EXPECT_NE(cots_test::message_of([&] { BecotsMap::from_field({0, 0, 0}, {0, 0, 1}, {0, 0, 2}, {0.1, 0.2}, {0.3, 0.4}); })
                .find("axis"),
            std::string::npos);
  // A flat parallelogram has no apex to bend about.
  const BecotsMap parallelogram(a, {0, 1, 0}, {1, 1, 0}, {1, 0, 0});
  EXPECT_THROW(parallelogram.bent(1.0), InvalidInput);
}

}  // namespace
