// Hub and lattice properties against OpenCASCADE's BRepGProp on solids fused from BRepPrimAPI primitives
// (explicit-radii beams: every intersection the fuse meets is transversal, where it is reliable).
#include <gtest/gtest.h>

#include <cstdio>
#include <random>

#include "hub_test_shapes.hpp"
#include "occ_reference.hpp"

namespace steady {
namespace {

double max_abs(const Mat3& m) {
  double v = 0.0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) v = std::max(v, std::abs(m[i][j]));
  return v;
}

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
    worst[2] = std::max(worst[2], max_abs(central_inertia(world) - occ.inertia) / max_abs(occ.inertia));
    EXPECT_NEAR(world.volume, occ.volume, 1e-6 * occ.volume) << "trial " << trial;
    EXPECT_NEAR(world.area + cut, occ.area, 1e-6 * occ.area) << "trial " << trial;
    EXPECT_LT(glm::length(centroid(world) - occ.centroid), 1e-6 * d) << "trial " << trial;
    EXPECT_LT(max_abs(central_inertia(world) - occ.inertia), 1e-6 * occ.volume * d * d) << "trial " << trial;
  }
  EXPECT_GE(compared, 10);
  EXPECT_GE(overlapping, 3);
  std::printf("[ report ] hubs vs BRepGProp: %d compared (%d with overlapping caps), largest relative difference "
              "volume %.2e, area %.2e, inertia %.2e\n",
              compared, overlapping, worst[0], worst[1], worst[2]);
}

}  // namespace
}  // namespace steady
