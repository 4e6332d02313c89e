#include "brep/hub_group.hpp"

#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <GProp_GProps.hxx>
#include <Geom_Circle.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <tuple>

#include "brep/cusp_tolerance.hpp"
#include "brep/occ_progress.hpp"
#include "brep/pcurve_pieces.hpp"
#include "properties/shared_volume_sampling.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

// Lines the shared volume is integrated along (properties/shared_volume_sampling.hpp), as for the properties'
// clusters: there the standard error was 2.3e-5 to 1.5e-4 of the shared volume, where sampling a group's whole box
// with 400,000 points left about 0.2 % of the box (a cluster Fuse 1.4e-3 off passed such a check).
constexpr int kLines = 1600000;

Vec3 world_point(const GroupMember& m, const Vec3& canonical) { return m.center + m.radius * (m.rotation * canonical); }

// The member as the sampler reads a hub closed at its cuts: the ball, and each stump's cone from where it touches
// its end ball up to the collar, nothing of a cone beyond its collar disk (a tight collar may lie inside the ball and
// another stump reach through its disk: the closed core ends there, what lies beyond is the beam's).
Hub member_as_hub(const GroupMember& m) {
  Hub h;
  h.ball = Ball{m.center, m.radius};
  for (std::size_t k = 0; k < m.stumps.size(); ++k) {
    const CoreStump& c = m.stumps[k];
    Stump s;
    BeamCone& cone = s.cone;
    cone.a = m.center;
    cone.axis = glm::normalize(m.rotation * glm::normalize(c.direction));
    cone.ra = m.radius * c.end_radius;
    cone.sin_phi = c.sin_phi;
    cone.cos_phi = std::sqrt(std::max(0.0, 1.0 - c.sin_phi * c.sin_phi));
    // Only the end at a is read; a far end that keeps the cone's lateral surface (|ra - rb| < length).
    cone.length = 4.0 * m.radius * (1.0 + std::abs(m.core->collar_position[k]));
    cone.rb = cone.ra - cone.length * cone.sin_phi;
    cone.b = cone.a + cone.length * cone.axis;
    s.cut_position = m.radius * m.core->collar_position[k];
    s.cut = Circle{cone.a + s.cut_position * cone.axis, cone.axis, cone.radius_at(s.cut_position)};
    h.stumps.push_back(s);
  }
  return h;
}

double solid_volume(const TopoDS_Shape& shape) {
  GProp_GProps g;
  BRepGProp::VolumeProperties(shape, g, 1e-9, Standard_True);
  return g.Mass();
}

// Which outer collar disk `face` is, as (member, stump), or (-1, -1): a planar face bounded by one circle edge
// whose center, radius and axis are the collar's.
std::pair<int, int> collar_disk(const TopoDS_Face& face, const std::vector<GroupMember>& members, double tolerance) {
  const std::pair<int, int> none(-1, -1);
  const Handle(Geom_Circle) circle = disk_circle(face);
  if (circle.IsNull()) return none;
  const gp_Pnt c = circle->Location();
  const gp_Dir n = circle->Axis().Direction();
  for (std::size_t i = 0; i < members.size(); ++i) {
    const GroupMember& m = members[i];
    for (std::size_t k = 0; k < m.stumps.size(); ++k) {
      if (m.inner[k]) continue;
      const Vec3 d = glm::normalize(m.stumps[k].direction);
      const double x = m.core->collar_position[k];
      const Vec3 center = world_point(m, x * d), axis = glm::normalize(m.rotation * d);
      if (c.Distance(gp_Pnt(center.x, center.y, center.z)) < tolerance &&
          std::abs(circle->Radius() - m.radius * m.stumps[k].radius_at(x)) < tolerance &&
          std::abs(std::abs(n.X() * axis.x + n.Y() * axis.y + n.Z() * axis.z) - 1.0) < 1e-9)
        return {static_cast<int>(i), static_cast<int>(k)};
    }
  }
  return none;
}

}  // namespace

std::pair<double, double> sampled_shared_core_volume(const std::vector<GroupMember>& members, std::uint64_t seed) {
  std::vector<Hub> hubs;
  for (const GroupMember& m : members) hubs.push_back(member_as_hub(m));
  return sampled_shared_volume(hubs, kLines, 0x9e3779b97f4a7c15ull ^ seed, HubReading::ClosedAtCuts);
}

gp_Trsf hub_placement(const Vec3& center, double radius, const Mat3& m) {
  gp_Trsf t;
  const double r = radius;
  t.SetValues(r * m[0][0], r * m[1][0], r * m[2][0], center.x, r * m[0][1], r * m[1][1], r * m[2][1], center.y,
              r * m[0][2], r * m[1][2], r * m[2][2], center.z);
  return t;
}

