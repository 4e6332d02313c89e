#pragma once
// Crowded hubs built as one. Where a beam is shorter than its two crowded hubs' collars (the neighbours at each
// end meet it past the other hub's collar: an octet or FCC node whose beams are nearly as thick as the node), no
// hub-by-hub construction holds. The hubs joined by such beams form a group, built by one Boolean Fuse of their
// cores, each closed by its collar disks and placed by similarity: the beams inside the group are covered by the
// two overlapping stumps, and the group keeps the collars of the beams that leave it, as a single core would.
// Each core is exact (hub_core.hpp) and the Fuse sees transversal contacts only, apart from the stumps of an inner
// beam, which lie on one cone.
#include <BRepBuilderAPI_Transform.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <gp_Trsf.hxx>

#include <cstdint>
#include <utility>
#include <vector>

#include "brep/hub_core.hpp"
#include "steady/core/progress.hpp"
#include "steady/core/vec.hpp"

namespace steady {

// One hub of a group: its core, where it is placed (world = center + radius * rotation * canonical), and which
// of its stumps (in the core's order) belong to beams inside the group.
struct GroupMember {
  const HubCore* core = nullptr;
  std::vector<CoreStump> stumps;  // canonical, as the core was built
  Vec3 center{0.0};
  double radius = 1.0;
  Mat3 rotation{1.0};
  std::vector<char> inner;  // per stump
};

struct HubGroup {
  TopoDS_Compound faces;                          // an open shell bounded by the outer collars
  std::vector<std::vector<TopoDS_Edge>> collars;  // per member, per stump: its collar (null when inner)
};

// The transform that places canonical coordinates of a hub (unit ball at the origin) at `center`, scaled by
// `radius` and turned by `rotation`.
gp_Trsf hub_placement(const Vec3& center, double radius, const Mat3& rotation);

// The volume the members' closed cores share (the sum of their volumes less their union's) by their own
// definition: the ball, and each stump's cone from where it touches its end ball up to the collar, but nothing of
// a cone beyond its collar disk. Integrated along lines where the cores meet (properties/shared_volume_sampling.hpp;
// a fixed seed, so runs repeat); returns the estimate and its standard error.
std::pair<double, double> sampled_shared_core_volume(const std::vector<GroupMember>& members, std::uint64_t seed);

// Fuses the members' closed cores and checks the result: done without errors, one valid solid, every outer collar
// disk found untouched (a planar face bounded by that collar circle alone), and the volume it encloses within the
// bounds of a union (no less than the largest member, no more than their sum) and equal, within 5 standard errors and
// 1e-7 of their sum, to the cores' volumes less the volume they share by their own definition (ball, and each
// stump's cone up to its collar), integrated along lines where they meet (properties/shared_volume_sampling.hpp).
// Where a check fails, the Fuse is tried
// again with small fuzzy values. Throws InvalidInput (field "hub") with the first failure when all fail, naming the
// group as "the N hubs <why>". Every Fuse (the retries too) reports to `progress` and stops at OpenCASCADE's next
// UserBreak check once it is cancelled; the call then throws Cancelled (never a partial shape). A Fuse grows about
// as n^1.6 with the group's n hubs (docs/brep.md): minutes for hundreds of hubs, so a cancel must reach it.
HubGroup fuse_hub_group(const std::vector<GroupMember>& members, std::uint64_t seed, const std::string& why,
                        Progress& progress);

}  // namespace steady
