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
#include "properties/box_sampling.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

// Points sampled for the volume check: its standard error is then about 0.2 % of the group's box.
constexpr int kSamples = 400000;

Vec3 world_point(const GroupMember& m, const Vec3& canonical) { return m.center + m.radius * (m.rotation * canonical); }

// Whether world point p lies in the member as its closed core is: the ball, or a stump's cone between the plane
// where the cone touches its end ball and the collar, but not in a stump's cone beyond its collar disk. A tight
// collar may lie inside the ball, and another stump may reach through its disk: the closed core ends at the disk
// (what lies beyond is the beam's), so those points are not the core's. (Counted, they put the sampled volume of
// 5 hubs of an FCC at beam/node 0.8 2 % above the Fuse's, which agreed with the properties to 3e-8.)
bool inside_member(const GroupMember& m, const Mat3& inverse, const Vec3& p) {
  const Vec3 q = inverse * ((p - m.center) / m.radius);
  const double qq = glm::dot(q, q);
  bool inside = qq <= 1.0;
  for (std::size_t k = 0; k < m.stumps.size(); ++k) {
    const CoreStump& s = m.stumps[k];
    const double t = glm::dot(q, glm::normalize(s.direction));
    if (t < s.end_radius * s.sin_phi) continue;
    const double r = s.radius_at(t);
    if (!(qq - t * t <= r * r)) continue;
    if (t > m.core->collar_position[k]) return false;  // beyond the collar disk: the beam's
    inside = true;
  }
  return inside;
}

// How far the member reaches from its center (canonical units): along a stump the distance is convex in the
// axial position, so it peaks at the collar (or in the ball).
double member_reach(const GroupMember& m) {
  double reach = 1.0;
  for (std::size_t k = 0; k < m.stumps.size(); ++k) {
    const double c = m.core->collar_position[k], r = m.stumps[k].radius_at(c);
    reach = std::max(reach, std::sqrt(c * c + r * r));
  }
  return reach;
}

// The group's volume by sampling its box [lo, hi] (a fixed seed, so runs repeat) and the estimate's standard error.
std::pair<double, double> sampled_volume(const std::vector<GroupMember>& members, const Vec3& lo, const Vec3& hi,
                                         std::uint64_t seed) {
  std::vector<double> reach2;
  std::vector<Mat3> inverse;
  for (const GroupMember& m : members) {
    const double reach = m.radius * member_reach(m);
    reach2.push_back(reach * reach);
    inverse.push_back(glm::inverse(m.rotation));
  }
  return sampled_box_volume(lo, hi, kSamples, 0x9e3779b97f4a7c15ull ^ seed, [&](const Vec3& p) {
    for (std::size_t k = 0; k < members.size(); ++k) {
      const Vec3 d = p - members[k].center;
      if (glm::dot(d, d) <= reach2[k] && inside_member(members[k], inverse[k], p)) return true;
    }
    return false;
  });
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
  double sampled = 0.0, sigma = 0.0;
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
  if (!(std::abs(volume - bounds.sampled) <= 6.0 * bounds.sigma + 1e-9 * bounds.sum)) {
    os << " where sampling the hubs gives " << bounds.sampled << " +- " << bounds.sigma;
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
  Vec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
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
    const double reach = m.radius * member_reach(m);
    lo = glm::min(lo, m.center - Vec3(reach));
    hi = glm::max(hi, m.center + Vec3(reach));
    placed.push_back(BRepBuilderAPI_Transform(closed, hub_placement(m.center, m.radius, m.rotation), Standard_True).Shape());
  }
  bounds.size = glm::length(hi - lo);
  std::tie(bounds.sampled, bounds.sigma) = sampled_volume(members, lo, hi, seed);
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
