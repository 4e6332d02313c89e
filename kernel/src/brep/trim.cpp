#include "steady/brep/trim.hpp"

#include <BRepAlgoAPI_BooleanOperation.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include "steady/brep/brep_io.hpp"
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <unordered_map>
#include <unordered_set>

#include "steady/lattice/beam_frustum.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/query/clean_check.hpp"
#include "brep/clip_retries.hpp"
#include "steady/core/errors.hpp"
#include "steady/brep/skin.hpp"
#include "brep/skin_holes.hpp"
#include "steady/brep/solid_body.hpp"
#include "brep/occ_progress.hpp"

namespace steady {

TrimPolicy trim_policy_from_string(const std::string& name) {
  if (name == "clip") return TrimPolicy::Clip;
  if (name == "whole") return TrimPolicy::Whole;
  fail_input("policy", "must be 'clip' or 'whole' (got '" + name + "')");
}

DanglingBeams dangling_from_string(const std::string& name) {
  if (name == "keep") return DanglingBeams::Keep;
  if (name == "remove") return DanglingBeams::Remove;
  fail_input("dangling", "must be 'keep' or 'remove' (got '" + name + "')");
}

namespace {

// A hub's bounding ball may come this close (relative to the body's size) to the boundary and still count as
// clear of it: far below any feature, far above the exact distance's own accuracy.
constexpr double kClearanceRelative = 1e-9;
// Places tried for a beam's cut when halfway is not clear of the boundary, as fractions of the way between its
// stumps' starts: nearest the middle first, never nearer a start than a tenth of the way.
constexpr double kMovedCutPlaces[] = {0.35, 0.65, 0.2, 0.8, 0.1, 0.9};

enum class HubState : char { Absent, Inside, Outside, Crossing };

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// The pieces of a hub, each in a bounding ball: the node ball, and each half-beam from its exit circle to its cut.
// A hub is clear of a boundary when all its pieces are; and since the segment joining two nodes runs through their
// pieces (ball, half-beam, half-beam, ball), hubs clear of the boundary and joined by a beam lie on the same side.
struct Piece {
  Vec3 center{0.0};
  double radius = 0.0;
};

std::vector<std::vector<Piece>> hub_pieces(const FlatLattice& f, const std::vector<BeamFrustum>& frustums,
                                           Progress& progress) {
  std::vector<std::vector<Piece>> out(f.ball_count());
  progress.set_total(f.ball_count());
  tbb::parallel_for(std::int64_t(0), f.ball_count(), [&](std::int64_t i) {
    progress.advance();
    const Ball& ball = f.balls[i];
    out[i].push_back({ball.center, ball.radius});
    for (const std::int64_t* e = f.incident_begin(i); e != f.incident_end(i); ++e) {
      const BeamFrustum& fr = frustums[*e];
      if (!fr.exists) continue;
      const bool at_a = f.beams[*e].a == i;
      const double x_exit = at_a ? fr.exit_a : fr.exit_b;
      const double x_cut = at_a ? fr.cut_position() : fr.cone.length - fr.cut_position();
      const double r_exit = at_a ? fr.circle_a.radius : fr.circle_b.radius;
      const double r_cut = fr.cone.radius_at(fr.cut_position());
      const Vec3 dir = at_a ? fr.cone.axis : -fr.cone.axis;
      out[i].push_back({ball.center + 0.5 * (x_exit + x_cut) * dir,
                        std::hypot(0.5 * (x_cut - x_exit), std::max(r_exit, r_cut))});
    }
  });
  progress.finish();
  return out;
}

// Inside / outside / crossing of every (non-absorbed) hub against a body's boundary.
std::vector<HubState> classify_hubs(const FlatLattice& f, const std::vector<char>& absorbed,
                                    const std::vector<std::vector<Piece>>& pieces, const SolidBody& body,
                                    TrimStats& stats, Progress& progress) {
  const std::int64_t n = f.ball_count();
  // Units: the triangulation's bounds 20, the exact distances 70 (BRepExtrema, serial: most of the time when many
  // hubs lie near the boundary), the regions and their point classifications 10.
  progress.set_total(100);
  std::vector<HubState> state(n, HubState::Absent);
  const double clearance = kClearanceRelative * body.size();
  // The triangulation's lower bound clears most pieces; the rest need the exact distance (serial).
  std::vector<char> clear(n, 0);
  std::vector<std::vector<char>> undecided(n);
  {
    Progress bounds(progress, 20, n);
    tbb::parallel_for(std::int64_t(0), n, [&](std::int64_t i) {
    bounds.advance();
    if (absorbed[i]) return;
    bool all = true;
    undecided[i].assign(pieces[i].size(), 0);
    for (std::size_t k = 0; k < pieces[i].size(); ++k)
      if (!(body.distance_lower_bound(pieces[i][k].center) > pieces[i][k].radius + clearance)) {
        undecided[i][k] = 1;
        all = false;
      }
    clear[i] = all;
    });
    bounds.finish();
  }
  Progress exact(progress, 70);
  {
    std::int64_t count = 0;
    for (std::int64_t i = 0; i < n; ++i) count += !absorbed[i] && !clear[i];
    exact.set_total(count);
  }
  for (std::int64_t i = 0; i < n; ++i) {
    if (absorbed[i] || clear[i]) continue;
    exact.advance();
    bool all = true;
    for (std::size_t k = 0; k < pieces[i].size() && all; ++k) {
      if (!undecided[i][k]) continue;
      ++stats.exact_distance_tests;
      all = body.exact_distance(pieces[i][k].center) > pieces[i][k].radius + clearance;
    }
    clear[i] = all;
    if (!all) state[i] = HubState::Crossing;
  }
  exact.finish();
  std::vector<std::int64_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int64_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (const FlatBeam& b : f.beams)
    if (clear[b.a] && clear[b.b]) parent[find(b.a)] = find(b.b);
  std::vector<char> root_state(n, 0);  // 0 unknown, 1 inside, 2 outside
  for (std::int64_t i = 0; i < n; ++i) {
    if (!clear[i]) continue;
    const std::int64_t r = find(i);
    if (!root_state[r]) {
      progress.check();
      root_state[r] = body.contains(f.balls[i].center) ? 1 : 2;
    }
    state[i] = root_state[r] == 1 ? HubState::Inside : HubState::Outside;
  }
  progress.finish();
  return state;
}

TopoDS_Shape compound_of(const std::vector<TopoDS_Shape>& shapes) {
  TopoDS_Compound c;
  const BRep_Builder b;
  b.MakeCompound(c);
  for (const TopoDS_Shape& s : shapes) b.Add(c, s);
  return c;
}

// A copy of a shape read back from its BREP text (see the clusters' Booleans for why).
TopoDS_Shape text_copy(const TopoDS_Shape& shape) { return brep_from_text(brep_to_text(shape), "body"); }

// One Boolean, non-destructive (the arguments' untouched sub-shapes, such as the disks at interface cuts, come
// out as the very same shapes), parallel.
// Cancelled when the progress is (OpenCASCADE stops at its next check).

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

// Edges of two sets of faces that one face uses once: where the faces do not close up (a seam is used twice by
// its one face; the degenerate edges at a sphere's poles do not count).
// `open_faces`: where given, the faces with such an edge.
std::int64_t free_edges(const std::vector<TopoDS_Face>& a, const std::vector<TopoDS_Face>& b,
                        std::vector<TopoDS_Shape>* open_faces = nullptr) {
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

// run_boolean for a boundary cluster: OpenCASCADE's failure there is one more reason to try again (nothing
// returned), not the end of the trim. A cancel still ends it.
std::optional<TopoDS_Shape> try_boolean(BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& a,
                                        const TopoDS_Shape& b, const char* what, Progress& progress) {
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

// Work units of trim_lattice (its progress' total). Before the hubs are classified, fixed shares: the body (its
// triangulation) and its skin (the offset, its triangulation), the hubs' bounding pieces, each classification.
// What follows depends on the classification: the rest is shared in proportion to the estimates below.
constexpr std::int64_t kTrimUnits = 100000;
constexpr std::int64_t kBodyUnits = 1000, kSkinUnits = 4000, kPiecesUnits = 1000, kClassifyUnits = 4000;
// Estimates of the rest, relative to building one element (ball or beam) = 2, measured on a cubic strut lattice
// in a cylinder (curved bodies: surface-surface intersections; a box's planes make the Booleans several times
// cheaper, and everything fast): per beam whose cut needs an exact distance (cluster split); per crossing hub,
// its cluster's Common with the body, the glued Fuse with the skin or else the Cut through the pores, the check
// of the faces the Booleans produced; per element, the assembly into solids.
constexpr std::int64_t kBuildPerElement = 2, kSplitPerBeam = 2, kBooleanPerHub = 2000, kGluedFusePerHub = 800,
                       kPoresCutPerHub = 3000, kVerifyPerHub = 300, kAssemblePerElement = 3;

}  // namespace

// One attempt at trimming, with the boundary hubs' spheres laid out by `seams`.
TrimResult trim_attempt(const FlatLattice& f, const TopoDS_Shape& body_shape, const TrimOptions& options,
                        SeamPreference seams, Progress& progress) {
  if (!std::isfinite(options.skin) || options.skin < 0.0) {
    std::ostringstream os;
    os << "must be a thickness >= 0 (got " << options.skin << ")";
    fail_input("skin", os.str());
  }
  progress.set_total(kTrimUnits);
  std::int64_t fixed_units = 0;  // the fixed shares handed out so far
  auto fixed_part = [&](std::int64_t units) {
    fixed_units += units;
    return units;
  };
  TrimResult out;
  TrimStats& stats = out.stats;
  auto clock = std::chrono::steady_clock::now();
  progress.check();
  const SolidBody body(body_shape, "body");
  progress.advance(fixed_part(kBodyUnits));
  std::optional<Skin> skin;
  std::optional<SolidBody> inner;
  if (options.skin > 0.0) {
    Progress part(progress, fixed_part(kSkinUnits));
    skin = make_skin(body, options.skin, part);
    inner.emplace(skin->inner, "skin");
    out.skin = skin->skin;
  }
  std::vector<BeamFrustum> frustums = beam_frustums(f);  // cuts moved below, on beams between boundary hubs
  const std::vector<char> absorbed = absorbed_balls(f, frustums);
  std::vector<std::vector<Piece>> pieces;
  {
    Progress part(progress, fixed_part(kPiecesUnits));
    pieces = hub_pieces(f, frustums, part);
  }
  std::vector<HubState> outer_state;
  {
    Progress part(progress, fixed_part(kClassifyUnits));
    outer_state = classify_hubs(f, absorbed, pieces, body, stats, part);
  }
  std::vector<HubState> inner_state = outer_state;
  if (inner) {
    Progress part(progress, fixed_part(kClassifyUnits));
    inner_state = classify_hubs(f, absorbed, pieces, *inner, stats, part);
  }
  stats.classify_seconds = seconds_since(clock);

  // Roles: interior hubs are built whole with no Boolean; band hubs go through the Booleans.
  const std::int64_t n = f.ball_count();
  std::vector<char> interior(n, 0), band(n, 0);
  bool any_in_body = false;
  for (std::int64_t i = 0; i < n; ++i) {
    const HubState o = outer_state[i], s = inner_state[i];
    if (o == HubState::Absent) continue;
    any_in_body = any_in_body || o != HubState::Outside;
    stats.inside_hubs += s == HubState::Inside;
    stats.outside_hubs += s == HubState::Outside;
    stats.crossing_hubs += s == HubState::Crossing;
    if (options.policy == TrimPolicy::Clip) {
      interior[i] = s == HubState::Inside;
      band[i] = s == HubState::Crossing;
    } else {
      // Whole: only hubs entirely inside the body; with a skin, those crossing its inner boundary fuse with it.
      interior[i] = o == HubState::Inside && s == HubState::Inside;
      band[i] = skin && o == HubState::Inside && s == HubState::Crossing;
    }
  }
  if (!any_in_body)
    fail_input("body", "the lattice does not meet the body (all " + std::to_string(n) + " hubs lie outside it)");
  const bool nothing_kept = std::none_of(interior.begin(), interior.end(), [](char c) { return c; }) &&
                            std::none_of(band.begin(), band.end(), [](char c) { return c; });
  if (nothing_kept) {
    if (options.policy == TrimPolicy::Whole)
      fail_input("policy", "'whole' keeps only hubs entirely inside the body, and none is: the trimmed lattice is empty");
    fail_input("skin", "leaves no room for the lattice: no hub reaches inside the inner offset");
  }

  // Beams: kept unless both hubs are dropped, or one is and dangling beams are removed.
  std::vector<char> beam_kept(f.beam_count(), 0), band_beams(f.beam_count(), 0), interior_beams(f.beam_count(), 0);
  std::vector<char> open_cuts(f.beam_count(), 0);
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!frustums[e].exists) continue;
    const std::int64_t a = f.beams[e].a, b = f.beams[e].b;
    const bool ka = interior[a] || band[a], kb = interior[b] || band[b];
    if (!ka && !kb) continue;
    if ((!ka || !kb) && options.dangling == DanglingBeams::Remove) {
      ++stats.removed_beams;
      continue;
    }
    beam_kept[e] = 1;
    band_beams[e] = band[a] || band[b];
    interior_beams[e] = interior[a] || interior[b];
    if ((band[a] && interior[b]) || (band[b] && interior[a])) {
      open_cuts[e] = 1;
    }
  }

