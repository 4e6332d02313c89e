// Trimming: each boundary cluster's Common with the boundary, in parallel, and the retry ladder of the clusters
// whose first Common failed (docs/brep.md, "retries").
#include <BRepAlgoAPI_Common.hxx>
#include <BRepBndLib.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "brep/clip_retries.hpp"
#include "brep/merged_bands.hpp"
#include "brep/occ_progress.hpp"
#include "brep/trim_phases.hpp"
#include "steady/brep/brep_io.hpp"

namespace steady::trim {

// ---- helpers shared by the phases ----------------------------------------------------------------------------

TopoDS_Shape compound_of(const std::vector<TopoDS_Shape>& shapes) {
  TopoDS_Compound c;
  const BRep_Builder b;
  b.MakeCompound(c);
  for (const TopoDS_Shape& s : shapes) b.Add(c, s);
  return c;
}

TopoDS_Shape text_copy(const TopoDS_Shape& shape) { return brep_from_text(brep_to_text(shape), "body"); }

TopoDS_Shape run_boolean(BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& a, const TopoDS_Shape& b,
                         const char* what, Progress& progress) {
  TopTools_ListOfShape args, tools;
  args.Append(a);
  tools.Append(b);
  op.SetArguments(args);
  op.SetTools(tools);
  op.SetNonDestructive(Standard_True);
  op.SetRunParallel(Standard_True);
  OccProgress occ(progress);
  op.Build(occ.range());
  occ.finish();  // a Boolean stopped by a cancel is not a failed one
  if (!op.IsDone() || op.HasErrors()) {
    std::ostringstream os;
    os << "OpenCASCADE's " << what << " of the boundary hubs failed";
    if (op.HasErrors()) {
      os << ": ";
      op.DumpErrors(os);
    }
    throw std::runtime_error(os.str());
  }
  return op.Shape();
}

std::optional<TopoDS_Shape> try_boolean(BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& a, const TopoDS_Shape& b,
                                        const char* what, Progress& progress) {
  try {
    return run_boolean(op, a, b, what, progress);
  } catch (const Cancelled&) {
    throw;
  } catch (const std::runtime_error&) {
    return std::nullopt;
  } catch (const Standard_Failure&) {
    return std::nullopt;
  }
}

std::int64_t free_edges(const std::vector<TopoDS_Face>& a, const std::vector<TopoDS_Face>& b,
                        std::vector<TopoDS_Shape>* open_faces) {
  std::unordered_map<const void*, int> uses;
  for (const auto* faces : {&a, &b})
    for (const TopoDS_Face& face : *faces)
      for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next())
        if (!BRep_Tool::Degenerated(TopoDS::Edge(x.Current()))) ++uses[x.Current().TShape().get()];
  std::int64_t open = 0;
  for (const auto& [edge, count] : uses) open += count == 1;
  if (open_faces)
    for (const auto* faces : {&a, &b})
      for (const TopoDS_Face& face : *faces)
        for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next())
          if (uses[x.Current().TShape().get()] == 1) {
            open_faces->push_back(face);
            break;
          }
  return open;
}

std::unordered_set<const void*> face_set(const TopoDS_Shape& shape) {
  std::unordered_set<const void*> faces;
  for (TopExp_Explorer x(shape, TopAbs_FACE); x.More(); x.Next()) faces.insert(x.Current().TShape().get());
  return faces;
}

void report(const TrimOptions& options, const std::string& message) {
  if (options.report) options.report(message);
}

// ---- the first Common of every cluster -----------------------------------------------------------------------

