// Steady brick lattice: direct evaluation against iterated application (Eq. 7), the steadiness
// identities of section 2, the Fig. 2 structure, indexing round trips with omissions, bulk listings
// against element-by-element evaluation, the interpolating controls, and bad input.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <set>
#include <tuple>

#include "steady/core/errors.hpp"
#include "steady/lattice/lattice.hpp"
#include "test_support.hpp"
#include "brick_definition.hpp"
#include "steady/core/constants.hpp"

namespace steady {
namespace {

using test::random_vec;


// A bent, twisted and tapered lattice with two nodes per group and beams in every direction.
Lattice graded_lattice(Counts counts, std::vector<NodeId> omitted = {}) {
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, 0.2}, {{0.5, 0.5, 0.5}, 0.15}};
  d.beams = {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}, {0, 0, 0, 0, 1},
             {1, 1, 1, 1, 0, 0.05, 0.04}, {1, 2, 1, 0, 0}, {1, 0, 1, -1, 0}, {0, -2, 0, 1, 1, 0.1, 0.1}};
  d.counts = counts;
  d.u = {Similarity::swirl(0.05, {0, 0, 1}, {0, -20, 0}, 1.01)};
  d.v = {Similarity::screw(0.03, {1, 0, 0}, {0, 0, 5}, 1.0)};
  d.w = {Similarity::swirl(-0.02, glm::normalize(Vec3(0.2, 1, 0.1)), {3, 3, -10}, 0.99)};
  d.placement = Similarity::rotation(0.4, {1, 1, 0}, {1, 2, 3}) * Similarity::dilation(2.0, {0, 0, 0});
  d.omitted = std::move(omitted);
  return Lattice(std::move(d));
}

double dist(const Vec3& a, const Vec3& b) { return glm::length(a - b); }

// The steady-brick view of a lattice: its steps by lattice axis and its placement.
const SteadyBrick& brick(const Lattice& lat) { return *lat.layout().steady_brick(); }

// Eq. 7: N[i,j,k,n] = Ball(W^k V^j U^i C_n, m_w^k m_v^j m_u^i r_n), checked against iterating U, V, W.
TEST(Lattice, DirectEvaluationMatchesIteration) {
  const Lattice lat = graded_lattice({7, 5, 4});
  const LatticeDefinition& d = lat.definition();
  const SteadyBrick& b = brick(lat);
  for (int n = 0; n < 2; ++n)
    for (std::int64_t k = 0; k < 4; ++k)
      for (std::int64_t j = 0; j < 5; ++j)
        for (std::int64_t i = 0; i < 7; ++i) {
          Vec3 p = d.nodes[n].center;
          for (int r = 0; r < i; ++r) p = b.step_along(0).apply_point(p);
          for (int r = 0; r < j; ++r) p = b.step_along(1).apply_point(p);
          for (int r = 0; r < k; ++r) p = b.step_along(2).apply_point(p);
          p = b.placement.apply_point(p);
          const double radius = d.nodes[n].radius * std::pow(1.01, i) * std::pow(0.99, k) * 2.0;
          const Ball ball = lat.ball({i, j, k, n});
          EXPECT_LT(dist(ball.center, p), 1e-12 * (1 + glm::length(p)));
          EXPECT_NEAR(ball.radius, radius, 1e-14);
        }
}

