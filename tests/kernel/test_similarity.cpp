// Similarity: constructors against hand values, powers, inverses, composition, canonical decomposition,
// the similarity between two frames (including the cases where the paper's formulas fail) and the
// oracles of sections 11.3-11.4 of steady-lattices.md.
#include <gtest/gtest.h>

#include <cmath>

#include "steady/core/errors.hpp"
#include "steady/core/similarity.hpp"
#include "test_support.hpp"
#include "steady/core/constants.hpp"

namespace steady {
namespace {

using test::map_error;
using test::random_similarity;
using test::random_unit;
using test::random_vec;
using test::record_error;


void expect_near(const Vec3& a, const Vec3& b, double tol) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Similarity, ConstructorsMatchHandValues) {
  const Vec3 z(0, 0, 1);
  expect_near(Similarity::rotation(kPi / 2, z, Vec3(0.0)).apply_point({1, 0, 0}), {0, 1, 0}, 1e-15);
  // A quarter turn about the vertical line through (1, 0, 0) takes the origin to (1, -1, 0).
  expect_near(Similarity::rotation(kPi / 2, z, {1, 0, 0}).apply_point({0, 0, 0}), {1, -1, 0}, 1e-15);
  expect_near(Similarity::translation({1, 2, 3}).apply_point({1, 1, 1}), {2, 3, 4}, 0);
  expect_near(Similarity::dilation(2.0, {1, 1, 1}).apply_point({2, 1, 1}), {3, 1, 1}, 1e-15);
  expect_near(Similarity::screw(kPi, z, {1, 0, 0}, 5.0).apply_point({0, 0, 0}), {2, 0, 5}, 1e-14);
  const Similarity sw = Similarity::swirl(kPi / 2, z, {1, 1, 0}, 3.0);
  expect_near(sw.apply_point({2, 1, 0}), {1, 4, 0}, 1e-14);
  expect_near(sw.apply_point({1, 1, 2}), {1, 1, 6}, 1e-14);
  EXPECT_NEAR(sw.scale(), 3.0, 1e-15);
  const Ball b = sw.apply(Ball{{1, 1, 0}, 0.5});
  EXPECT_NEAR(b.radius, 1.5, 1e-15);
}

TEST(Similarity, KindsAndCanonicalParameters) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec3 axis = random_unit(rng), point = random_vec(rng, 4.0);
    const double angle = 0.1 + 2.9 * (trial % 10) / 10.0;
    const double distance = 0.3 + trial * 0.01, scale = 1.3;

    const CanonicalForm screw = Similarity::screw(angle, axis, point, distance).canonical();
    EXPECT_EQ(screw.kind, SimilarityKind::Screw);
    EXPECT_NEAR(screw.angle, angle, 1e-12);
    expect_near(screw.axis, axis, 1e-12);
    EXPECT_NEAR(screw.distance, distance, 1e-12);
    // the canonical point lies on the given axis and is the axis point nearest the origin
    const Vec3 off = screw.point - point;
    EXPECT_NEAR(glm::length(off - glm::dot(off, axis) * axis), 0.0, 1e-11);
    EXPECT_NEAR(glm::dot(screw.point, axis), 0.0, 1e-11);

    const Similarity swirl = Similarity::swirl(angle, axis, point, scale);
    const CanonicalForm c = swirl.canonical();
    EXPECT_EQ(c.kind, SimilarityKind::Swirl);
    expect_near(c.point, point, 1e-11);
    EXPECT_NEAR(c.scale, scale, 1e-14);
    expect_near(swirl.apply_point(c.point), c.point, 1e-11);