namespace {

// Fuzzy values of the Fuse's retries, relative to the group's size. The exact Fuse of the 32 hubs of a 2 x 2 x 2
// octet whose beams are as thick as its nodes failed; 1e-7 gave the part (valid, one solid, within the sampled
// volume); 1e-5 lost 11 % of it, which the volume check refused. The edges a fuzzy Fuse makes keep a tolerance of
// that size, so the exact Fuse comes first and the smaller value before the larger.
constexpr double kFuzzyRetries[] = {0.0, 1e-7, 1e-6};

struct GroupBounds {
  double largest = 0.0, sum = 0.0;  // the members' volumes: a union lies between
  double sampled = 0.0, sigma = 0.0;  // the union's volume by the sampled shared volume, its standard error
  double size = 0.0;                // the diagonal of the group's box
};

// One Boolean Fuse of `args` with `tools`, advancing `progress`; throws InvalidInput when OpenCASCADE reports a
// failure, Cancelled when it stopped because the build was cancelled.
TopoDS_Shape fuse_shapes(const TopTools_ListOfShape& args, const TopTools_ListOfShape& tools, double fuzzy,
                         const std::string& what, Progress& progress) {
  BRepAlgoAPI_Fuse fuse;
  fuse.SetArguments(args);
  fuse.SetTools(tools);
  fuse.SetRunParallel(Standard_False);  // groups are fused in parallel
  if (fuzzy > 0.0) fuse.SetFuzzyValue(fuzzy);
  OccProgress occ(progress);
  fuse.Build(occ.range());
  occ.finish();  // a Fuse stopped by a cancel is not a failed one
  if (!fuse.IsDone() || fuse.HasErrors()) fail_input("hub", "OpenCASCADE's Fuse of " + what + " failed");
  return fuse.Shape();
}

// The placed cores fused at once, or (`one_by_one`) each added to the union of those before it: where the Fuse of
// all at once breaks, one at a time has held (the 32 hubs of an octet at beam/node 0.8 with a taper, whose
// elements meet other nodes' with overlaps down to 1e-7 of a hub's volume: 19 solids and 43 % of the volume at
// once, with or without fuzzy values; one valid solid one by one, 22 s). One by one, each addition is a part of
// `progress` and a cancel is also seen between two.
TopoDS_Shape fuse_members(const std::vector<TopoDS_Shape>& placed, double fuzzy, bool one_by_one,
                          const std::string& what, Progress& progress) {
  TopTools_ListOfShape args, tools;
  args.Append(placed[0]);
  if (!one_by_one) {
    for (std::size_t i = 1; i < placed.size(); ++i) tools.Append(placed[i]);
    return fuse_shapes(args, tools, fuzzy, what, progress);
  }
  progress.set_total(static_cast<std::int64_t>(placed.size()) - 1);
  TopoDS_Shape sum = placed[0];
  for (std::size_t i = 1; i < placed.size(); ++i) {
    progress.check();
    args.Clear();
    tools.Clear();
    args.Append(sum);
    tools.Append(placed[i]);
    Progress addition(progress, 1);
    sum = fuse_shapes(args, tools, fuzzy, what, addition);
  }
  return sum;
}

// One Fuse of the placed closed cores with its checks; throws InvalidInput naming what failed.
HubGroup fuse_once(const std::vector<GroupMember>& members, const std::vector<TopoDS_Shape>& placed,
                   const GroupBounds& bounds, double fuzzy, bool one_by_one, const std::string& what,
                   Progress& progress) {
  const TopoDS_Shape result = fuse_members(placed, fuzzy * bounds.size, one_by_one, what, progress);
  progress.check();  // the checks below are not interrupted: stop before them
  int solids = 0;
  for (TopExp_Explorer x(result, TopAbs_SOLID); x.More(); x.Next()) ++solids;
  if (solids != 1 || !BRepCheck_Analyzer(result).IsValid())
    fail_input("hub", "OpenCASCADE's Fuse of " + what + " gave " +
                          (solids != 1 ? std::to_string(solids) + " solids" : std::string("an invalid solid")));
  HubGroup out;
  const BRep_Builder b;
  b.MakeCompound(out.faces);
  out.collars.resize(members.size());
  for (std::size_t i = 0; i < members.size(); ++i) out.collars[i].resize(members[i].stumps.size());
  const double tolerance = std::max(1e-9 * bounds.size, 2.0 * fuzzy * bounds.size);
  for (TopExp_Explorer x(result, TopAbs_FACE); x.More(); x.Next()) {
    const TopoDS_Face face = TopoDS::Face(x.Current());
    const auto [i, k] = collar_disk(face, members, tolerance);
    if (i >= 0) {
      if (!out.collars[i][k].IsNull()) fail_input("hub", "the Fuse of " + what + " split a collar disk");
      TopExp_Explorer e(face, TopAbs_EDGE);
      out.collars[i][k] = TopoDS::Edge(e.Current());
      continue;
    }
    b.Add(out.faces, face);
  }
  for (std::size_t i = 0; i < members.size(); ++i)
    for (std::size_t k = 0; k < members[i].stumps.size(); ++k)
      if (!members[i].inner[k] && out.collars[i][k].IsNull()) {
        std::ostringstream os;
        os << "the Fuse of " << what << " touched the collar of stump " << k << " of the hub at (" << members[i].center.x
           << ", " << members[i].center.y << ", " << members[i].center.z << ")";
        fail_input("hub", os.str());
      }
  const double volume = solid_volume(result);
  const double slack = 1e-7 * bounds.sum;
  std::ostringstream os;
  os << "OpenCASCADE's Fuse of " << what << " encloses " << volume;
  if (!(volume >= bounds.largest - slack && volume <= bounds.sum + slack)) {
    os << ", outside [" << bounds.largest << ", " << bounds.sum << "]";
    fail_input("hub", os.str());
  }
  if (!(std::abs(volume - bounds.sampled) <= 5.0 * bounds.sigma + 1e-7 * bounds.sum)) {
    os << " where the cores less the volume they share, sampled where they meet, give " << bounds.sampled << " +- "
       << bounds.sigma;
    fail_input("hub", os.str());
  }
  give_edges_their_own_pcurves(out.faces);  // the Fuse kept the parents' pcurves on split edges
  widen_cusp_vertices(out.faces);
  return out;
}

}  // namespace