// steady-lattices.md section 2: i-rows, j-rows and k-rows of clusters and k-rows of beams are steady.
TEST(Lattice, SteadinessIdentities) {
  const Lattice lat = graded_lattice({6, 5, 4});
  const Similarity U = brick(lat).step_along(0), V = brick(lat).step_along(1), W = brick(lat).step_along(2),
                   G = brick(lat).placement;
  const Similarity Ginv = G.inverse();
  for (std::int64_t k = 0; k < 4; ++k)
    for (std::int64_t j = 0; j < 5; ++j)
      for (std::int64_t i = 0; i < 6; ++i)
        for (int n = 0; n < 2; ++n) {
          const Vec3 c = lat.ball({i, j, k, n}).center;
          // local (template) coordinates: G^-1 applied
          const Vec3 local = Ginv.apply_point(c);
          const Similarity m_i = W.power(k) * V.power(j) * U * V.power(-j) * W.power(-k);
          const Vec3 from_row_i = m_i.power(i).apply_point(Ginv.apply_point(lat.ball({0, j, k, n}).center));
          EXPECT_LT(dist(local, from_row_i), 1e-11);
          const Similarity m_j = W.power(k) * V * W.power(-k);
          const Vec3 from_row_j = m_j.power(j).apply_point(Ginv.apply_point(lat.ball({i, 0, k, n}).center));
          EXPECT_LT(dist(local, from_row_j), 1e-11);
          const Vec3 from_row_k = W.power(k).apply_point(Ginv.apply_point(lat.ball({i, j, 0, n}).center));
          EXPECT_LT(dist(local, from_row_k), 1e-11);
        }
  // beams: B[i,j,k,p] = W^k B[i,j,0,p]
  for (std::int64_t b = 0; b < lat.beam_count(); ++b) {
    const BeamId id = lat.beam_id(b);
    if (id.k == 0) continue;
    BeamId base = id;
    base.k = 0;
    if (!lat.beam_exists(base)) continue;
    const BeamGeometry g = lat.beam(id), g0 = lat.beam(base);
    const Similarity wk = G * W.power(id.k) * Ginv;
    EXPECT_LT(dist(g.start.center, wk.apply_point(g0.start.center)), 1e-11);
    EXPECT_LT(dist(g.end.center, wk.apply_point(g0.end.center)), 1e-11);
    EXPECT_NEAR(g.end.radius, wk.scale() * g0.end.radius, 1e-14);
  }
}

// steady-lattices.md 11.4: the Fig. 2 lattice has 140 nodes, and rack 3 = (1, 2, 1, 0, 0) has 48 beams.
TEST(Lattice, Figure2Counts) {
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, 0.1}, {{0.4, 0.6, 0}, 0.08}};
  d.beams = {{1, 0, 0, 0, 0}, {0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {1, 2, 1, 0, 0}, {1, 1, 0, 0, 1}};
  d.counts = {10, 7, 1};
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  const Lattice lat{d};
  EXPECT_EQ(lat.ball_count(), 140);
  EXPECT_EQ(lat.beam_index({0, 0, 0, 4}) - lat.beam_index({0, 0, 0, 3}), 48);
  EXPECT_EQ(lat.beam_count(), 70 + 9 * 7 + 10 * 6 + 48 + 9 * 7);
  // N[7,4,0,1] is the 8th column, 5th row: (7.4, 4.6, 0)
  EXPECT_LT(dist(lat.ball({7, 4, 0, 1}).center, {7.4, 4.6, 0}), 1e-14);
}