namespace {

// With a skin: a clipped cluster's cut faces (on the inner boundary), and whether they can be holes in it.
void find_cut_faces(const ClipContext& c, BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& tool_passed,
                    std::size_t cluster, ClusterClips& clips) {
  if (!c.unite) return;
  TopTools_IndexedMapOfShape tool_faces;
  TopExp::MapShapes(tool_passed, TopAbs_FACE, tool_faces);
  clips.cut_faces[cluster] = cut_faces(op, tool_faces, clips.results[cluster]);
  clips.as_holes[cluster] = cut_faces_are_holes(clips.results[cluster], clips.cut_faces[cluster]);
}

// With a skin: the clusters whose hubs' bounding pieces come within reach of the inner boundary's edges, seams or
// vertices. Their cut faces would run along those edges (or hold a pore, on a lattice dense enough to cover an
// edge), so they could not be holes, and they are united with the skin through the pores, in one Cut of the inner
// body by all of them, unclipped. That pays where they hold most of the band: the 10,800-beam dense octet's band
// is a single cluster of 13,162 faces, whose Common took 31 s, the check of what it produced 15 s (7.7 s of it on
// its 365-wire cut face) and the glued Fuse with the skin 16 s, where the Cut takes 29 s. Where they are a small part of the band their Commons
// (each retried on its own should OpenCASCADE fail) and the glued Fuse are cheap, and one Cut of all of them has
// no retries: on the 10,095-beam benchmark with a skin (41 of 601 clusters) it left a self-intersecting wire, and
// the fallback cost 7 s. So none is marked unless the marked clusters hold at least half of the band's faces.
std::vector<char> clusters_on_rims(const ClipContext& c) {
  std::vector<char> out(c.clusters.faces.size(), 0);
  if (!c.unite || c.options.policy != TrimPolicy::Clip || !c.bodies.inner || !c.options.rim_cut) return out;
  const std::vector<std::vector<Piece>> pieces = hub_pieces(c.f, c.frustums, no_progress());
  const SolidBody& inner = *c.bodies.inner;
  const double clearance = kClearanceRelative * inner.size();
  std::vector<char> near(c.f.ball_count(), 0);
  tbb::parallel_for(std::int64_t(0), c.f.ball_count(), [&](std::int64_t i) {
    if (!c.roles.band[i]) return;
    for (const Piece& p : pieces[i])
      if (!(inner.edge_distance_lower_bound(p.center) > p.radius + clearance)) {
        near[i] = 1;
        return;
      }
  });
  for (std::int64_t i = 0; i < c.f.ball_count(); ++i)
    if (near[i]) out[c.clusters.of_ball(c.plan, i)] = 1;
  std::size_t marked_faces = 0, band_faces = 0;
  for (std::size_t k = 0; k < out.size(); ++k) {
    band_faces += c.clusters.faces[k].size();
    if (out[k]) marked_faces += c.clusters.faces[k].size();
  }
  if (2 * marked_faces < band_faces) std::fill(out.begin(), out.end(), 0);
  return out;
}

bool is_empty(const TopoDS_Shape& shape) { return !TopExp_Explorer(shape, TopAbs_FACE).More(); }

// Per cluster: whether a ball of it has its centre inside the tool (the clip's boundary), farther from the
// boundary than the Booleans' tolerances. The first such ball of each cluster is enough; balls whose centre is
// near the boundary by the fast bound are skipped (the classifier and the exact distance are serial).
std::vector<char> clusters_that_cannot_be_empty(const ClipContext& c) {
  std::vector<char> out(c.clusters.faces.size(), 0);
  const SolidBody* boundary = c.plan.boundary;
  if (!boundary) return out;
  const double margin = 1e-6 * boundary->size();
  for (std::int64_t i = 0; i < c.f.ball_count(); ++i) {
    if (!c.roles.band[i]) continue;
    const auto found = c.clusters.index.find(c.plan.cluster_root[i]);
    if (found == c.clusters.index.end() || out[found->second]) continue;
    const Vec3& center = c.f.balls[i].center;
    if (boundary->distance_lower_bound(center) > margin && boundary->contains(center)) out[found->second] = 1;
  }
  return out;
}

// The Common of cluster k (its unclipped solid) with the tool; marked failed for the retries when it fails or its
// result does not pass cluster_result_ok.
void clip_one(const ClipContext& c, std::size_t k, ClusterClips& clips, CutDisks& disks, Progress& progress) {
  progress.advance(1);
  // Each cluster is clipped against its own copy of the body (the Booleans share no mutable data), read back from
  // BREP text: against the in-memory shape OpenCASCADE's Common misclassified untouched disks that the text copy
  // clips right, and took twice as long (docs/brep.md).
  const TopoDS_Shape copy = brep_from_text(clips.tool_text, "body");
  BRepAlgoAPI_Common op;
  Progress boolean(progress, 9);
  const std::optional<TopoDS_Shape> clipped = try_boolean(op, clips.unclipped[k], copy, clips.what, boolean);
  const int cluster_id = static_cast<int>(k);
  if (!clipped || (c.options.verify_booleans && !disks.cluster_result_ok(op, *clipped, cluster_id, 0)) ||
      (clips.cannot_be_empty[k] && is_empty(*clipped))) {
    clips.failed[k] = 1;  // tried again (retry_failed_clusters)
  } else {
    clips.results[k] = *clipped;
    disks.track(op, clips.results[k], cluster_id);
    find_cut_faces(c, op, copy, k, clips);
  }
}

}  // namespace