  // Band hubs are clipped in independent clusters, in parallel: a beam between two band hubs is split at its cut
  // (each side closed by its own disk) when that disk is clear of every boundary the Booleans use, so each side
  // comes out of its Boolean untouched or wholly deleted and the two sides can be glued again.
  // Clip: the clusters meet the body, or with a skin its inner offset. Whole with a skin: the band is fused with the
  // skin in one Boolean (see below) and is not split.
  const bool unite = skin && options.unite_skin;
  const bool has_band = std::any_of(band.begin(), band.end(), [](char c) { return c; });

  // The rest of the progress, in proportion to the work left (estimates in elements built).
  std::int64_t band_hubs = 0, interior_elements = 0, band_elements = 0, band_band_beams = 0;
  for (std::int64_t i = 0; i < n; ++i) {
    band_hubs += band[i];
    interior_elements += interior[i];
  }
  band_elements = band_hubs;
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!beam_kept[e]) continue;
    interior_elements += interior_beams[e];
    band_elements += band_beams[e];
    band_band_beams += band[f.beams[e].a] && band[f.beams[e].b];
  }
  const std::int64_t split_weight = kSplitPerBeam * band_band_beams;
  const std::int64_t build_weight = kBuildPerElement * (band_elements + interior_elements);
  const std::int64_t boolean_weight =
      has_band ? (options.policy == TrimPolicy::Clip ? kBooleanPerHub : kBuildPerElement) * band_hubs : 0;
  const std::int64_t union_weight =
      has_band && unite ? (options.policy == TrimPolicy::Clip ? kGluedFusePerHub : kPoresCutPerHub) * band_hubs : 0;
  const std::int64_t verify_weight = has_band && options.verify_booleans ? kVerifyPerHub * band_hubs : 0;
  const std::int64_t assemble_weight = kAssemblePerElement * (band_elements + interior_elements) + 1;
  const std::int64_t weights =
      split_weight + build_weight + boolean_weight + union_weight + verify_weight + assemble_weight;
  const std::int64_t rest_units = kTrimUnits - fixed_units;
  auto rest_part = [&](std::int64_t weight) {
    return static_cast<std::int64_t>(static_cast<double>(rest_units) * static_cast<double>(weight) /
                                     static_cast<double>(weights));
  };
  Progress split_progress(progress, rest_part(split_weight), std::max<std::int64_t>(1, band_band_beams));

  std::vector<const SolidBody*> boundaries;
  if (options.policy == TrimPolicy::Clip) boundaries.push_back(inner ? &*inner : &body);
  const bool clusters_wanted = !boundaries.empty();
  const double clearance = kClearanceRelative * body.size();
  std::vector<char> split(f.beam_count(), 0);
  std::vector<std::int64_t> cluster_parent(n);
  std::iota(cluster_parent.begin(), cluster_parent.end(), 0);
  auto find = [&](std::int64_t x) {
    while (cluster_parent[x] != x) x = cluster_parent[x] = cluster_parent[cluster_parent[x]];
    return x;
  };
  // A cut is clear when its disk keeps off every boundary the Booleans use.
  auto clear_of_boundaries = [&](const Circle& cut) {
    for (const SolidBody* b : boundaries) {
      if (b->distance_lower_bound(cut.center) > cut.radius + clearance) continue;
      ++stats.exact_distance_tests;
      if (!(b->exact_distance(cut.center) > cut.radius + clearance)) return false;
    }
    return true;
  };
  // Where a boundary hub's stumps start (exit circles, or a crowded hub's collars), for the beams its build has.
  // (The cuts' places are kept in `frustums`; `moved` marks the beams whose cut left the middle.)
  std::vector<char> moved(f.beam_count(), 0);
  std::unordered_map<std::int64_t, std::vector<double>> starts;
  auto stump_start = [&](std::int64_t ball, std::int64_t e) {
    auto found = starts.find(ball);
    if (found == starts.end()) found = starts.emplace(ball, stump_starts(f, frustums, band_beams, ball)).first;
    return found->second[f.incident_slot(ball, e)];
  };
  // A clear place for the cut of beam e between its stumps' starts (kept a tenth of the way off them), or NaN.
  auto clear_cut_fraction = [&](std::int64_t e) {
    BeamFrustum fr = frustums[e];
    const double from = stump_start(f.beams[e].a, e), to = fr.cone.length - stump_start(f.beams[e].b, e);
    if (!(from < to)) return std::nan("");
    for (const double u : kMovedCutPlaces) {
      fr.cut_fraction = (from + u * (to - from) - fr.exit_a) / fr.length();
      if (fr.cut_fraction > 0.0 && fr.cut_fraction < 1.0 && clear_of_boundaries(fr.cut_circle()))
        return fr.cut_fraction;
    }
    return std::nan("");
  };
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!beam_kept[e] || !band[f.beams[e].a] || !band[f.beams[e].b]) continue;
    split_progress.advance();
    if (!clusters_wanted) {
      cluster_parent[find(f.beams[e].a)] = find(f.beams[e].b);
      continue;
    }
    if (clear_of_boundaries(frustums[e].cut_circle())) {
      split[e] = 1;
      continue;
    }
    // Halfway is not clear: another place along the beam may be (a beam crossing the boundary is clear of it
    // some way off the crossing). Without this, the boundary hubs of a lattice whose beams run near the body's
    // surface join into one cluster (213 of 298 on the main job's octet lattice clipped by its cylinder): one
    // Boolean, slow, and failing as a whole where any one of its hubs grazes the surface.
    const double t = options.move_cuts ? clear_cut_fraction(e) : std::nan("");
    if (!std::isnan(t)) {
      frustums[e].cut_fraction = t;
      split[e] = moved[e] = 1;
    } else {
      cluster_parent[find(f.beams[e].a)] = find(f.beams[e].b);
    }
  }
  // A clear cut inside one cluster stays whole: its two disks would be coincident faces of one Boolean argument.
  for (std::int64_t e = 0; e < f.beam_count(); ++e)
    if (split[e] && find(f.beams[e].a) == find(f.beams[e].b)) {
      split[e] = moved[e] = 0;
      frustums[e].cut_fraction = 0.5;
    }
  stats.moved_cuts = std::count(moved.begin(), moved.end(), 1);
  std::vector<double> cut_fractions(f.beam_count());  // for the builds of the boundary hubs
  for (std::int64_t e = 0; e < f.beam_count(); ++e) cut_fractions[e] = frustums[e].cut_fraction;
  split_progress.finish();

  clock = std::chrono::steady_clock::now();
  CutEdges cuts;
  BrepPieces band_pieces, second_layout;  // the boundary hubs, and the clusters built again with the other layout
  if (has_band) {
    BrepSelection sel;
    sel.balls = band;
    sel.beams = band_beams;
    sel.split = split;
    sel.cut_fractions = cut_fractions;
    sel.seams = seams;
    Progress part(progress, rest_part(kBuildPerElement * band_elements));
    band_pieces = build_brep_pieces(f, sel, cuts, part);
  }
  BrepSelection sel;
  sel.balls = interior;
  sel.beams = interior_beams;
  sel.open_cuts = open_cuts;
  BrepPieces interior_pieces;
  {
    Progress part(progress, rest_part(kBuildPerElement * interior_elements));
    interior_pieces = build_brep_pieces(f, sel, cuts, part);
  }
  stats.build_seconds = seconds_since(clock);
  for (const BrepPieces* p : {&band_pieces, &interior_pieces}) {
    stats.core_hubs += p->stats.core_hubs;
    stats.distinct_cores += p->stats.distinct_cores;
  }
  if (std::getenv("STEADY_TRIM_VERBOSE"))
    std::fprintf(stderr, "trim: built the boundary and interior hubs in %.1f s (%lld and %lld distinct cores)\n",
                 stats.build_seconds, static_cast<long long>(band_pieces.stats.distinct_cores),
                 static_cast<long long>(interior_pieces.stats.distinct_cores));

  clock = std::chrono::steady_clock::now();
  std::vector<TopoDS_Face> faces = interior_pieces.faces;
  if (has_band) {
    // Clusters and their faces.
    std::unordered_map<std::int64_t, int> cluster_index;
    std::vector<std::vector<TopoDS_Face>> cluster_faces;
    std::vector<int> face_cluster(band_pieces.faces.size());
    for (std::size_t k = 0; k < band_pieces.faces.size(); ++k) {
      const std::int64_t root = find(band_pieces.face_owner[k]);
      auto [it, inserted] = cluster_index.emplace(root, static_cast<int>(cluster_faces.size()));
      if (inserted) cluster_faces.emplace_back();
      cluster_faces[it->second].push_back(band_pieces.faces[k]);
      face_cluster[k] = it->second;
    }
    stats.band_clusters = static_cast<std::int64_t>(cluster_faces.size());
    // Disks to remove after the Booleans: toward interior hubs, and between split band hubs.
    enum class Fate : char { Present, Deleted, Modified };
    struct Removed {
      const CutCap* cap;
      int cluster;
      int layout = 0;       // 0: the first layout of the spheres; 1: the other one (for clusters that failed)
      bool active = true;   // the disk of the layout its cluster uses
      Fate fate = Fate::Present;
      int changed_by = -2;  // the cluster whose Boolean changed its fate, or -1 for the final one
    };
    std::vector<Removed> removed;
    std::unordered_map<const void*, std::size_t> removed_index;
    {
      std::unordered_map<const void*, int> cluster_of_face;
      for (std::size_t k = 0; k < band_pieces.faces.size(); ++k)
        cluster_of_face.emplace(band_pieces.faces[k].TShape().get(), face_cluster[k]);
      for (const CutCap& c : band_pieces.caps) {
        if (!open_cuts[c.beam] && !split[c.beam]) continue;  // a stump toward a dropped hub keeps its disk
        removed_index.emplace(c.face.TShape().get(), removed.size());
        removed.push_back({&c, cluster_of_face.at(c.face.TShape().get())});
      }
    }
    // A disk's fate in a Boolean's result: present when the very same face is in it (non-destructive mode),
    // modified when the history says so, deleted otherwise. Presence is looked up in the result itself: the
    // history has reported untouched faces as deleted (OCC 7.6, seen on clusters of a tilted cylinder). `frame`:
    // where the Boolean saw its arguments (see turned_frame).
    auto fate_in = [&](BRepAlgoAPI_BooleanOperation& op, const std::unordered_set<const void*>& present,
                       const TopoDS_Face& disk, const TopLoc_Location& frame) {
      if (present.count(disk.TShape().get())) return Fate::Present;
      return op.Modified(disk.Moved(frame)).IsEmpty() ? Fate::Deleted : Fate::Modified;
    };
    auto faces_of = [](const TopoDS_Shape& shape) {
      std::unordered_set<const void*> faces;
      for (TopExp_Explorer x(shape, TopAbs_FACE); x.More(); x.Next()) faces.insert(x.Current().TShape().get());
      return faces;
    };
    // (A cluster's own disks first: the clusters are clipped in parallel, each writing its own disks.)
    // `among`: for the final Boolean (cluster -1), the clusters that took part in it, when not all did.
    auto track = [&](BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& result, int cluster,
                     const TopLoc_Location& frame = TopLoc_Location(), const std::vector<char>* among = nullptr) {
      const std::unordered_set<const void*> present = faces_of(result);
      for (Removed& r : removed) {
        if ((cluster >= 0 && r.cluster != cluster) || !r.active || r.fate != Fate::Present) continue;
        if (among && !(*among)[r.cluster]) continue;
        r.fate = fate_in(op, present, r.cap->face, frame);
        if (r.fate != Fate::Present) r.changed_by = cluster;
      }
    };
    const TopoDS_Shape* tool = nullptr;
    const char* what = "";
    if (options.policy == TrimPolicy::Clip) {
      tool = skin ? &skin->inner : &body.solid();
      what = skin ? "Common with the inner body" : "Common with the body";
    }
    // The union with the skin (one Boolean, and a second one should the first go wrong) and the check of what the
    // Booleans produced.
    Progress union_progress(progress, rest_part(union_weight + verify_weight), union_weight + verify_weight + 1);
    // Each disk removed for gluing lies clear of the boundary, so its fate is known before any Boolean: a disk
    // toward an interior hub stays; a disk between two boundary hubs stays when its center is inside the body
    // the clusters are clipped to, and goes otherwise. (Classified here, serially: BRepClass3d is not shared.)
    std::vector<char> expected_present(removed.size(), 1);
    if (tool)
      for (std::size_t k = 0; k < removed.size(); ++k)
        if (!open_cuts[removed[k].cap->beam])
          expected_present[k] = boundaries.front()->contains(frustums[removed[k].cap->beam].cut_circle().center);
    // A cluster's Common is right when its disks met their expected fate (untouched or wholly deleted) and the
    // faces it produced are valid; the other checks (the final union) follow below.
    auto cluster_result_ok = [&](BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& result, int c, int layout,
                                 const TopLoc_Location& frame = TopLoc_Location()) {
      const std::unordered_set<const void*> present = faces_of(result);
      for (std::size_t k = 0; k < removed.size(); ++k) {
        if (removed[k].cluster != c || removed[k].layout != layout) continue;
        const Fate fate = fate_in(op, present, removed[k].cap->face, frame);
        if (fate != (expected_present[k] ? Fate::Present : Fate::Deleted)) return false;
      }
      // The result must close up by itself: a Common that drops a face (a beam's cone beside an untouched ball)
      // passes the other checks and leaves the part open (measured at 101,343 beams with a skin).
      std::vector<TopoDS_Face> all;
      std::vector<TopoDS_Shape> produced;
      for (TopExp_Explorer x(result, TopAbs_FACE); x.More(); x.Next()) {
        all.push_back(TopoDS::Face(x.Current()));
        if (!removed_index.count(x.Current().TShape().get())) produced.push_back(x.Current());
      }
      return free_edges(all, {}) == 0 && is_valid(compound_of(produced));
    };
    std::vector<TopoDS_Shape> results(cluster_faces.size()), unclipped(cluster_faces.size());
    std::vector<char> failed(cluster_faces.size(), 0);
    // With a skin: each clipped cluster's cut faces (on the inner boundary), and whether they can be holes in it
    // (skin_holes.hpp).
    std::vector<std::vector<CutFace>> cluster_cuts(cluster_faces.size());
    std::vector<char> as_holes(cluster_faces.size(), 0);
    auto find_cuts = [&](BRepAlgoAPI_BooleanOperation& op, const TopoDS_Shape& tool_passed, std::size_t c) {
      if (!unite) return;
      TopTools_IndexedMapOfShape tool_faces;
      TopExp::MapShapes(tool_passed, TopAbs_FACE, tool_faces);
      cluster_cuts[c] = cut_faces(op, tool_faces, results[c]);
      as_holes[c] = cut_faces_are_holes(results[c], cluster_cuts[c]);
    };
    const std::string tool_text = tool ? brep_to_text(*tool) : std::string();
    // Each cluster's share of the Booleans' progress is its number of faces; a cancel stops the clusters not yet
    // started, and the running Booleans at their next check.
    Progress booleans(progress, rest_part(boolean_weight), static_cast<std::int64_t>(band_pieces.faces.size()));
    tbb::parallel_for(std::size_t(0), cluster_faces.size(), [&](std::size_t c) {
      Progress cluster(booleans, static_cast<std::int64_t>(cluster_faces[c].size()), 10);
      cluster.check();
      const TopoDS_Shape solid = solids_from_faces(cluster_faces[c]);
      unclipped[c] = solid;
      if (!tool) {
        results[c] = solid;
        cluster.finish();
        return;
      }
      cluster.advance(1);
      // Each cluster is clipped against its own copy of the body (the Booleans share no mutable data), read back
      // from BREP text: against the in-memory shape (a primitive, or the skin's offset, meshed for the distance
      // bounds) OpenCASCADE's Common misclassified untouched disks on clusters that the text copy clips right, and
      // took twice as long (measured: 2,980 beams in a cylinder tilted by 0.3 rad).
      const TopoDS_Shape copy = brep_from_text(tool_text, "body");
      BRepAlgoAPI_Common op;
      Progress boolean(cluster, 9);
      const std::optional<TopoDS_Shape> clipped = try_boolean(op, solid, copy, what, boolean);
      if (!clipped || (options.verify_booleans && !cluster_result_ok(op, *clipped, static_cast<int>(c), 0))) {
        failed[c] = 1;  // tried again below (clip_retries)
      } else {
        results[c] = *clipped;
        track(op, results[c], static_cast<int>(c));
        find_cuts(op, copy, c);
      }
      cluster.finish();
    });
    booleans.finish();
    // The failed clusters are clipped again through clip_retries(): with the spheres laid out the other way,
    // in turned frames, with fuzzy values. Both layouts share the cut circles, and a turned frame is undone on
    // the result, so whichever attempt succeeds glues to the neighbours as the first one would have.
    if (std::any_of(failed.begin(), failed.end(), [](char x) { return x; })) {
      progress.check();
      std::unordered_map<std::int64_t, std::size_t> vertices_before;
      for (const auto& [beam, circle] : cuts) vertices_before[beam] = circle.vertices.size();
      // Only the failed clusters' hubs (and their beams) are laid out again: a crowded hub's core in the other
      // layout can take minutes (measured on the main job's octet lattice), and the other clusters need none.
      BrepSelection other;
      other.balls.assign(n, 0);
      other.beams.assign(f.beam_count(), 0);
      for (std::int64_t i = 0; i < n; ++i) other.balls[i] = band[i] && failed[cluster_index.at(find(i))];
      for (std::int64_t e = 0; e < f.beam_count(); ++e)
        other.beams[e] = band_beams[e] && (other.balls[f.beams[e].a] || other.balls[f.beams[e].b]);
      other.split = split;
      other.cut_fractions = cut_fractions;
      other.seams = seams == SeamPreference::FewestCrossings ? SeamPreference::MostCrossings
                                                             : SeamPreference::FewestCrossings;
      second_layout = build_brep_pieces(f, other, cuts);
      for (const auto& [beam, count] : vertices_before)
        if (cuts.at(beam).vertices.size() != count)
          throw std::runtime_error("trim: the second layout of the boundary hubs changed a shared cut circle");
      std::vector<std::vector<TopoDS_Face>> other_faces(cluster_faces.size());
      std::unordered_map<const void*, int> cluster_of_face;
      for (std::size_t k = 0; k < second_layout.faces.size(); ++k) {
        const int c = cluster_index.at(find(second_layout.face_owner[k]));
        other_faces[c].push_back(second_layout.faces[k]);
        cluster_of_face.emplace(second_layout.faces[k].TShape().get(), c);
      }
      std::unordered_map<std::int64_t, char> present_by_beam;
      for (std::size_t k = 0; k < removed.size(); ++k) present_by_beam[removed[k].cap->beam] = expected_present[k];
      for (const CutCap& cap : second_layout.caps) {
        if (!open_cuts[cap.beam] && !split[cap.beam]) continue;
        const int c = cluster_of_face.at(cap.face.TShape().get());
        removed_index.emplace(cap.face.TShape().get(), removed.size());
        removed.push_back({&cap, c, 1, static_cast<bool>(failed[c])});
        expected_present.push_back(present_by_beam.at(cap.beam));
      }
      std::atomic<std::int64_t> retried{0}, relaid{0}, turned{0}, fuzzy_clusters{0};
      tbb::parallel_for(std::size_t(0), cluster_faces.size(), [&](std::size_t c) {
        if (!failed[c]) return;
        progress.check();
        const TopoDS_Shape layouts[2] = {unclipped[c], solids_from_faces(other_faces[c])};
        Bnd_Box box;
        BRepBndLib::Add(layouts[0], box);
        const double size = std::sqrt(box.SquareExtent());
        const gp_Pnt center((box.CornerMin().XYZ() + box.CornerMax().XYZ()) / 2.0);
        // The cluster's disks of one layout take part in the checks and the assembly, the other's do not.
        auto use_layout = [&](int layout) {
          for (Removed& r : removed)
            if (r.cluster == static_cast<int>(c)) r.active = r.layout == layout;
        };
        bool done = false;
        for (const ClipAttempt& attempt : clip_retries()) {
          if (attempt.layout == 0 && attempt.frame == 0 && attempt.fuzzy == 0.0) continue;  // the first pass
          progress.check();
          const TopLoc_Location frame = turned_frame(attempt.frame, center);
          BRepAlgoAPI_Common op;
          if (attempt.fuzzy > 0.0) op.SetFuzzyValue(attempt.fuzzy * size);
          use_layout(attempt.layout);
          const TopoDS_Shape tool_copy = brep_from_text(tool_text, "body").Moved(frame);
          const std::optional<TopoDS_Shape> clipped =
              try_boolean(op, layouts[attempt.layout].Moved(frame), tool_copy, what, no_progress());
          if (!clipped) continue;
          results[c] = clipped->Moved(frame.Inverted());
          if (!cluster_result_ok(op, results[c], static_cast<int>(c), attempt.layout, frame)) continue;
          track(op, results[c], static_cast<int>(c), frame);
          find_cuts(op, tool_copy, c);
          unclipped[c] = layouts[attempt.layout];
          ++retried;
          relaid += attempt.layout == 1;
          turned += attempt.frame != 0;
          fuzzy_clusters += attempt.fuzzy > 0.0;
          done = true;
          break;
        }
        if (!done) {
          // For the developers: STEADY_TRIM_DUMP=<folder> writes the cluster (both layouts) and the tool as BREP.
          if (const char* dir = std::getenv("STEADY_TRIM_DUMP")) {
            const std::string stem = std::string(dir) + "/cluster" + std::to_string(c);
            std::ofstream(stem + "_layout0.brep") << brep_to_text(layouts[0]);
            std::ofstream(stem + "_layout1.brep") << brep_to_text(layouts[1]);
            std::ofstream(stem + "_tool.brep") << tool_text;
          }
          throw std::runtime_error("trim: the Common of boundary cluster " + std::to_string(c) + " (of " +
                                   std::to_string(cluster_faces.size()) +
                                   ") misclassified a disk it did not touch, or produced invalid faces, with "
                                   "both layouts of its spheres, in turned frames and with fuzzy values");
        }
      });
      stats.retried_clusters = retried;
      stats.relaid_clusters = relaid;
      stats.turned_clusters = turned;
      stats.fuzzy_clusters = fuzzy_clusters;
    }
    // Checks one attempt: every interface disk untouched, the two disks of a split beam with one fate, the
    // Boolean's faces valid (OpenCASCADE reports success on some results it got wrong: check what it produced,
    // only that, and not again when `faces_checked` says the clusters' checks already did; the rest was built
    // exactly and the solids are assembled again below, `checked` holds faces checked before), a union with the
    // skin closed up. Returns the faces to keep, or an error message.
    auto collect = [&](const TopoDS_Shape& merged, bool pores, std::vector<TopoDS_Face>& kept,
                       bool faces_checked = false,
                       const std::unordered_set<const void*>& checked = {}) -> std::string {
      std::unordered_map<std::int64_t, int> split_present;
      for (const Removed& r : removed) {
        if (!r.active) continue;
        if (r.fate == Fate::Modified || (open_cuts[r.cap->beam] && r.fate != Fate::Present))
          return "the disk closing beam " + std::to_string(r.cap->beam) + " at its cut (toward " +
                 (split[r.cap->beam] ? "another boundary hub" : "an interior hub") + ") was " +
                 (r.fate == Fate::Deleted ? "deleted" : "modified") + " by " +
                 (r.changed_by >= 0 ? "the Boolean of boundary cluster " + std::to_string(r.changed_by) + " (of " +
                                          std::to_string(cluster_faces.size()) + ")"
                                    : std::string("the final Boolean")) +
                 ", though it lies clear of the boundary: OpenCASCADE misclassified it";
        if (split[r.cap->beam]) split_present[r.cap->beam] += r.fate == Fate::Present ? 1 : 0;
      }
      for (const auto& [beam, present] : split_present)
        if (present == 1) return "only one side of the cut of beam " + std::to_string(beam) + " survived";
      for (TopExp_Explorer x(merged, TopAbs_FACE); x.More(); x.Next())
        if (!removed_index.count(x.Current().TShape().get()))
          kept.push_back(TopoDS::Face(pores ? x.Current().Reversed() : x.Current()));
      if (options.verify_booleans && !faces_checked) {
        union_progress.check();
        std::vector<TopoDS_Shape> unchecked;
        for (const TopoDS_Face& face : kept)
          if (!checked.count(face.TShape().get())) unchecked.push_back(face);
        const TopoDS_Shape produced = compound_of(unchecked);
        if (!is_valid(produced)) return "its Boolean produced invalid faces (" + validity_report(produced, 2) + ")";
        union_progress.advance(verify_weight);
      }
      // A union with the skin must close up with the interior's faces: the checks above look at the faces one by
      // one, and a glued Fuse at 10^5 beams passed them and still left a part that was not closed (measured).
      if (unite)
        if (const std::int64_t open = free_edges(kept, faces)) {
          // For the developers: STEADY_TRIM_DUMP=<folder> writes the faces with an open edge as BREP.
          if (const char* dir = std::getenv("STEADY_TRIM_DUMP")) {
            std::vector<TopoDS_Shape> open_faces;
            free_edges(kept, faces, &open_faces);
            std::ofstream(std::string(dir) + "/open_faces.brep") << brep_to_text(compound_of(open_faces));
          }
          return "its faces leave " + std::to_string(open) + " edges open";
        }
      return "";
    };
    // The union with the skin through the pores: body \ (inner \ band). The band only meets the inner boundary
    // (what it has outside the body falls away by itself), and no two faces of the Boolean coincide; the part is
    // the body with the pores as voids.
    auto through_pores = [&](std::vector<TopoDS_Face>& kept) {
      for (Removed& r : removed) r.fate = Fate::Present, r.changed_by = -2;
      BRepAlgoAPI_Cut op;
      Progress part(union_progress, union_weight);
      const TopoDS_Shape pores = run_boolean(op, text_copy(skin->inner), compound_of(unclipped),
                                             "Cut of the inner body by the boundary hubs", part);
      track(op, pores, -1);
      for (TopExp_Explorer x(body.solid(), TopAbs_FACE); x.More(); x.Next()) kept.push_back(TopoDS::Face(x.Current()));
      return collect(pores, true, kept);
    };
    const auto union_clock = std::chrono::steady_clock::now();
    // The union with the skin by holes in its inner faces for the clusters whose cut faces can be holes, and a
    // glued Fuse for the others (clusters straddling the inner boundary's edges or seams).
    auto through_holes = [&](std::vector<TopoDS_Face>& kept) -> std::string {
      TopTools_IndexedMapOfShape inner_faces, skin_faces;
      TopExp::MapShapes(skin->inner, TopAbs_FACE, inner_faces);
      TopExp::MapShapes(skin->skin, TopAbs_FACE, skin_faces);
      std::vector<TopoDS_Face> faces_out;  // the union's faces but the inner boundary's
      // Faces checked already: the clusters' glued by holes (after their Common), the pierced ones (by pierce).
      std::unordered_set<const void*> checked;
      std::vector<std::vector<TopoDS_Face>> pieces(inner_faces.Extent() + 1), holes(inner_faces.Extent() + 1);
      std::vector<char> fused(cluster_faces.size(), 0);
      std::vector<TopoDS_Shape> fused_results;
      for (std::size_t c = 0; c < cluster_faces.size(); ++c) {
        if (!as_holes[c]) {
          fused[c] = 1;
          fused_results.push_back(results[c]);
          continue;
        }
        ++stats.holed_clusters;
        std::unordered_set<const void*> cut;
        for (const CutFace& k : cluster_cuts[c]) {
          cut.insert(k.face.TShape().get());
          holes[k.inner_face].push_back(k.face);
        }
        for (TopExp_Explorer x(results[c], TopAbs_FACE); x.More(); x.Next())
          if (!cut.count(x.Current().TShape().get())) {
            faces_out.push_back(TopoDS::Face(x.Current()));
            checked.insert(x.Current().TShape().get());
          }
      }
      // The skin's face standing for inner face i: the same face (reversed), or its pieces after the Fuse.
      std::unordered_map<const void*, int> inner_of;  // by TShape
      if (fused_results.empty()) {
        for (int i = 1; i <= inner_faces.Extent(); ++i) inner_of.emplace(inner_faces(i).TShape().get(), i);
        for (TopExp_Explorer x(skin->skin, TopAbs_FACE); x.More(); x.Next()) {
          const auto it = inner_of.find(x.Current().TShape().get());
          (it == inner_of.end() ? faces_out : pieces[it->second]).push_back(TopoDS::Face(x.Current()));
        }
      } else {
        BRepAlgoAPI_Fuse op;
        op.SetGlue(BOPAlgo_GlueShift);
        Progress part(union_progress, union_weight);
        const TopoDS_Shape copy = text_copy(skin->skin);
        const TopoDS_Shape merged =
            run_boolean(op, copy, compound_of(fused_results), "glued Fuse with the skin", part);
        track(op, merged, -1, TopLoc_Location(), &fused);
        TopTools_IndexedMapOfShape copy_faces;
        TopExp::MapShapes(copy, TopAbs_FACE, copy_faces);
        if (copy_faces.Extent() != skin_faces.Extent()) return "the skin read back from BREP text differs";
        for (int i = 1; i <= inner_faces.Extent(); ++i) {
          const TopoDS_Shape& face = copy_faces(skin_faces.FindIndex(inner_faces(i)));
          inner_of.emplace(face.TShape().get(), i);
          for (TopTools_ListOfShape::Iterator it(op.Modified(face)); it.More(); it.Next())
            inner_of.emplace(it.Value().TShape().get(), i);
        }
        for (TopExp_Explorer x(merged, TopAbs_FACE); x.More(); x.Next()) {
          const auto it = inner_of.find(x.Current().TShape().get());
          (it == inner_of.end() ? faces_out : pieces[it->second]).push_back(TopoDS::Face(x.Current()));
        }
      }
      for (int i = 1; i <= inner_faces.Extent(); ++i) {
        if (holes[i].empty()) {
          faces_out.insert(faces_out.end(), pieces[i].begin(), pieces[i].end());
          continue;
        }
        std::string error;
        const std::vector<TopoDS_Face> pierced = pierce(pieces[i], holes[i], options.verify_booleans, error);
        if (!error.empty()) return "holes in the skin: " + error;
        faces_out.insert(faces_out.end(), pierced.begin(), pierced.end());
        for (const TopoDS_Face& face : pierced) checked.insert(face.TShape().get());  // pierce checked them
      }
      return collect(compound_of(std::vector<TopoDS_Shape>(faces_out.begin(), faces_out.end())), false, kept, false,
                     checked);
    };
    std::vector<TopoDS_Face> kept;
    std::string error;
    if (unite && options.policy == TrimPolicy::Clip) {
      // skin U (lattice n inner): the clipped clusters touch the skin only along their cut faces, pieces of the
      // inner boundary's faces that nothing crosses. Where they can, the cut faces become holes in the skin's
      // inner faces (no Boolean: skin_holes.hpp); the other clusters go into a glued Fuse with the skin, with no
      // surface-surface intersection at all (each cluster met the inner body in its own local Common above).
      // Should either go wrong, the union is done again through the pores.
      error = through_holes(kept);
      if (!error.empty()) {
        kept.clear();
        stats.union_through_pores = true;
        stats.pores_reason = error;
        // For the developers: STEADY_TRIM_VERBOSE=1 says why as soon as it happens (a pores' Cut can be long).
        if (std::getenv("STEADY_TRIM_VERBOSE")) std::fprintf(stderr, "trim: through the pores: %s\n", error.c_str());
        stats.holed_clusters = 0;
        const std::string retry = through_pores(kept);
        error = retry.empty() ? "" : error + "; and through the pores: " + retry;
      }
    } else if (unite) {
      // Whole: hubs are never cut, so they cross the inner boundary: through the pores.
      error = through_pores(kept);
    } else {
      // The clipped clusters' faces were each checked right after their Common (cluster_result_ok).
      error = collect(compound_of(results), false, kept, tool != nullptr);
    }
    if (!error.empty()) throw std::runtime_error("trim: " + error + "; the pieces cannot be glued");
    stats.union_seconds = seconds_since(union_clock);
    union_progress.finish();
    faces.insert(faces.end(), kept.begin(), kept.end());
  } else if (skin && options.unite_skin) {
    for (TopExp_Explorer x(skin->skin, TopAbs_FACE); x.More(); x.Next()) faces.push_back(TopoDS::Face(x.Current()));
  }
  stats.boolean_seconds = seconds_since(clock);
  clock = std::chrono::steady_clock::now();
  if (faces.empty()) fail_input("body", "nothing of the lattice lies inside the body");
  TopoDS_Shape shape;
  {
    Progress part(progress, rest_part(assemble_weight));
    shape = solids_from_faces(faces, part);
  }
  if (skin && !options.unite_skin) {
    out.lattice = shape;
    out.part = compound_of({out.skin, out.lattice});
  } else {
    out.part = shape;
    out.lattice = shape;
  }
  stats.faces = static_cast<std::int64_t>(faces.size());
  stats.assemble_seconds = seconds_since(clock);
  progress.finish();
  return out;
}