// Index round trips and beam existence against a brute-force enumeration, with omitted nodes.
TEST(Lattice, IndexingMatchesBruteForce) {
  std::mt19937_64 rng(5);
  const Counts counts{6, 4, 3};
  std::vector<NodeId> omitted;
  for (int q = 0; q < 15; ++q)
    omitted.push_back({static_cast<std::int64_t>(rng() % 6), static_cast<std::int64_t>(rng() % 4),
                       static_cast<std::int64_t>(rng() % 3), static_cast<int>(rng() % 2)});
  const Lattice lat = graded_lattice(counts, omitted);
  auto is_omitted = [&](const NodeId& id) {
    for (const NodeId& o : omitted)
      if (o == id) return true;
    return false;
  };
  // balls: enumerate in the documented order
  std::int64_t index = 0;
  for (std::int64_t k = 0; k < 3; ++k)
    for (std::int64_t j = 0; j < 4; ++j)
      for (std::int64_t i = 0; i < 6; ++i)
        for (int n = 0; n < 2; ++n) {
          const NodeId id{i, j, k, n};
          if (is_omitted(id)) {
            EXPECT_EQ(lat.ball_index(id), -1);
            continue;
          }
          EXPECT_EQ(lat.ball_index(id), index);
          EXPECT_TRUE(lat.ball_id(index) == id);
          ++index;
        }
  EXPECT_EQ(lat.ball_count(), index);
  // beams: pattern, then start group (k, j, i)
  index = 0;
  const auto& d = lat.definition();
  for (int p = 0; p < lat.pattern_count(); ++p)
    for (std::int64_t k = 0; k < 3; ++k)
      for (std::int64_t j = 0; j < 4; ++j)
        for (std::int64_t i = 0; i < 6; ++i) {
          const BeamPattern& b = d.beams[p];
          const NodeId s{i, j, k, b.from}, e{i + b.di, j + b.dj, k + b.dk, b.to};
          const bool exists = lat.group_exists(e.i, e.j, e.k) && !is_omitted(s) && !is_omitted(e);
          const BeamId id{i, j, k, p};
          if (!exists) {
            EXPECT_EQ(lat.beam_index(id), -1);
            continue;
          }
          EXPECT_EQ(lat.beam_index(id), index);
          EXPECT_TRUE(lat.beam_id(index) == id);
          ++index;
        }
  EXPECT_EQ(lat.beam_count(), index);
}

TEST(Lattice, BulkListingsMatchElementEvaluation) {
  const Lattice lat = graded_lattice({9, 6, 5}, {{1, 1, 1, 0}, {8, 5, 4, 1}, {0, 0, 0, 0}});
  std::vector<double> centers(3 * lat.ball_count()), radii(lat.ball_count());
  lat.balls(centers.data(), radii.data());
  lat.for_each_ball([&](std::int64_t index, const NodeId& id, const Ball& b) {
    EXPECT_EQ(lat.ball_index(id), index);
    EXPECT_LT(dist(Vec3(centers[3 * index], centers[3 * index + 1], centers[3 * index + 2]), b.center), 1e-12);
    EXPECT_NEAR(radii[index], b.radius, 1e-15);
  });
  const std::int64_t nb = lat.beam_count();
  std::vector<std::int64_t> a(nb), e(nb);
  std::vector<double> ra(nb), re(nb);
  lat.beams(a.data(), e.data(), ra.data(), re.data());
  lat.for_each_beam([&](std::int64_t index, const BeamId& id, const BeamGeometry& g) {
    EXPECT_EQ(a[index], lat.ball_index(lat.beam_start(id)));
    EXPECT_EQ(e[index], lat.ball_index(lat.beam_end(id)));
    EXPECT_NEAR(ra[index], g.start.radius, 1e-14);
    EXPECT_NEAR(re[index], g.end.radius, 1e-14);
    const Vec3 ca(centers[3 * a[index]], centers[3 * a[index] + 1], centers[3 * a[index] + 2]);
    EXPECT_LT(dist(ca, g.start.center), 1e-12);
  });
}

TEST(Lattice, ExplicitBeamRadiiScaleWithTheirGroups) {
  const Lattice lat = graded_lattice({4, 3, 3});
  const BeamId id{1, 1, 1, 4};  // pattern (1, 1,1,1, 0) with radii (0.05, 0.04)
  EXPECT_FALSE(lat.beam_exists({0, 0, 0, 6}));  // pattern (1, 0,1,-1, 0) needs k >= 1
  EXPECT_TRUE(lat.beam_exists({0, 0, 2, 6}));   // ... up to the last layer
  EXPECT_FALSE(lat.beam_exists({1, 0, 0, 7}));  // pattern (0, -2,0,1, 1) needs i >= 2
  EXPECT_TRUE(lat.beam_exists({3, 0, 0, 7}));
  const BeamGeometry g = lat.beam(id);
  const double s_start = lat.group_transform(1, 1, 1).scale, s_end = lat.group_transform(2, 2, 2).scale;
  EXPECT_NEAR(g.start.radius, 0.05 * s_start, 1e-15);
  EXPECT_NEAR(g.end.radius, 0.04 * s_end, 1e-15);
  // the hull model takes the balls' radii
  const BeamGeometry h = lat.beam({1, 1, 1, 0});
  EXPECT_NEAR(h.start.radius, lat.ball({1, 1, 1, 0}).radius, 1e-15);
}

