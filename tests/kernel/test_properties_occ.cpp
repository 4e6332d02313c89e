// Hub and lattice properties against OpenCASCADE's BRepGProp on solids fused from BRepPrimAPI primitives
// (explicit-radii beams: every intersection the fuse meets is transversal, where it is reliable).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "hub_test_shapes.hpp"
#include "occ_reference.hpp"
#include "steady/query/hub_overlaps.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "brick_definition.hpp"

namespace steady {
namespace {

TEST(PropertiesOcc, HubsMatchBRepGProp) {
  std::mt19937_64 rng(41);
  int compared = 0, overlapping = 0;
  double worst[3] = {0, 0, 0};
  for (int trial = 0; trial < 12; ++trial) {
    const HubShape h = test::random_hub(rng, 2 + trial % 4, test::BeamModel::ExplicitRadii);
    const auto shape = test::occ_hub(h);
    if (!shape) continue;  // OCC could not fuse this one into a valid solid
    ++compared;
    const HubProperties p = hub_properties(h);
    overlapping += !p.closed_form;
    const test::OccProperties occ = test::occ_properties(*shape);
    const MassMoments world = about(p.moments, -h.center);
    double cut = 0.0;
    for (const auto& s : p.stumps) cut += s.cut_area;
    const double d = test::hub_reach(h);
    worst[0] = std::max(worst[0], std::abs(world.volume - occ.volume) / occ.volume);
    worst[1] = std::max(worst[1], std::abs(world.area + cut - occ.area) / occ.area);
    worst[2] = std::max(worst[2], test::max_abs(central_inertia(world) - occ.inertia) / test::max_abs(occ.inertia));
    EXPECT_NEAR(world.volume, occ.volume, 1e-6 * occ.volume) << "trial " << trial;
    EXPECT_NEAR(world.area + cut, occ.area, 1e-6 * occ.area) << "trial " << trial;
    EXPECT_LT(glm::length(centroid(world) - occ.centroid), 1e-6 * d) << "trial " << trial;
    EXPECT_LT(test::max_abs(central_inertia(world) - occ.inertia), 1e-6 * occ.volume * d * d) << "trial " << trial;
  }
  EXPECT_GE(compared, 10);
  EXPECT_GE(overlapping, 3);
  std::printf("[ report ] hubs vs BRepGProp: %d compared (%d with overlapping caps), largest relative difference "
              "volume %.2e, area %.2e, inertia %.2e\n",
              compared, overlapping, worst[0], worst[1], worst[2]);
}

TEST(PropertiesOcc, SmallLatticesMatchBRepGProp) {
  // Bent and graded BCC-like lattices with explicit radii (caps overlap at every node: the quadrature runs),
  // one with an omitted node; OCC fuses every ball and beam.
  struct Case {
    Counts counts;
    bool omit;
  };
  int compared = 0;
  for (const Case& cs : {Case{{2, 2, 2}, false}, Case{{3, 2, 2}, true}}) {
    test::BrickDefinition d;
    d.nodes = {{Vec3(0.0), 0.2}, {Vec3(0.5, 0.5, 0.5), 0.18}};
    d.beams = {{0, 1, 0, 0, 0, 0.1, 0.1}, {0, 0, 1, 0, 0, 0.1, 0.1}, {0, 0, 0, 1, 0, 0.1, 0.1},
               {0, 0, 0, 0, 1, 0.12, 0.1}, {1, 1, 1, 1, 0, 0.1, 0.12}, {1, 1, 0, 0, 0, 0.09, 0.11}};
    d.counts = cs.counts;
    // bent and graded along i, twisted along k; stronger bending (0.08 rad, scale 1.05) makes the lattice
    // non-clean (see the clean-check tests)
    d.u = {Similarity::swirl(0.05, {0, 0, 1}, {0.5, -6, 0}, 1.03) * Similarity::translation({1, 0, 0})};
    d.v = {Similarity::translation({0, 1.1, 0})};
    d.w = {Similarity::rotation(0.12, {1, 0, 0}, {0, 0, -5}) * Similarity::translation({0, 0, 1})};
    d.placement = Similarity::rotation(0.4, {1, 2, 3}, {1, 0, 0});
    if (cs.omit) d.omitted = {{1, 0, 1, 1}};
    const Lattice lat(d);
    ASSERT_TRUE(check_hub_overlaps(lat).clean());
    std::vector<TopoDS_Shape> pieces;
    lat.for_each_ball([&](std::int64_t, const NodeId&, const Ball& b) {
      pieces.push_back(BRepPrimAPI_MakeSphere(test::occ_point(b.center), b.radius).Shape());
    });
    lat.for_each_beam([&](std::int64_t, const BeamId&, const BeamGeometry& g) {
      pieces.push_back(test::occ_beam(g.start.center, g.start.radius, g.end.center, g.end.radius));
    });
    const auto shape = test::occ_fuse(pieces);
    ASSERT_TRUE(shape.has_value()) << "OCC could not fuse the lattice into a valid solid";
    ++compared;
    const test::OccProperties occ = test::occ_properties(*shape);
    const LatticeProperties p = lattice_properties(lat);
    EXPECT_GT(p.overlapping_hub_shapes, 0);
    const double size = std::cbrt(occ.volume);
    EXPECT_NEAR(p.volume, occ.volume, 1e-6 * occ.volume);
    EXPECT_NEAR(p.area, occ.area, 1e-6 * occ.area);
    EXPECT_LT(glm::length(p.centroid - occ.centroid), 1e-6 * size);
    EXPECT_LT(test::max_abs(p.inertia - occ.inertia), 1e-6 * test::max_abs(occ.inertia));
    std::printf("[ report ] lattice %lldx%lldx%lld (%lld balls, %lld beams) vs BRepGProp: volume %.2e, area %.2e, "
                "inertia %.2e relative\n",
                (long long)cs.counts.u, (long long)cs.counts.v, (long long)cs.counts.w, (long long)lat.ball_count(),
                (long long)lat.beam_count(), std::abs(p.volume - occ.volume) / occ.volume,
                std::abs(p.area - occ.area) / occ.area, test::max_abs(p.inertia - occ.inertia) / test::max_abs(occ.inertia));
  }
  EXPECT_EQ(compared, 2);
}

}  // namespace
}  // namespace steady
