// Trimming: the disks closing the clusters' cuts, and the fates the Booleans gave them.
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include "brep/trim_phases.hpp"
#include "steady/brep/brep_io.hpp"

namespace steady::trim {
namespace {

// A disk's fate in a Boolean's result: present when the very same face is in it (non-destructive mode),
// modified when the history says so, deleted otherwise. Presence is looked up in the result itself: the
// history has reported untouched faces as deleted (OCC 7.6, seen on clusters of a tilted cylinder). `frame`:
// where the Boolean saw its arguments (see turned_frame).
Fate fate_in(BRepAlgoAPI_BooleanOperation& op, const std::unordered_set<const void*>& present, const TopoDS_Face& disk,
             const TopLoc_Location& frame) {
  if (present.count(disk.TShape().get())) return Fate::Present;
  return op.Modified(disk.Moved(frame)).IsEmpty() ? Fate::Deleted : Fate::Modified;
}

}  // namespace

void CutDisks::add(const BrepPieces& pieces, int layout, const std::unordered_map<const void*, int>& cluster_of_face,
                   const HubRoles& roles, const CutPlan& plan, const std::vector<char>* active,
                   const std::vector<BeamFrustum>& frustums) {
  // The first layout decides what each beam's disks are expected to do; another layout's disks follow it.
  std::unordered_map<std::int64_t, char> expected_by_beam;
  for (const Disk& d : disks_) expected_by_beam[d.cap->beam] = d.expected_present;
  for (const CutCap& c : pieces.caps) {
    if (!roles.open_cuts[c.beam] && !plan.split[c.beam]) continue;  // a stump toward a dropped hub keeps its disk
    Disk d;
    d.cap = &c;
    d.cluster = cluster_of_face.at(c.face.TShape().get());
    d.layout = layout;
    d.active = !active || (*active)[d.cluster];
    const auto known = expected_by_beam.find(c.beam);
    if (known != expected_by_beam.end())
      d.expected_present = known->second;
    else if (plan.boundary && !roles.open_cuts[c.beam])
      // Classified here, serially: BRepClass3d is not shared.
      d.expected_present = plan.boundary->contains(frustums[c.beam].cut_circle().center);
    index_.emplace(c.face.TShape().get(), disks_.size());
    disks_.push_back(d);
  }
}

void CutDisks::use_layout(int cluster, int layout) {
  for (Disk& d : disks_)
    if (d.cluster == cluster) d.active = d.layout == layout;
}

void CutDisks::reset_fates(const std::vector<char>* among) {
  for (Disk& d : disks_)
    if (!among || (*among)[d.cluster]) d.fate = Fate::Present, d.changed_by = -2;
}

void CutDisks::track(BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& result, int cluster,
                     const TopLoc_Location& frame, const std::vector<char>* among) {
  const std::unordered_set<const void*> present = face_set(result);
  // (A cluster's own disks first: the clusters are clipped in parallel, each writing its own disks.)
  for (Disk& d : disks_) {
    if ((cluster >= 0 && d.cluster != cluster) || !d.active || d.fate != Fate::Present) continue;
    if (among && !(*among)[d.cluster]) continue;
    d.fate = fate_in(op, present, d.cap->face, frame);
    if (d.fate != Fate::Present) d.changed_by = cluster;
  }
}

bool CutDisks::cluster_result_ok(BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& result, int cluster, int layout,
                                 const TopLoc_Location& frame) const {
  const std::unordered_set<const void*> present = face_set(result);
  for (const Disk& d : disks_) {
    if (d.cluster != cluster || d.layout != layout) continue;
    if (fate_in(op, present, d.cap->face, frame) != (d.expected_present ? Fate::Present : Fate::Deleted)) return false;
  }
  // The result must close up by itself: a Common that drops a face (a beam's cone beside an untouched ball) passes
  // the other checks and leaves the part open (docs/brep.md).
  std::vector<TopoDS_Face> all;
  std::vector<TopoDS_Shape> produced;
  for (TopExp_Explorer x(result, TopAbs_FACE); x.More(); x.Next()) {
    all.push_back(TopoDS::Face(x.Current()));
    if (!contains(x.Current())) produced.push_back(x.Current());
  }
  return free_edges(all, {}) == 0 && is_valid(compound_of(produced));
}

std::string CutDisks::check_fates(const HubRoles& roles, const CutPlan& plan, std::size_t cluster_count) const {
  std::unordered_map<std::int64_t, int> split_present;
  for (const Disk& d : disks_) {
    if (!d.active) continue;
    const std::int64_t beam = d.cap->beam;
    if (d.fate == Fate::Modified || (roles.open_cuts[beam] && d.fate != Fate::Present))
      return "the disk closing beam " + std::to_string(beam) + " at its cut (toward " +
             (plan.split[beam] ? "another boundary hub" : "an interior hub") + ") was " +
             (d.fate == Fate::Deleted ? "deleted" : "modified") + " by " +
             (d.changed_by >= 0 ? "the Boolean of boundary cluster " + std::to_string(d.changed_by) + " (of " +
                                      std::to_string(cluster_count) + ")"
                                : std::string("the final Boolean")) +
             ", though it lies clear of the boundary: OpenCASCADE misclassified it";
    if (plan.split[beam]) split_present[beam] += d.fate == Fate::Present ? 1 : 0;
  }
  for (const auto& [beam, present] : split_present)
    if (present == 1) return "only one side of the cut of beam " + std::to_string(beam) + " survived";
  return "";
}

}  // namespace steady::trim