// The interpolating controls: the last group of each direction lands where the designer put it.
TEST(Lattice, InterpolatingControlsHitTheEndFrames) {
  std::mt19937_64 rng(23);
  const std::vector<TemplateNode> nodes{{{0, 0, 0}, 0.1}};
  const std::vector<BeamPattern> beams{{0, 1, 0, 0, 0}};
  for (int trial = 0; trial < 50; ++trial) {
    const Similarity Ut = test::random_similarity(rng, 4, 2.5), Vt = test::random_similarity(rng, 2, 2.5),
                     Wt = test::random_similarity(rng, 5, 2.5), G = test::random_similarity(rng, 5);
    const Counts c{3 + trial % 5, 2 + trial % 3, 4};
    const Lattice lat = Lattice::interpolating(nodes, beams, c, Ut, Vt, Wt, G);
    EXPECT_LT(lat.group_similarity(c.u - 1, 0, 0).map_distance(G * Ut), 1e-10);
    EXPECT_LT(lat.group_similarity(0, c.v - 1, 0).map_distance(G * Vt), 1e-10);
    EXPECT_LT(lat.group_similarity(0, 0, c.w - 1).map_distance(G * Wt), 1e-10);
    // four frames
    const Frame base = G.frame();
    const Frame fu = test::random_similarity(rng, 5, 2.5).frame(), fv = test::random_similarity(rng, 4, 2.5).frame(),
                fw = test::random_similarity(rng, 1, 2.5).frame();
    const Lattice lf = Lattice::from_frames(nodes, beams, c, base, fu, fv, fw);
    EXPECT_LT(lf.group_similarity(0, 0, 0).map_distance(Similarity::from_frame(base)), 1e-12);
    EXPECT_LT(lf.group_similarity(c.u - 1, 0, 0).map_distance(Similarity::from_frame(fu)), 1e-10);
    EXPECT_LT(lf.group_similarity(0, c.v - 1, 0).map_distance(Similarity::from_frame(fv)), 1e-10);
    EXPECT_LT(lf.group_similarity(0, 0, c.w - 1).map_distance(Similarity::from_frame(fw)), 1e-10);
  }
  // a single group in a direction: no increment
  const Lattice one = Lattice::interpolating(nodes, beams, {1, 1, 1}, Similarity::translation({5, 0, 0}),
                                             Similarity::identity(), Similarity::identity());
  EXPECT_LT(brick(one).step_along(0).map_distance(Similarity::identity()), 1e-15);
  // a row winding more than a full turn keeps its turns: 9 groups over 3 pi, each a 3 pi / 8 step
  const Lattice spring = Lattice::interpolating(nodes, beams, {9, 1, 1},
                                                Similarity::screw(3 * kPi, {0, 0, 1}, {-1, 0, 0}, 8.0),
                                                Similarity::identity(), Similarity::identity());
  EXPECT_NEAR(brick(spring).step_along(0).canonical().angle, 3 * kPi / 8, 1e-14);
  EXPECT_LT(dist(spring.ball({8, 0, 0, 0}).center, {-2, 0, 8}), 1e-13);
}

std::string error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "no error";
}