    EXPECT_EQ(Similarity::rotation(angle, axis, point).kind(), SimilarityKind::Rotation);
    EXPECT_EQ(Similarity::dilation(scale, point).kind(), SimilarityKind::Dilation);
    expect_near(Similarity::dilation(scale, point).canonical().point, point, 1e-12);
  }
  EXPECT_EQ(Similarity::identity().kind(), SimilarityKind::Identity);
  EXPECT_EQ(Similarity::translation({0, 0, 1}).kind(), SimilarityKind::Translation);
  EXPECT_EQ(Similarity::rotation(0.0, {0, 0, 1}, {0, 0, 0}).kind(), SimilarityKind::Identity);
  EXPECT_EQ(Similarity::screw(0.0, {0, 0, 1}, {0, 0, 0}, 2.0).kind(), SimilarityKind::Translation);
  EXPECT_EQ(Similarity::swirl(0.0, {0, 0, 1}, {0, 0, 0}, 2.0).kind(), SimilarityKind::Dilation);
  EXPECT_EQ(Similarity::swirl(1.0, {0, 0, 1}, {0, 0, 0}, 1.0).kind(), SimilarityKind::Rotation);
}

TEST(Similarity, PowersAddAndInvert) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> ut(-3.0, 3.0);
  for (int trial = 0; trial < 3000; ++trial) {
    const Similarity s = random_similarity(rng, trial);
    const double a = ut(rng), b = ut(rng);
    const double e1 = map_error(s.power(a) * s.power(b), s.power(a + b));
    EXPECT_LT(e1, 1e-9) << s.describe() << " a=" << a << " b=" << b;
    record_error(e1);
    const double e2 = map_error(s * s.inverse(), Similarity::identity());
    EXPECT_LT(e2, 1e-12);
    record_error(e2);
    const double e3 = map_error(s.power(-1.0), s.inverse());
    EXPECT_LT(e3, 1e-12);
    EXPECT_LT(map_error(s.power(0.0), Similarity::identity()), 1e-15);
    EXPECT_LT(map_error(s.power(1.0), s), 1e-12);
    // (S^a)^-1 = S^-a
    EXPECT_LT(map_error(s.power(a).inverse(), s.power(-a)), 1e-9);
  }
}

TEST(Similarity, RootsAndIntegerPowers) {
  std::mt19937_64 rng(13);
  for (int trial = 0; trial < 1200; ++trial) {
    const Similarity s = random_similarity(rng, trial);
    const int n = 1 + trial % 12;
    // (S^(1/n))^n = S, both as a real power and as repeated composition
    const Similarity root = s.power(1.0 / n);
    Similarity repeated = Similarity::identity();
    for (int r = 0; r < n; ++r) repeated = repeated * root;
    const double e1 = map_error(root.power(n), s), e2 = map_error(repeated, s);
    EXPECT_LT(e1, 1e-10) << s.describe() << " n=" << n;
    EXPECT_LT(e2, 1e-10) << s.describe() << " n=" << n;
    record_error(std::max(e1, e2));
    // integer powers equal repeated composition of S itself, applied to points one at a time
    Vec3 p = random_vec(rng, 2.0), q = p;
    for (int r = 0; r < n; ++r) q = s.apply_point(q);
    const double e3 = glm::length(s.power(n).apply_point(p) - q) / (1.0 + glm::length(q));
    EXPECT_LT(e3, 1e-11);
    record_error(e3);
  }
}

TEST(Similarity, NearIdentityAndNearFullTurnStayAccurate) {
  const Vec3 axis = glm::normalize(Vec3(0.3, -0.2, 0.9)), point(4.0, -1.0, 2.0);
  for (double eps : {1e-6, 1e-9, 1e-12, 1e-14, 1e-16}) {
    const Similarity s = Similarity::swirl(eps, axis, point, 1.0 + eps) * Similarity::translation({eps, 0, 0});
    const Similarity half = s.power(0.5);
    const double e = map_error(half * half, s);
    EXPECT_LT(e, 1e-14) << eps;
    record_error(e);
    for (int c = 0; c < 3; ++c) EXPECT_TRUE(std::isfinite(half.translation_part()[c]));
  }
  for (double gap : {1e-3, 1e-8, 1e-12}) {
    const Similarity s = Similarity::rotation(2 * kPi - gap, axis, point);
    const double e = map_error(s.power(1.0 / 3.0).power(3.0), s);
    EXPECT_LT(e, 1e-10) << gap;
    record_error(e);
  }
}