ClusterClips clip_clusters(const ClipContext& c, CutDisks& disks, Progress& progress) {
  const std::size_t count = c.clusters.faces.size();
  ClusterClips clips;
  if (c.options.policy == TrimPolicy::Clip) {
    clips.tool = c.bodies.skin ? &c.bodies.skin->inner : &c.bodies.body.solid();
    clips.what = c.bodies.skin ? "Common with the inner body" : "Common with the body";
  }
  clips.tool_text = clips.tool ? brep_to_text(*clips.tool) : std::string();
  clips.results.resize(count);
  clips.unclipped.resize(count);
  clips.failed.assign(count, 0);
  clips.cannot_be_empty = clusters_that_cannot_be_empty(c);
  clips.cut_faces.resize(count);
  clips.as_holes.assign(count, 0);
  clips.on_rim = clusters_on_rims(c);
  // Each cluster's share of the progress is its number of faces; a cancel stops the clusters not yet started,
  // and the running Booleans at their next check.
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t k) {
    Progress cluster(progress, static_cast<std::int64_t>(c.clusters.faces[k].size()), 10);
    cluster.check();
    clips.unclipped[k] = solids_from_faces(c.clusters.faces[k]);
    clips.results[k] = clips.unclipped[k];
    if (clips.tool && !clips.on_rim[k]) clip_one(c, k, clips, disks, cluster);
    cluster.finish();
  });
  progress.finish();
  return clips;
}

// ---- the retries ---------------------------------------------------------------------------------------------

namespace {

// The failed clusters' hubs (and their beams) built again with the spheres laid out the other way: only those, a
// crowded hub's core in the other layout can take minutes. Both layouts share the cut circles.
std::vector<std::vector<TopoDS_Face>> second_layout_faces(const ClipContext& c, SeamPreference seams, CutEdges& cuts,
                                                          const ClusterClips& clips, CutDisks& disks,
                                                          BrepPieces& second) {
  const FlatLattice& f = c.f;
  std::unordered_map<std::int64_t, std::size_t> vertices_before;
  for (const auto& [beam, circle] : cuts) vertices_before[beam] = circle.vertices.size();
  BrepSelection other;
  other.balls.assign(f.ball_count(), 0);
  other.beams.assign(f.beam_count(), 0);
  for (std::int64_t i = 0; i < f.ball_count(); ++i)
    other.balls[i] = c.roles.band[i] && clips.failed[c.clusters.of_ball(c.plan, i)];
  for (std::int64_t e = 0; e < f.beam_count(); ++e)
    other.beams[e] = c.roles.band_beams[e] && (other.balls[f.beams[e].a] || other.balls[f.beams[e].b]);
  other.split = c.plan.split;
  other.cut_fractions = c.plan.cut_fractions;
  other.foreign = &c.roles.contacts;
  other.seams = seams == SeamPreference::FewestCrossings ? SeamPreference::MostCrossings : SeamPreference::FewestCrossings;
  second = build_brep_pieces(f, other, cuts);
  for (const auto& [beam, count] : vertices_before)
    if (cuts.at(beam).vertices.size() != count)
      throw std::runtime_error("trim: the second layout of the boundary hubs changed a shared cut circle");
  std::vector<std::vector<TopoDS_Face>> faces(c.clusters.faces.size());
  std::unordered_map<const void*, int> cluster_of_face;
  for (std::size_t k = 0; k < second.faces.size(); ++k) {
    const int cluster = c.clusters.of_ball(c.plan, second.face_owner[k]);
    faces[cluster].push_back(second.faces[k]);
    cluster_of_face.emplace(second.faces[k].TShape().get(), cluster);
  }
  disks.add(second, 1, cluster_of_face, c.roles, c.plan, &clips.failed, c.frustums);
  return faces;
}

struct RetryCounts {
  std::atomic<std::int64_t> retried{0}, relaid{0}, turned{0}, fuzzy{0}, merged{0};
};

// One failed cluster through clip_retries(); false when every attempt failed.
bool retry_cluster(const ClipContext& c, std::size_t k, const TopoDS_Shape (&layouts)[2], ClusterClips& clips,
                   CutDisks& disks, RetryCounts& counts, Progress& progress) {
  Bnd_Box box;
  BRepBndLib::Add(layouts[0], box);
  const double size = std::sqrt(box.SquareExtent());
  const gp_Pnt center((box.CornerMin().XYZ() + box.CornerMax().XYZ()) / 2.0);
  const int cluster = static_cast<int>(k);
  std::optional<TopoDS_Shape> merged[2];  // each layout with its bands merged, made when first tried
  for (const ClipAttempt& attempt : clip_retries()) {
    if (attempt.layout == 0 && attempt.frame == 0 && attempt.fuzzy == 0.0 && !attempt.merged) continue;  // first pass
    progress.check();
    if (attempt.merged && !merged[attempt.layout]) merged[attempt.layout] = with_bands_merged(layouts[attempt.layout]);
    const TopoDS_Shape& cluster_shape = attempt.merged ? *merged[attempt.layout] : layouts[attempt.layout];
    if (cluster_shape.IsNull()) continue;  // no band to merge: the same as an attempt before
    const TopLoc_Location frame = turned_frame(attempt.frame, center);
    BRepAlgoAPI_Common op;
    if (attempt.fuzzy > 0.0) op.SetFuzzyValue(attempt.fuzzy * size);
    // The cluster's disks of one layout take part in the checks and the assembly, the other's do not.
    disks.use_layout(cluster, attempt.layout);
    const TopoDS_Shape tool_copy = brep_from_text(clips.tool_text, "body").Moved(frame);
    const std::optional<TopoDS_Shape> clipped =
        try_boolean(op, cluster_shape.Moved(frame), tool_copy, clips.what, no_progress());
    if (!clipped) continue;
    clips.results[k] = clipped->Moved(frame.Inverted());
    if (!disks.cluster_result_ok(op, clips.results[k], cluster, attempt.layout, frame)) continue;
    if (clips.cannot_be_empty[k] && is_empty(clips.results[k])) continue;
    disks.track(op, clips.results[k], cluster, frame);
    find_cut_faces(c, op, tool_copy, k, clips);
    clips.unclipped[k] = cluster_shape;
    ++counts.retried;
    counts.relaid += attempt.layout == 1;
    counts.turned += attempt.frame != 0;
    counts.fuzzy += attempt.fuzzy > 0.0;
    counts.merged += attempt.merged;
    return true;
  }
  return false;
}

}  // namespace