HubGroup fuse_hub_group(const std::vector<GroupMember>& members, std::uint64_t seed, const std::string& why,
                        Progress& progress) {
  const std::string what = "the " + std::to_string(members.size()) + " hubs " + why + ", built as one";
  if (members.size() < 2) fail_input("hub", "a group of hubs needs two hubs at least");
  GroupBounds bounds;
  std::vector<TopoDS_Shape> placed;
  std::vector<Hub> hubs;
  // Members share cores (similar hubs): each closed core and its volume once. Measuring it for each member took
  // 19 s of the 248 hubs of a BCC (5 x 5 x 5 cells, loaded machine), before the Fuse and out of a cancel's reach.
  std::map<const HubCore*, std::pair<TopoDS_Solid, double>> closed_cores;
  for (const GroupMember& m : members) {
    auto [it, added] = closed_cores.try_emplace(m.core);
    if (added) {
      progress.check();
      it->second.first = closed_core(*m.core);
      it->second.second = solid_volume(it->second.first);
    }
    const TopoDS_Solid& closed = it->second.first;
    const double volume = it->second.second * m.radius * m.radius * m.radius;
    bounds.largest = std::max(bounds.largest, volume);
    bounds.sum += volume;
    hubs.push_back(member_as_hub(m));  // for the box around the group
    placed.push_back(BRepBuilderAPI_Transform(closed, hub_placement(m.center, m.radius, m.rotation), Standard_True).Shape());
  }
  const auto [lo, hi] = hubs_bounds(hubs);
  bounds.size = glm::length(hi - lo);
  const auto [shared, sigma] = sampled_shared_core_volume(members, seed);
  bounds.sampled = bounds.sum - shared;  // the cores as built and measured, less what they share
  bounds.sigma = sigma;
  progress.check();
  // The first attempt (the exact Fuse of all at once) is the whole course of `progress`, in as many units as
  // OpenCASCADE's progress has (one unit would move the bar only when the Fuse ends); the retries, rarely needed,
  // take no share of it but stop at a cancel all the same.
  constexpr std::int64_t kAttemptUnits = 1000;
  progress.set_total(kAttemptUnits);
  std::string first_error;
  bool first = true;
  for (double fuzzy : kFuzzyRetries)
    for (bool one_by_one : {false, true}) {
      Progress attempt(progress, first ? kAttemptUnits : 0);
      first = false;
      try {
        HubGroup group = fuse_once(members, placed, bounds, fuzzy, one_by_one, what, attempt);
        progress.finish();
        return group;
      } catch (const InvalidInput& error) {
        if (first_error.empty()) first_error = error.what();
      }
    }
  throw InvalidInput(first_error);
}

}  // namespace steady