TEST(Similarity, WindingAnglesAreKept) {
  const Vec3 z(0, 0, 1), p(1, 0, 0);
  // A full turn about the line through (1,0,0): the identity map, but its square root is a half turn
  // about that line, taking the origin to (2, 0, 0).
  const Similarity full = Similarity::rotation(2 * kPi, z, p);
  EXPECT_LT(map_error(full, Similarity::identity()), 1e-14);
  expect_near(full.power(0.5).apply_point({0, 0, 0}), {2, 0, 0}, 1e-14);
  // Three half turns: the cube root is one half turn (not the principal -pi/3 of the group element).
  expect_near(Similarity::rotation(3 * kPi, z, p).power(1.0 / 3.0).apply_point({0, 0, 0}), {2, 0, 0}, 1e-14);
  // A spring of two and a half turns rising 10: each of its five steps is a half turn rising 2.
  const Similarity spring = Similarity::screw(5 * kPi, z, p, 10.0);
  expect_near(spring.power(0.2).apply_point({0, 0, 0}), {2, 0, 2}, 1e-13);
  // Composition of commuting similarities keeps the winding: (S^0.75) * (S^0.25) = S.
  const Similarity product = spring.power(0.75) * spring.power(0.25);
  EXPECT_NEAR(product.canonical().angle, 5 * kPi, 1e-12);
}

TEST(Similarity, FramesRoundTrip) {
  std::mt19937_64 rng(17);
  for (int trial = 0; trial < 2000; ++trial) {
    const Similarity s = random_similarity(rng, trial, 3.1);
    const Similarity place = random_similarity(rng, 5);
    const Frame a = place.frame();
    const Frame b = (s * place).frame();
    const Similarity r = Similarity::from_frames(a, b);
    const double e = map_error(r, s);
    EXPECT_LT(e, 1e-10) << s.describe();
    record_error(e);
    EXPECT_LE(r.canonical().angle, kPi + 1e-12);
    // frame -> similarity -> frame
    const Frame back = Similarity::from_frame(a).frame();
    const double ef = glm::length(back.origin - a.origin) + glm::length(back.x - a.x) + glm::length(back.y - a.y) +
                      glm::length(back.z - a.z);
    EXPECT_LT(ef, 1e-12);
    record_error(ef);
  }
}

