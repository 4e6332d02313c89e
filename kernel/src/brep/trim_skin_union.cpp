// Trimming: the faces the boundary band contributes, united with the skin where there is one (docs/brep.md,
// "skin"): by holes in the skin's inner faces where the clipped clusters' cut faces can be holes (no Boolean,
// skin_holes.hpp); for the clusters on the inner boundary's edges and seams, one Cut through the pores (when they
// hold most of the band) or a glued Fuse; and through the pores for every cluster should that go wrong.
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <fstream>
#include <memory>

#include "brep/trim_phases.hpp"
#include "steady/brep/brep_io.hpp"

namespace steady::trim {
namespace {

// Checks one way of gluing: the disks met their fates, the Boolean's faces are valid (OpenCASCADE reports success
// on some results it got wrong: only what it produced is checked, and not again when `faces_checked` says the
// clusters' checks already did; `checked` holds faces checked before), and a union with the skin closes up.
// Adds the faces to keep (all of `merged` but the disks) to `kept`; returns an error message, or empty.
std::string collect(UnionContext& u, const TopoDS_Shape& merged, bool pores, std::vector<TopoDS_Face>& kept,
                    bool faces_checked = false, const std::unordered_set<const void*>& checked = {}) {
  const ClipContext& c = u.clip;
  const std::string fates = u.disks.check_fates(c.roles, c.plan, c.clusters.faces.size());
  if (!fates.empty()) return fates;
  for (TopExp_Explorer x(merged, TopAbs_FACE); x.More(); x.Next())
    if (!u.disks.contains(x.Current())) kept.push_back(TopoDS::Face(pores ? x.Current().Reversed() : x.Current()));
  if (c.options.verify_booleans && !faces_checked) {
    u.progress.check();
    std::vector<TopoDS_Shape> unchecked;
    for (const TopoDS_Face& face : kept)
      if (!checked.count(face.TShape().get())) unchecked.push_back(face);
    const TopoDS_Shape produced = compound_of(unchecked);
    if (!is_valid(produced)) return "its Boolean produced invalid faces (" + validity_report(produced, 2) + ")";
    u.progress.advance(u.verify_weight);
  }
  // A union with the skin must close up with the interior's faces: the checks above look at the faces one by one,
  // and a glued Fuse (once used for the rim clusters) passed them and still left a part that was not closed
  // (docs/brep.md).
  if (c.unite)
    if (const std::int64_t open = free_edges(kept, u.interior_faces)) {
      if (!c.options.dump_directory.empty()) {
        std::vector<TopoDS_Shape> open_faces;
        free_edges(kept, u.interior_faces, &open_faces);
        std::ofstream(c.options.dump_directory + "/open_faces.brep") << brep_to_text(compound_of(open_faces));
      }
      return "its faces leave " + std::to_string(open) + " edges open";
    }
  return "";
}

// The union with the skin through the pores: body \ (inner \ band). The band only meets the inner boundary (what it
// has outside the body falls away by itself), and no two faces of the Boolean coincide; the part is the body with
// the pores as voids.
std::string through_pores(UnionContext& u, std::vector<TopoDS_Face>& kept) {
  const Bodies& bodies = u.clip.bodies;
  u.disks.reset_fates();
  BRepAlgoAPI_Cut op;
  Progress part(u.progress, u.union_weight);
  const TopoDS_Shape pores = run_boolean(op, text_copy(bodies.skin->inner), compound_of(u.clips.unclipped),
                                         "Cut of the inner body by the boundary hubs", part);
  u.disks.track(op, pores, -1);
  for (TopExp_Explorer x(bodies.body.solid(), TopAbs_FACE); x.More(); x.Next()) kept.push_back(TopoDS::Face(x.Current()));
  return collect(u, pores, true, kept);
}

// The skin's faces, split by inner face: per inner face (1-based), its pieces (itself, or what the rim clusters'
// Boolean left of it, facing the pores as in the skin) in `pieces`; the body's shell and the rim clusters' faces in
// `others`. `rim`: per cluster, those on the inner boundary's rims (edges, seams, poles), whose cut faces cannot be
// holes; `rim_solids`: theirs, clipped (a glued Fuse of them with the skin) or, with `rim_cut`, unclipped (a Cut of
// the inner body by them: skin U (rims n inner) = body \ (inner \ rims), through the pores). `untouched`: gains
// the Cut's faces it passed on unchanged (built exactly: not checked again).
std::string skin_pieces(UnionContext& u, const std::vector<char>& rim, const std::vector<TopoDS_Shape>& rim_solids,
                        bool rim_cut, const TopTools_IndexedMapOfShape& inner_faces,
                        std::vector<std::vector<TopoDS_Face>>& pieces, std::vector<TopoDS_Face>& others,
                        std::unordered_set<const void*>& untouched) {
  const Skin& skin = *u.clip.bodies.skin;
  std::unordered_map<const void*, int> inner_of;  // by TShape
  if (rim_solids.empty()) {
    for (int i = 1; i <= inner_faces.Extent(); ++i) inner_of.emplace(inner_faces(i).TShape().get(), i);
    for (TopExp_Explorer x(skin.skin, TopAbs_FACE); x.More(); x.Next()) {
      const auto it = inner_of.find(x.Current().TShape().get());
      (it == inner_of.end() ? others : pieces[it->second]).push_back(TopoDS::Face(x.Current()));
    }
    return "";
  }
  Progress part(u.progress, u.union_weight);
  const TopoDS_Shape tool = compound_of(rim_solids);
  TopTools_IndexedMapOfShape skin_faces, copy_faces;
  TopExp::MapShapes(skin.skin, TopAbs_FACE, skin_faces);
  std::unique_ptr<BRepAlgoAPI_BooleanOperation> op;
  TopoDS_Shape copy, merged;
  if (rim_cut) {
    for (TopExp_Explorer x(skin.skin, TopAbs_FACE); x.More(); x.Next())
      if (!inner_faces.Contains(x.Current())) others.push_back(TopoDS::Face(x.Current()));  // the body's shell
    op = std::make_unique<BRepAlgoAPI_Cut>();
    copy = text_copy(skin.inner);
    merged = run_boolean(*op, copy, tool, "Cut of the inner body by the boundary clusters on its rims", part);
  } else {
    op = std::make_unique<BRepAlgoAPI_Fuse>();
    op->SetGlue(BOPAlgo_GlueShift);
    copy = text_copy(skin.skin);
    merged = run_boolean(*op, copy, tool, "glued Fuse with the skin", part);
  }
  u.disks.track(*op, merged, -1, TopLoc_Location(), &rim);
  TopExp::MapShapes(copy, TopAbs_FACE, copy_faces);
  if (copy_faces.Extent() != (rim_cut ? inner_faces : skin_faces).Extent())
    return "the skin read back from BREP text differs";
  for (int i = 1; i <= inner_faces.Extent(); ++i) {
    const int at = rim_cut ? i : skin_faces.FindIndex(inner_faces(i));  // where the copy holds inner face i
    inner_of.emplace(copy_faces(at).TShape().get(), i);
    for (TopTools_ListOfShape::Iterator it(op->Modified(copy_faces(at))); it.More(); it.Next())
      inner_of.emplace(it.Value().TShape().get(), i);
  }
  const std::unordered_set<const void*> before = rim_cut ? face_set(tool) : std::unordered_set<const void*>();
  for (TopExp_Explorer x(merged, TopAbs_FACE); x.More(); x.Next()) {
    // The Cut's faces bound the pores: turned, they bound the part.
    const TopoDS_Face face = TopoDS::Face(rim_cut ? x.Current().Reversed() : x.Current());
    const auto it = inner_of.find(face.TShape().get());
    (it == inner_of.end() ? others : pieces[it->second]).push_back(face);
    if (before.count(face.TShape().get())) untouched.insert(face.TShape().get());
  }
  return "";
}

// The union with the skin by holes in its inner faces for the clusters whose cut faces can be holes, and for the
// others (clusters on the inner boundary's rims: edges, seams, poles) a Cut through the pores (`rim_cut`: their
// Commons were not run) or a glued Fuse.
std::string through_holes(UnionContext& u, bool rim_cut, std::vector<TopoDS_Face>& kept, TrimStats& stats) {
  const ClusterClips& clips = u.clips;
  const std::size_t count = u.clip.clusters.faces.size();
  TopTools_IndexedMapOfShape inner_faces;
  TopExp::MapShapes(u.clip.bodies.skin->inner, TopAbs_FACE, inner_faces);
  std::vector<TopoDS_Face> faces_out;  // the union's faces but the inner boundary's
  // Faces checked already: the clusters' glued by holes (after their Common), the pierced ones (by pierce), the
  // faces of the rim clusters the Cut left untouched (built exactly).
  std::unordered_set<const void*> checked;
  std::vector<std::vector<TopoDS_Face>> pieces(inner_faces.Extent() + 1), holes(inner_faces.Extent() + 1);
  std::vector<char> rim(count, 0);
  std::vector<TopoDS_Shape> rim_solids;
  for (std::size_t k = 0; k < count; ++k) {
    if (!clips.as_holes[k]) {
      rim[k] = 1;
      rim_solids.push_back(rim_cut ? clips.unclipped[k] : clips.results[k]);
      ++stats.rim_clusters;
      stats.rim_clusters_unclipped += clips.on_rim[k];
      continue;
    }
    ++stats.holed_clusters;
    std::unordered_set<const void*> cut;
    for (const CutFace& face : clips.cut_faces[k]) {
      cut.insert(face.face.TShape().get());
      holes[face.inner_face].push_back(face.face);
    }
    for (TopExp_Explorer x(clips.results[k], TopAbs_FACE); x.More(); x.Next())
      if (!cut.count(x.Current().TShape().get())) {
        faces_out.push_back(TopoDS::Face(x.Current()));
        checked.insert(x.Current().TShape().get());
      }
  }
  const std::string error = skin_pieces(u, rim, rim_solids, rim_cut, inner_faces, pieces, faces_out, checked);
  if (!error.empty()) return error;
  for (int i = 1; i <= inner_faces.Extent(); ++i) {
    if (holes[i].empty()) {
      faces_out.insert(faces_out.end(), pieces[i].begin(), pieces[i].end());
      continue;
    }
    std::string pierce_error;
    const std::vector<TopoDS_Face> pierced = pierce(pieces[i], holes[i], u.clip.options.verify_booleans, pierce_error);
    if (!pierce_error.empty()) return "holes in the skin: " + pierce_error;
    faces_out.insert(faces_out.end(), pierced.begin(), pierced.end());
    for (const TopoDS_Face& face : pierced) checked.insert(face.TShape().get());  // pierce checked them
  }
  return collect(u, compound_of(std::vector<TopoDS_Shape>(faces_out.begin(), faces_out.end())), false, kept, false,
                 checked);
}

}  // namespace

std::string band_faces(UnionContext& u, std::vector<TopoDS_Face>& kept, TrimStats& stats) {
  const ClipContext& c = u.clip;
  if (c.unite && c.options.policy == TrimPolicy::Clip) {
    // skin U (lattice n inner): the clipped clusters touch the skin only along their cut faces, pieces of the inner
    // boundary's faces that nothing crosses.
    const bool rim_cut = std::any_of(u.clips.on_rim.begin(), u.clips.on_rim.end(), [](char x) { return x; });
    std::string error = through_holes(u, rim_cut, kept, stats);
    if (error.empty()) return "";
    if (rim_cut && u.clip_rim_clusters) {
      // One Boolean for every rim cluster has no retries of its own: the clusters are clipped one by one as the
      // others were (with their retries), then glued to the skin by a Fuse.
      kept.clear();
      stats.holed_clusters = stats.rim_clusters = stats.rim_clusters_unclipped = 0;
      stats.rim_cut_reason = error;
      report(c.options, "trim: the rim clusters' Cut: " + error + "; clipping them one by one");
      u.clip_rim_clusters();
      error = through_holes(u, false, kept, stats);
      if (error.empty()) return "";
    }
    kept.clear();
    stats.union_through_pores = true;
    stats.pores_reason = error;
    report(c.options, "trim: through the pores: " + error);  // as soon as it happens: a pores' Cut can be long
    stats.holed_clusters = stats.rim_clusters = stats.rim_clusters_unclipped = 0;
    const std::string retry = through_pores(u, kept);
    return retry.empty() ? "" : error + "; and through the pores: " + retry;
  }
  if (c.unite) return through_pores(u, kept);  // Whole: hubs are never cut, so they cross the inner boundary
  // The clipped clusters' faces were each checked right after their Common (cluster_result_ok).
  return collect(u, compound_of(u.clips.results), false, kept, u.clips.tool != nullptr);
}

}  // namespace steady::trim