TrimResult trim_lattice(const FlatLattice& f, const TopoDS_Shape& body_shape, const TrimOptions& options,
                        Progress& progress) {
  // OpenCASCADE's Booleans may fail on the boundary hubs (detected: see collect); their outcome depends on how the
  // spheres are parametrized (where a seam or pole sits relative to the body's surface) and on how the hubs are
  // grouped into clusters. The attempts, in order: the first as asked; then, when cuts were moved, every cut
  // halfway (larger clusters: other numbers in OpenCASCADE, and fuzzy retries scaled to a larger cluster; measured:
  // at 101,343 beams in a cylinder along the beams, a lone hub whose beam the wall grazes by 0.003 failed every
  // per-cluster retry, and clips within a cluster of several); then the spheres laid out the other way (measured:
  // a cylinder tilted by 0.3 rad that failed the first layout trims with the second). The progress bar does not go
  // back; the later attempts report nothing.
  struct Attempt {
    SeamPreference seams;
    bool move_cuts;
  };
  std::vector<Attempt> attempts = {{SeamPreference::FewestCrossings, options.move_cuts}};
  if (options.move_cuts) attempts.push_back({SeamPreference::FewestCrossings, false});
  attempts.push_back({SeamPreference::MostCrossings, false});
  std::string failures;
  for (std::size_t k = 0; k < attempts.size(); ++k) {
    TrimOptions o = options;
    o.move_cuts = attempts[k].move_cuts;
    try {
      if (k == 0) return trim_attempt(f, body_shape, o, attempts[k].seams, progress);
      TrimResult retried = trim_attempt(f, body_shape, o, attempts[k].seams, no_progress());
      retried.stats.relaid_out = true;
      retried.stats.relaid_reason = failures;
      progress.finish();
      return retried;
    } catch (const Cancelled&) {
      throw;
    } catch (const ResourceLimit&) {
      throw;  // too large for memory: no other attempt fits either
    } catch (const std::runtime_error& e) {
      progress.check();
      if (std::getenv("STEADY_TRIM_VERBOSE"))
        std::fprintf(stderr, "trim: attempt %zu of %zu failed: %s\n", k + 1, attempts.size(), e.what());
      failures += (failures.empty() ? "" : "; then ") + std::string(e.what());
    }
  }
  throw std::runtime_error(failures +
                           ". OpenCASCADE's Booleans fail where the body's surface grazes the lattice (runs along a "
                           "beam, or nearly touches a ball): moving or resizing the body slightly helps");
}

}  // namespace steady