// steady-lattices.md 11.3: Appendix A round trip and the two failure oracles of the paper's formulas.
TEST(Similarity, AppendixAOracles) {
  const Vec3 F(0.5, 1.5, -1), N = Vec3(1, 2, 2) / 3.0;
  const Frame base{{2, 0, 1}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (double alpha : {0.7, -0.7}) {
    const Similarity truth = Similarity::swirl(alpha, N, F, 1.2);
    const Similarity got = Similarity::from_frames(base, (truth * Similarity::from_frame(base)).frame());
    const CanonicalForm c = got.canonical();
    EXPECT_EQ(c.kind, SimilarityKind::Swirl);
    EXPECT_NEAR(c.scale, 1.2, 1e-14);
    expect_near(c.point, F, 1e-13);
    // alpha N is the invariant: the angle is reported >= 0 with the axis carrying the sense
    expect_near(c.angle * c.axis, alpha * N, 1e-14);
  }
  // The paper's A.2 sum of cross products vanishes for an axis orthogonal to I + J + K.
  const Frame unit{};
  const Vec3 bad_axis = glm::normalize(Vec3(1, -1, 0));
  const Similarity t1 = Similarity::swirl(0.7, bad_axis, {0.3, 0.2, 0.1}, 1.2);
  const CanonicalForm c1 = Similarity::from_frames(unit, t1.frame()).canonical();
  expect_near(c1.angle * c1.axis, 0.7 * bad_axis, 1e-14);
  EXPECT_NEAR(c1.scale, 1.2, 1e-14);
  // A.3's max() returns 0 for a negative angle about a basis vector.
  const Similarity t2 = Similarity::rotation(-0.7, {0, 0, 1}, {0, 0, 0});
  const CanonicalForm c2 = Similarity::from_frames(unit, t2.frame()).canonical();
  expect_near(c2.angle * c2.axis, Vec3(0, 0, -0.7), 1e-15);
  // No rotation: translation, dilation with F = (s O_A - O_B) / (s - 1); and s = 1 with rotation: screw.
  const Frame a{{1, 2, 3}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  const Frame shifted{{4, 2, 3}, {2, 0, 0}, {0, 2, 0}, {0, 0, 2}};
  EXPECT_EQ(Similarity::from_frames(a, shifted).kind(), SimilarityKind::Translation);
  const Frame grown{{5, 2, 3}, {4, 0, 0}, {0, 4, 0}, {0, 0, 4}};
  const CanonicalForm d = Similarity::from_frames(a, grown).canonical();
  EXPECT_EQ(d.kind, SimilarityKind::Dilation);
  expect_near(d.point, (2.0 * a.origin - grown.origin) / (2.0 - 1.0), 1e-13);
  const Similarity scr = Similarity::screw(1.0, {0, 1, 0}, {1, 0, 0}, 2.0);
  EXPECT_EQ(Similarity::from_frames(a, (scr * Similarity::from_frame(a)).frame()).kind(), SimilarityKind::Screw);
}

// steady-lattices.md 11.3: U' a swirl about the origin, axis z, angle pi/2, scale 8, 4 groups.
TEST(Similarity, FractionalPowerOracle) {
  const Similarity total = Similarity::swirl(kPi / 2, {0, 0, 1}, {0, 0, 0}, 8.0);
  const Similarity step = total.power(1.0 / 3.0);
  EXPECT_NEAR(step.canonical().angle, kPi / 6, 1e-15);
  EXPECT_NEAR(step.scale(), 2.0, 1e-15);
  expect_near(step.apply_point({1, 0, 0}), {std::sqrt(3.0), 1.0, 0.0}, 1e-15);
  EXPECT_LT(map_error(step * step * step, total), 1e-14);
}

TEST(Similarity, BadInputNamesTheParameter) {
  auto message = [](auto&& f) {
    try {
      f();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([] { Similarity::rotation(1.0, {0, 0, 0}, {0, 0, 0}); }).find("rotation.axis"), std::string::npos);
  EXPECT_NE(message([] { Similarity::dilation(-2.0, {0, 0, 0}); }).find("dilation.scale: must be > 0"), std::string::npos);
  EXPECT_NE(message([] { Similarity::swirl(1.0, {0, 0, 1}, {0, 0, 0}, 0.0); }).find("swirl.scale"), std::string::npos);
  EXPECT_NE(message([] { Similarity::translation({NAN, 0, 0}); }).find("translation.vector: must be a finite"),
            std::string::npos);
  EXPECT_NE(message([] { Similarity::identity().power(NAN); }).find("power exponent"), std::string::npos);
  const Frame skewed{{0, 0, 0}, {1, 0, 0}, {0.6, 0.8, 0}, {0, 0, 1}};
  EXPECT_NE(message([&] { Similarity::from_frame(skewed); }).find("orthogonal"), std::string::npos);
  const Frame left{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, -1}};
  EXPECT_NE(message([&] { Similarity::from_frame(left); }).find("right-handed"), std::string::npos);
  const Frame unequal{{0, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, 1}};
  EXPECT_NE(message([&] { Similarity::from_frame(unequal); }).find("must be equal"), std::string::npos);
}

}  // namespace
}  // namespace steady
