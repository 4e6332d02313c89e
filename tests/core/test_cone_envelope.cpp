// The hull model's cone envelopes (lattice/cone_envelope.hpp) against a brute force that knows only the
// definition: a point of cone i is on the hull iff w_i(x) >= max(0, w_j(x)) for every other stump j, and along a
// generator w_i(x) = v. No OpenCASCADE here: this executable links the core library alone.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <stdexcept>

#include "lattice/cone_envelope.hpp"

namespace steady::hull {
namespace {

constexpr double kTwoPi = 2.0 * M_PI;

struct BruteEnvelope {
  double v = 0.0;
  int active = -1;
  bool ambiguous = false;  // two constraints (or one and the tangent circle) nearly tied: skip the sample
};

// The smallest v >= 0 along generator u of cone i where no other stump dominates, by scanning (step 1e-2, finer
// than any feasible interval the callers allow) and bisection, and the stump whose constraint is tight there.
// found = false: no hull point on the generator below v_max.
BruteEnvelope brute_envelope(const std::vector<Cone>& cones, int i, double u, double v_max, bool& found) {
  auto holds = [&](double v) {
    const Vec3 x = cones[i].point(u, v);
    for (std::size_t j = 0; j < cones.size(); ++j)
      if (static_cast<int>(j) != i && cones[j].w(x) > v) return false;
    return true;
  };
  BruteEnvelope out;
  found = true;
  if (!holds(0.0)) {
    double lo = 0.0, hi = -1.0;
    for (double v = 1e-2; v <= v_max; v += 1e-2) {
      if (holds(v)) {
        hi = v;
        break;
      }
      lo = v;
    }
    if (hi < 0.0) {
      found = false;
      return out;
    }
    for (int it = 0; it < 60; ++it) (holds(0.5 * (lo + hi)) ? hi : lo) = 0.5 * (lo + hi);
    out.v = hi;
  }
  const Vec3 x = cones[i].point(u, out.v);
  double best = 1e300, second = 1e300;
  for (std::size_t j = 0; j < cones.size(); ++j) {
    if (static_cast<int>(j) == i) continue;
    const double gap = std::abs(cones[j].w(x) - out.v);
    if (gap < best) {
      second = best;
      best = gap;
      out.active = static_cast<int>(j);
    } else {
      second = std::min(second, gap);
    }
  }
  if (out.v == 0.0) {
    // On the tangent circle: the sphere is the neighbour unless a stump is tight there too.
    out.ambiguous = best < 1e-6;
    out.active = -1;
  } else {
    out.ambiguous = second < 1e-6;
  }
  return out;
}

std::vector<Cone> cones_of(const std::vector<std::pair<Vec3, double>>& stumps) {
  std::vector<Cone> cones;
  for (const auto& [direction, sin_phi] : stumps) cones.push_back(make_cone(direction, sin_phi));
  return cones;
}

// Random hubs: stumps at least 40 degrees apart, narrowing or widening.
std::vector<Cone> random_hub(std::mt19937& rng) {
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> sin_phi(-0.3, 0.3);
  std::uniform_int_distribution<int> count(2, 8);
  const int n = count(rng);
  std::vector<std::pair<Vec3, double>> stumps;
  for (int tries = 0; static_cast<int>(stumps.size()) < n && tries < 1000; ++tries) {
    const Vec3 d = glm::normalize(Vec3(gauss(rng), gauss(rng), gauss(rng)));
    bool apart = true;
    for (const auto& s : stumps) apart = apart && glm::dot(s.first, d) < std::cos(40.0 * M_PI / 180.0);
    if (apart) stumps.emplace_back(d, sin_phi(rng));
  }
  return cones_of(stumps);
}

TEST(ConeEnvelope, AlongGeneratorsMatchesTheDefinition) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> turn(0.0, kTwoPi);
  int compared = 0;
  for (int hub = 0; hub < 40; ++hub) {
    const std::vector<Cone> cones = random_hub(rng);
    for (int i = 0; i < static_cast<int>(cones.size()); ++i)
      for (int sample = 0; sample < 25; ++sample) {
        const double u = turn(rng);
        // Up to the apex of a narrowing cone; generators that leave the hull again have no simple envelope.
        const double v_max = cones[i].s > 0.0 ? 0.99 * cones[i].c / cones[i].s : 60.0;
        if (ceiling_at(cones, i, u) < v_max) continue;
        bool found = false;
        const BruteEnvelope brute = brute_envelope(cones, i, u, v_max, found);
        const Active fast = envelope_at(cones, i, u);
        if (!found) {
          EXPECT_GT(fast.v, v_max) << "hub " << hub << " cone " << i << " u " << u;
          continue;
        }
        EXPECT_NEAR(fast.v, brute.v, 1e-9) << "hub " << hub << " cone " << i << " u " << u;
        if (!brute.ambiguous) EXPECT_EQ(fast.index, brute.active) << "hub " << hub << " cone " << i << " u " << u;
        ++compared;
      }
  }
  EXPECT_GT(compared, 1000);
}

TEST(ConeEnvelope, BoundsAgreeWithTheLinearFunctionsTheyStandFor) {
  // bound_from's algebra against two evaluations of w_j along the generator (w_j is linear in v there).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> turn(0.0, kTwoPi);
  for (int hub = 0; hub < 20; ++hub) {
    const std::vector<Cone> cones = random_hub(rng);
    for (std::size_t i = 0; i < cones.size(); ++i)
      for (std::size_t j = 0; j < cones.size(); ++j) {
        if (i == j) continue;
        const double u = turn(rng);
        const double a = cones[j].w(cones[i].point(u, 0.0)), b = cones[j].w(cones[i].point(u, 1.0)) - a;
        const Bound bound = bound_from(cones[i], cones[j], u);
        // j dominates where a + b v > v.
        if (bound.kind == Bound::Lower) {
          EXPECT_LT(b, 1.0);
          EXPECT_NEAR(bound.t, a / (1.0 - b), 1e-9);
        } else if (bound.kind == Bound::Upper) {
          EXPECT_GT(b, 1.0);
          EXPECT_NEAR(bound.t, a / (1.0 - b), 1e-9);
        }
      }
  }
}

// Checks every property of an arrangement that the B-rep core relies on, sampling the definition.
void expect_consistent(const std::vector<Cone>& cones, const std::vector<double>& v_collar,
                       const Arrangement& arrangement, const std::string& name) {
  const int n = static_cast<int>(cones.size());
  ASSERT_EQ(static_cast<int>(arrangement.envelopes.size()), n);
  for (int i = 0; i < n; ++i) {
    const Envelope& env = arrangement.envelopes[i];
    ASSERT_FALSE(env.pieces.empty()) << name;
    // The pieces tile one turn from the window, in order, each ending where the next starts.
    EXPECT_DOUBLE_EQ(env.pieces.front().u0, env.window) << name;
    EXPECT_NEAR(env.pieces.back().u1, env.window + kTwoPi, 1e-12) << name;
    for (std::size_t k = 0; k < env.pieces.size(); ++k) {
      const Piece& p = env.pieces[k];
      const Piece& next = env.pieces[(k + 1) % env.pieces.size()];
      EXPECT_LT(p.u0, p.u1) << name;
      if (k + 1 < env.pieces.size()) EXPECT_DOUBLE_EQ(p.u1, next.u0) << name;
      EXPECT_EQ(p.v1, next.v0) << name << " cone " << i;
      // Each piece's neighbour is the one the definition finds inside it.
      for (int s = 1; s < 8; ++s) {
        const double u = p.u0 + (p.u1 - p.u0) * s / 8.0;
        bool found = false;
        const BruteEnvelope brute = brute_envelope(cones, i, u, v_collar[i], found);
        EXPECT_TRUE(found) << name << " cone " << i << " u " << u;
        if (found && !brute.ambiguous) EXPECT_EQ(p.active, brute.active) << name << " cone " << i << " u " << u;
      }
      // Its start vertex lies on the cone, on the envelope, and on the neighbour's side of it (w_i = w_j or 0).
      const Vec3 x = arrangement.vertices.points.at(p.v0);
      EXPECT_NEAR(glm::dot(x, x) - 1.0, cones[i].w(x) * cones[i].w(x), 1e-9) << name;
      const double other = p.active < 0 ? 0.0 : cones[p.active].w(x);
      EXPECT_NEAR(cones[i].w(x), other, 1e-9) << name << " cone " << i;
      // A cone-cone piece appears on the partner's envelope, run the other way.
      if (p.active >= 0) {
        bool partner = false;
        for (const Piece& q : arrangement.envelopes[p.active].pieces)
          partner = partner || (q.active == i && q.v0 == p.v1 && q.v1 == p.v0);
        EXPECT_TRUE(partner) << name << " cone " << i << " with " << p.active;
      }
    }
  }
}

TEST(ConeEnvelope, SixCylindersMeetInTheExpectedEdges) {
  // Unit cylinders along +-x, +-y, +-z (the hull model of a cubic node with equal balls). On the cylinder along
  // z the envelope is v = max(|cos u|, |sin u|): four elliptic arcs, switching at the diagonals, between the 8
  // points (+-1, +-1, +-1) / sqrt(2); no tangent circle survives.
  const std::vector<Cone> cones = cones_of({{{1, 0, 0}, 0.0}, {{-1, 0, 0}, 0.0}, {{0, 1, 0}, 0.0},
                                            {{0, -1, 0}, 0.0}, {{0, 0, 1}, 0.0}, {{0, 0, -1}, 0.0}});
  const Cone& z = cones[4];
  for (int s = 0; s < 200; ++s) {
    const double u = kTwoPi * s / 200.0;
    const Vec3 r = std::cos(u) * z.e + std::sin(u) * z.f;
    EXPECT_NEAR(envelope_at(cones, 4, u).v, std::max(std::abs(r.x), std::abs(r.y)), 1e-12);
  }
  const std::vector<double> v_collar(6, 2.0);
  const Arrangement arrangement = arrange_envelopes(cones, v_collar);
  expect_consistent(cones, v_collar, arrangement, "six cylinders");
  EXPECT_EQ(arrangement.vertices.points.size(), 8u);
  for (const Vec3& x : arrangement.vertices.points)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(std::abs(x[c]), 1.0 / std::sqrt(2.0), 1e-12);
  for (const Envelope& env : arrangement.envelopes) {
    EXPECT_EQ(env.pieces.size(), 4u);
    for (const Piece& p : env.pieces) EXPECT_GE(p.active, 0);
  }
}

TEST(ConeEnvelope, TwoStumpsFarApartLeaveTheirTangentCircles) {
  // Two opposite stumps never meet: each envelope is its whole tangent circle, one closed piece on the sphere.
  const std::vector<Cone> cones = cones_of({{{0, 0, 1}, 0.2}, {{0, 0, -1}, -0.1}});
  const std::vector<double> v_collar{1.0, 1.0};
  const Arrangement arrangement = arrange_envelopes(cones, v_collar);
  expect_consistent(cones, v_collar, arrangement, "two stumps");
  for (const Envelope& env : arrangement.envelopes) {
    ASSERT_EQ(env.pieces.size(), 1u);
    EXPECT_EQ(env.pieces[0].active, -1);
    EXPECT_NEAR(env.pieces[0].u1 - env.pieces[0].u0, kTwoPi, 1e-12);
  }
}

TEST(ConeEnvelope, RandomHubsGiveConsistentArrangements) {
  std::mt19937 rng(2024);
  int arranged = 0, refused = 0;
  for (int hub = 0; hub < 60; ++hub) {
    const std::vector<Cone> cones = random_hub(rng);
    // Collars just above the highest envelope, as the B-rep core places them; a hub whose stumps cannot keep
    // their collars clear is refused with a message naming the hub, never a wrong arrangement.
    std::vector<double> v_collar;
    for (int i = 0; i < static_cast<int>(cones.size()); ++i) {
      double top = 0.0;
      for (int s = 0; s < 512; ++s) top = std::max(top, envelope_at(cones, i, kTwoPi * s / 512).v);
      v_collar.push_back(top + 2.0 * kCollarClearance);
    }
    try {
      const Arrangement arrangement = arrange_envelopes(cones, v_collar);
      expect_consistent(cones, v_collar, arrangement, "random hub " + std::to_string(hub));
      ++arranged;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find("hub"), std::string::npos) << e.what();
      ++refused;
    }
  }
  EXPECT_GT(arranged, 40) << "refused " << refused;
}

TEST(ConeEnvelope, SwallowedStumpIsRefused) {
  // A thin stump right next to a wide one is inside it beyond its tangent circle: refused, not built.
  const std::vector<Cone> cones = cones_of({{{0, 0, 1}, -0.5}, {glm::normalize(Vec3(0.05, 0, 1)), 0.6}});
  EXPECT_THROW(arrange_envelopes(cones, {1.0, 1.0}), std::invalid_argument);
}

}  // namespace
}  // namespace steady::hull