void retry_failed_clusters(const ClipContext& c, SeamPreference seams, CutEdges& cuts, ClusterClips& clips,
                           CutDisks& disks, BrepPieces& second_layout, TrimStats& stats, Progress& progress) {
  if (std::none_of(clips.failed.begin(), clips.failed.end(), [](char x) { return x; })) return;
  progress.check();
  const std::vector<std::vector<TopoDS_Face>> other_faces =
      second_layout_faces(c, seams, cuts, clips, disks, second_layout);
  RetryCounts counts;
  const std::size_t count = c.clusters.faces.size();
  tbb::parallel_for(std::size_t(0), count, [&](std::size_t k) {
    if (!clips.failed[k]) return;
    progress.check();
    const TopoDS_Shape layouts[2] = {clips.unclipped[k], solids_from_faces(other_faces[k])};
    if (retry_cluster(c, k, layouts, clips, disks, counts, progress)) return;
    if (!c.options.dump_directory.empty()) {  // both layouts and the tool, for study
      const std::string stem = c.options.dump_directory + "/cluster" + std::to_string(k);
      std::ofstream(stem + "_layout0.brep") << brep_to_text(layouts[0]);
      std::ofstream(stem + "_layout1.brep") << brep_to_text(layouts[1]);
      std::ofstream(stem + "_tool.brep") << clips.tool_text;
    }
    throw std::runtime_error("trim: the Common of boundary cluster " + std::to_string(k) + " (of " +
                             std::to_string(count) +
                             ") misclassified a disk it did not touch, produced invalid faces, or kept nothing of "
                             "hubs inside the body, with both layouts of its spheres, in turned frames and with fuzzy "
                             "values");
  });
  stats.retried_clusters += counts.retried;  // += : the rim clusters may be retried later (clip_rim_clusters)
  stats.relaid_clusters += counts.relaid;
  stats.turned_clusters += counts.turned;
  stats.fuzzy_clusters += counts.fuzzy;
  stats.merged_clusters += counts.merged;
}

void clip_rim_clusters(const ClipContext& c, SeamPreference seams, CutEdges& cuts, ClusterClips& clips,
                       CutDisks& disks, BrepPieces& second_layout, TrimStats& stats, Progress& progress) {
  const std::vector<char> rim = clips.on_rim;
  disks.reset_fates(&rim);  // the Cut's fates
  // Only these clusters are retried now; the others' retries are done and their flags kept.
  const std::vector<char> failed_before = clips.failed;
  std::fill(clips.failed.begin(), clips.failed.end(), 0);
  std::fill(clips.on_rim.begin(), clips.on_rim.end(), 0);
  tbb::parallel_for(std::size_t(0), rim.size(), [&](std::size_t k) {
    if (!rim[k]) return;
    Progress cluster(progress, 0, 10);  // no share of the bar (it does not go back), but cancellable
    cluster.check();
    clips.results[k] = clips.unclipped[k];
    clip_one(c, k, clips, disks, cluster);
    cluster.finish();
  });
  retry_failed_clusters(c, seams, cuts, clips, disks, second_layout, stats, progress);
  for (std::size_t k = 0; k < rim.size(); ++k) clips.failed[k] |= failed_before[k];
}

}  // namespace steady::trim