TEST(Lattice, BadInputNamesTheField) {
  const std::vector<TemplateNode> nodes{{{0, 0, 0}, 0.1}, {{0.5, 0, 0}, 0.1}};
  const Similarity T = Similarity::translation({1, 0, 0});
  auto make = [&](std::vector<TemplateNode> n, std::vector<BeamPattern> b, Counts c) {
    return [=] { Lattice::incremental(n, b, c, T, T, T); };
  };
  EXPECT_NE(error_of(make({{{0, 0, 0}, -1.0}}, {}, {1, 1, 1})).find("nodes[0].radius: must be > 0"), std::string::npos);
  EXPECT_NE(error_of(make({{{0, NAN, 0}, 1.0}}, {}, {1, 1, 1})).find("nodes[0].center"), std::string::npos);
  EXPECT_NE(error_of(make({}, {}, {1, 1, 1})).find("nodes"), std::string::npos);
  EXPECT_NE(error_of(make(nodes, {}, {0, 1, 1})).find("counts.u: must be >= 1"), std::string::npos);
  EXPECT_NE(error_of(make(nodes, {}, {1, 1, -3})).find("counts.w"), std::string::npos);
  EXPECT_NE(error_of(make(nodes, {{0, 1, 0, 0, 5}}, {2, 1, 1})).find("beams[0].to: node 5 does not exist"),
            std::string::npos);
  EXPECT_NE(error_of(make(nodes, {{0, 0, 0, 0, 0}}, {2, 1, 1})).find("beams[0]: joins a node to itself"),
            std::string::npos);
  EXPECT_NE(error_of(make(nodes, {{0, 1, 0, 0, 1}, {1, -1, 0, 0, 0}}, {2, 1, 1})).find("beams[1]: describes the same"),
            std::string::npos);
  EXPECT_NE(error_of(make(nodes, {{0, 1, 0, 0, 1, -0.1, 0.1}}, {2, 1, 1})).find("beams[0].radii[0]"),
            std::string::npos);
  EXPECT_NE(error_of(make(nodes, {}, {2000000000, 2000000000, 2000000000})).find("counts"), std::string::npos);
  // scales that compound beyond floating point
  EXPECT_NE(error_of([&] {
              Lattice::incremental(nodes, {}, {1000, 1, 1}, Similarity::dilation(10.0, {0, 0, 0}), T, T);
            }).find("U, V, W"),
            std::string::npos);
  test::BrickDefinition d;
  d.nodes = nodes;
  d.counts = {2, 2, 2};
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  d.omitted = {{2, 0, 0, 0}};
  EXPECT_NE(error_of([&] { Lattice{d}; }).find("omitted[0]"), std::string::npos);
  // A step that is the identity map (also a whole turn) would put every group of its direction in one place
  // (issue 16, repro 06: the B-rep of such a lattice came out empty).
  d.omitted.clear();
  d.v = {Similarity::identity()};
  EXPECT_NE(error_of([&] { Lattice{d}; }).find("V: the step is the identity: the 2 groups along V"), std::string::npos);
  d.v = {Similarity::rotation(2 * kPi, {0, 0, 1}, {3, 0, 0})};
  EXPECT_NE(error_of([&] { Lattice{d}; }).find("V: the step is the identity"), std::string::npos);
  d.counts.v = 1;
  EXPECT_NO_THROW(Lattice{d});  // one group along V: nothing coincides
  // Similarities beyond the supported range are refused when made, naming the field (repro 05, 09).
  EXPECT_NE(error_of([] { Similarity::rotation(1e300, {0, 0, 1}, {0, 0, 0}); }).find("rotation.angle: is 1e+300, beyond"),
            std::string::npos);
  EXPECT_NE(error_of([] { Similarity::from_generator(1000, Vec3(0.0), Vec3(0.0)); }).find("log_scale"), std::string::npos);
  EXPECT_NE(error_of([] { Similarity::dilation(1e200, {0, 0, 0}).power(2); }).find("log_scale"), std::string::npos);
  EXPECT_NE(error_of([] { Similarity::translation({1e308, 0, 0}); }).find("translation.vector"), std::string::npos);
  EXPECT_LT(Similarity::rotation(0.3, {1e308, 1e308, 1e308}, {0, 0, 0}).map_distance(
                Similarity::rotation(0.3, {1, 1, 1}, {0, 0, 0})),
            1e-15);  // a huge axis is still an axis
  EXPECT_NE(error_of(make({{{1e200, 0, 0}, 0.2}}, {}, {2, 1, 1})).find("nodes[0].center: is 1e+200"), std::string::npos);
}

}  // namespace
}  // namespace steady
