// Hubs built as one (hub_group.hpp): the group's Fuse reports to the build's Progress and stops at a cancel.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "brep/foreign_groups.hpp"
#include "brep/hub_group.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/progress.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady {
namespace {

// A row of n lone balls of radius r, `spacing` apart: as members of one group (no stumps, no collars).
std::vector<GroupMember> row_of_balls(const std::shared_ptr<const HubCore>& ball, int n, double spacing, double r) {
  std::vector<GroupMember> members(n);
  for (int i = 0; i < n; ++i) {
    members[i].core = ball.get();
    members[i].center = Vec3(spacing * i, 0.0, 0.0);
    members[i].radius = r;
  }
  return members;
}

// The union of n balls of radius r in a row, each overlapping only the next (2r > spacing >= r): n balls less
// n - 1 lenses pi (4r + d)(2r - d)^2 / 12.
double row_volume(int n, double spacing, double r) {
  const double d = spacing;
  return n * 4.0 / 3.0 * M_PI * r * r * r - (n - 1) * M_PI * (4.0 * r + d) * (2.0 * r - d) * (2.0 * r - d) / 12.0;
}

// Every call of the progress callback (report interval zero, so every advance on this thread calls it); from call
// `stop_at` (1-based) on, it cancels.
struct Recorder {
  std::size_t calls = 0, stop_at = 0;
  Progress progress{[this](double) {
    ++calls;
    return stop_at == 0 || calls < stop_at;
  }};
  explicit Recorder(std::size_t stop = 0) : stop_at(stop) { progress.set_report_interval(std::chrono::milliseconds(0)); }
};

// The Fuse of a group advances the build's Progress while it runs (OpenCASCADE's progress, through OccProgress):
// a full run calls back many times. Before the Fuse starts, fuse_hub_group checks the progress twice (once per
// distinct core, here one, and after sampling), so a cancel at the third call is seen inside the Fuse: it throws
// Cancelled, with no call after the cancelling one; a cancel at a later call too.
TEST(HubGroup, TheFuseReportsProgressAndACancelInsideItThrowsCancelled) {
  const std::shared_ptr<const HubCore> ball = lone_ball_core();
  const std::vector<GroupMember> members = row_of_balls(ball, 24, 0.5, 0.3);
  Recorder full;
  const HubGroup group = fuse_hub_group(members, 0, "in a row", full.progress);
  EXPECT_FALSE(group.faces.IsNull());
  ASSERT_GE(full.calls, 20u) << "the Fuse did not report its progress";  // 1,561 measured; 5 without it
  for (std::size_t stop : {std::size_t(3), full.calls / 2}) {
    Recorder r(stop);
    EXPECT_THROW(fuse_hub_group(members, 0, "in a row", r.progress), Cancelled) << "cancelled at call " << stop;
    EXPECT_EQ(r.calls, stop) << "a call after the cancel";
  }
}

// The group's volume check: the balls' lenses by lines where they meet, against their closed form, closely enough
// to refuse a Fuse 1e-4 of the union off (the check allows 5 standard errors and 1e-7 of the members' sum; 5e-5
// measured, where 400,000 points over the group's box allowed 6 standard errors of 3.4e-3, 0.8 % of the union).
// Cores with stumps are checked the same way by every group the builds of the HubCore and BrepBuilder tests fuse.
TEST(HubGroup, TheSharedVolumeOfItsCoresIsSampledCloselyWhereTheyMeet) {
  const std::shared_ptr<const HubCore> ball = lone_ball_core();
  const int n = 24;
  const double spacing = 0.5, r = 0.3;
  const std::vector<GroupMember> members = row_of_balls(ball, n, spacing, r);
  const double sum = n * 4.0 / 3.0 * M_PI * r * r * r, lenses = sum - row_volume(n, spacing, r);
  const auto [shared, sigma] = sampled_shared_core_volume(members, 1);
  std::printf("[ report ] %d balls in a row share %.9f, sampled %.9f +- %.1e\n", n, lenses, shared, sigma);
  EXPECT_NEAR(shared, lenses, 5.0 * sigma);
  EXPECT_GT(sigma, 0.0);
  EXPECT_LT(5.0 * sigma, 1e-4 * (sum - lenses));
}

// The same through the whole build: a lattice of one group (overlapping balls of different nodes), cancelled
// while the group is fused, throws Cancelled (no partial shape); a full run afterwards is one valid solid of the
// union's exact volume.
TEST(HubGroup, ABuildCancelledWhileItsGroupIsFusedThrowsCancelled) {
  std::vector<Ball> balls;
  for (int i = 0; i < 24; ++i) balls.push_back({{0.5 * i, 0, 0}, 0.3});
  const FlatLattice f = make_flat_lattice(balls, {});
  Recorder full;
  const LatticeBrep b = build_lattice_brep(f, SeamPreference::FewestCrossings, full.progress);
  EXPECT_TRUE(is_valid(b.shape)) << validity_report(b.shape);
  EXPECT_EQ(solid_count(b.shape), 1);
  EXPECT_NEAR(shape_volume(b.shape) / row_volume(24, 0.5, 0.3), 1.0, 1e-7);
  ASSERT_GE(full.calls, 20u);
  Recorder r(full.calls / 2);
  EXPECT_THROW(build_lattice_brep(f, SeamPreference::FewestCrossings, r.progress), Cancelled);
  EXPECT_EQ(r.calls, full.calls / 2);
}

// The bar moves while a group is fused: its Fuse has a share of the build's progress (the faces' share, split
// once the hubs that may join a group are known). Before, the share was zero and the fraction stood still through
// the whole Fuse, which takes minutes from a few hundred hubs: almost every callback of the build reported the
// same fraction.
TEST(HubGroup, TheBuildsFractionMovesWhileItsGroupIsFused) {
  std::vector<Ball> balls;
  for (int i = 0; i < 24; ++i) balls.push_back({{0.5 * i, 0, 0}, 0.3});
  const FlatLattice f = make_flat_lattice(balls, {});
  std::vector<double> fractions;
  Progress progress([&](double x) {
    fractions.push_back(x);
    return true;
  });
  progress.set_report_interval(std::chrono::milliseconds(0));
  const LatticeBrep b = build_lattice_brep(f, SeamPreference::FewestCrossings, progress);
  EXPECT_EQ(b.stats.foreign_hubs, 24);
  ASSERT_GE(fractions.size(), 100u);
  std::size_t longest = 0, run = 0;
  for (std::size_t i = 0; i < fractions.size(); ++i) {
    if (i > 0) EXPECT_GE(fractions[i], fractions[i - 1]) << "call " << i;
    run = i > 0 && fractions[i] == fractions[i - 1] ? run + 1 : 1;
    longest = std::max(longest, run);
  }
  EXPECT_LT(longest, fractions.size() / 4) << "the fraction stood still for " << longest << " of " << fractions.size()
                                           << " calls";
  EXPECT_EQ(fractions.back(), 1.0);
}

}  // namespace
}  // namespace steady
