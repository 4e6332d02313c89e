#include "steady/brep/trim.hpp"

#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>

#include <algorithm>
#include <chrono>
#include <fstream>
#include <stdexcept>
#include <unordered_set>

#include "brep/part_check.hpp"
#include "brep/grazing_beams.hpp"
#include "brep/pcurve_pieces.hpp"
#include "brep/loose_pieces.hpp"
#include "brep/trim_phases.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"
#include "steady/query/clean_check.hpp"

namespace steady {

TrimPolicy trim_policy_from_string(const std::string& name) {
  if (name == "clip") return TrimPolicy::Clip;
  if (name == "whole") return TrimPolicy::Whole;
  if (name == "bridge") return TrimPolicy::Bridge;
  fail_input("policy", "must be 'clip', 'whole' or 'bridge' (got '" + name + "')");
}

DanglingBeams dangling_from_string(const std::string& name) {
  if (name == "keep") return DanglingBeams::Keep;
  if (name == "remove") return DanglingBeams::Remove;
  fail_input("dangling", "must be 'keep' or 'remove' (got '" + name + "')");
}

namespace {

using namespace trim;

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

struct BuiltHubs {
  CutEdges cuts;  // the circles at the cuts, shared by both sides (and by a second layout of the band)
  BrepPieces band, interior;
};

// The boundary hubs (split at their clear cuts, spheres laid out by `seams`) and the interior hubs, Boolean-free.
BuiltHubs build_hubs(const FlatLattice& f, const HubRoles& roles, const CutPlan& plan, SeamPreference seams,
                     const WorkWeights& weights, TrimBudget& budget, const TrimOptions& options, TrimStats& stats) {
  const auto clock = std::chrono::steady_clock::now();
  BuiltHubs out;
  if (roles.has_band) {
    BrepSelection sel;
    sel.balls = roles.band;
    sel.beams = roles.band_beams;
    sel.split = plan.split;
    sel.cut_fractions = plan.cut_fractions;
    sel.seams = seams;
    sel.foreign = &roles.contacts;
    Progress part(budget.progress(), budget.rest(weights.build_band));
    out.band = build_brep_pieces(f, sel, out.cuts, part);
  }
  BrepSelection sel;
  sel.balls = roles.interior;
  sel.beams = roles.interior_beams;
  sel.open_cuts = roles.open_cuts;
  // The open cuts' circles are the band's (shared through out.cuts): the interior's half-beams must end where
  // the band put them (between crowded hubs' collars, or moved off the boundary), not halfway.
  if (roles.has_band) sel.cut_fractions = plan.cut_fractions;
  sel.foreign = &roles.contacts;
  {
    Progress part(budget.progress(), budget.rest(weights.build_interior));
    out.interior = build_brep_pieces(f, sel, out.cuts, part);
  }
  stats.build_seconds = seconds_since(clock);
  for (const BrepPieces* p : {&out.band, &out.interior}) {
    stats.core_hubs += p->stats.core_hubs;
    stats.distinct_cores += p->stats.distinct_cores;
    stats.fused_cores += p->stats.fused_cores;
    stats.tight_cores += p->stats.tight_cores;
    stats.hub_groups += p->stats.hub_groups;
    stats.grouped_hubs += p->stats.grouped_hubs;
    stats.foreign_groups += p->stats.foreign_groups;
    stats.foreign_hubs += p->stats.foreign_hubs;
  }
  report(options, "trim: built the boundary and interior hubs in " + std::to_string(stats.build_seconds) + " s (" +
                      std::to_string(out.band.stats.distinct_cores) + " and " +
                      std::to_string(out.interior.stats.distinct_cores) + " distinct cores)");
  return out;
}

// The band's faces: its clusters clipped (and retried), glued to the rest, united with the skin.
std::vector<TopoDS_Face> band_part(const ClipContext& c, BuiltHubs& built, SeamPreference seams,
                                   const WorkWeights& weights, TrimBudget& budget, TrimStats& stats) {
  Progress& progress = budget.progress();
  stats.band_clusters = static_cast<std::int64_t>(c.clusters.faces.size());
  CutDisks disks;
  {
    std::unordered_map<const void*, int> cluster_of_face;
    for (std::size_t k = 0; k < built.band.faces.size(); ++k)
      cluster_of_face.emplace(built.band.faces[k].TShape().get(), c.clusters.of_ball(c.plan, built.band.face_owner[k]));
    disks.add(built.band, 0, cluster_of_face, c.roles, c.plan, nullptr, c.frustums);
  }
  // The union with the skin (and a second way should the first go wrong) and the checks of what the Booleans made.
  Progress union_progress(progress, budget.rest(weights.skin_union + weights.verify),
                          weights.skin_union + weights.verify + 1);
  ClusterClips clips;
  {
    Progress booleans(progress, budget.rest(weights.boolean), static_cast<std::int64_t>(built.band.faces.size()));
    clips = clip_clusters(c, disks, booleans);
  }
  BrepPieces second_layout;  // the failed clusters' pieces laid out the other way: alive until the faces are kept
  retry_failed_clusters(c, seams, built.cuts, clips, disks, second_layout, stats, progress);
  const auto clock = std::chrono::steady_clock::now();
  BrepPieces rim_second_layout;  // likewise for the rim clusters, should they be clipped after all
  UnionContext u{c, clips, disks, built.interior.faces, union_progress, weights.skin_union, weights.verify, [&] {
                   clip_rim_clusters(c, seams, built.cuts, clips, disks, rim_second_layout, stats, progress);
                 }};
  std::vector<TopoDS_Face> kept;
  const std::string error = band_faces(u, kept, stats);
  if (!error.empty()) throw std::runtime_error("trim: " + error + "; the pieces cannot be glued");
  stats.union_seconds = seconds_since(clock);
  union_progress.finish();
  return kept;
}

// One attempt at trimming, with the boundary hubs' spheres laid out by `seams`: the phases of trim_phases.hpp.
TrimResult trim_attempt(const FlatLattice& f, const TopoDS_Shape& body_shape, const TrimOptions& options,
                        SeamPreference seams, const KnownCollars& known, Progress& progress) {
  TrimResult out;
  TrimStats& stats = out.stats;
  TrimBudget budget(progress);
  auto clock = std::chrono::steady_clock::now();
  const Bodies bodies = make_bodies(body_shape, options, budget);
  if (bodies.skin) out.skin = bodies.skin->skin;
  std::vector<BeamFrustum> frustums = beam_frustums(f);  // place_cuts moves some cuts
  // Before the hubs' reach is classified.
  const std::vector<char> no_room = place_cuts_between_collars(f, frustums, known);
  const std::vector<char> absorbed = absorbed_balls(f, frustums);
  const HubStates states = classify(f, frustums, absorbed, bodies, stats, budget);
  stats.classify_seconds = seconds_since(clock);
  const HubRoles roles =
      assign_roles(f, frustums, states, no_room, foreign_contacts(f), options, bodies.skin.has_value(), stats);
  const bool unite = bodies.skin && options.unite_skin;
  const WorkWeights weights = work_weights(f, roles, options, unite);
  budget.share_rest(weights.total());
  CutPlan plan;
  {
    Progress part(progress, budget.rest(weights.split), std::max<std::int64_t>(1, weights.band_band_beams));
    plan = place_cuts(f, roles, bodies, options, frustums, stats, part, known);
  }
  BuiltHubs built = build_hubs(f, roles, plan, seams, weights, budget, options, stats);
  clock = std::chrono::steady_clock::now();
  std::vector<TopoDS_Face> faces = built.interior.faces;
  if (roles.has_band) {
    const Clusters clusters = group_clusters(built.band, plan);
    const ClipContext c{f, frustums, options, bodies, roles, plan, clusters, built.band, unite};
    const std::vector<TopoDS_Face> kept = band_part(c, built, seams, weights, budget, stats);
    for (const TopoDS_Face& face : kept) give_edges_their_own_pcurves(face);  // the Booleans kept parents' pcurves
    faces.insert(faces.end(), kept.begin(), kept.end());
  } else if (unite) {
    for (TopExp_Explorer x(bodies.skin->skin, TopAbs_FACE); x.More(); x.Next()) faces.push_back(TopoDS::Face(x.Current()));
  }
  stats.boolean_seconds = seconds_since(clock);
  // Assembly.
  clock = std::chrono::steady_clock::now();
  if (faces.empty()) fail_input("body", "nothing of the lattice lies inside the body");
  TopoDS_Shape shape;
  {
    Progress part(progress, budget.rest(weights.assemble));
    shape = solids_from_faces(faces, part);
  }
  {
    const auto check_clock = std::chrono::steady_clock::now();
    if (!options.dump_directory.empty())  // the assembled part as checked, for study when the check refuses it
      std::ofstream(options.dump_directory + "/assembled_part.brep") << brep_to_text(shape);
    check_trimmed_part(f, shape, stats.core_hubs);
    report(options, "trim: checked the assembled part in " + std::to_string(seconds_since(check_clock)) + " s");
  }
  if (bodies.skin && !options.unite_skin) {
    const auto pieces_clock = std::chrono::steady_clock::now();
    std::unordered_set<const void*> interior_faces;
    for (const TopoDS_Face& face : built.interior.faces) interior_faces.insert(face.TShape().get());
    // No share of the bar, but cancellable (the main job: 7 s for the split along grazing beams, 2 s for the Fuse).
    Progress checks_only(progress, 0);
    const std::vector<std::int64_t> grazing_candidates = grazing_beams(f, frustums, *bodies.inner, checks_only);
    const GrazingSplit grazing =
        split_off_grazing_beams(shape, frustums, grazing_candidates, interior_faces, checks_only);
    stats.grazing_pieces = grazing.pieces;
    stats.grazing_seconds = seconds_since(pieces_clock);
    stats.grazing_kept_reason = grazing.kept_reason;
    report(options, "trim: " + std::to_string(grazing.pieces) + " lenses of " +
                        std::to_string(grazing_candidates.size()) + " beams grazing the inner wall split off" +
                        (grazing.kept_reason.empty() ? "" : "; the lattice kept whole: " + grazing.kept_reason));
    PartsApart apart = give_loose_pieces_to_skin(grazing.lattice, out.skin, interior_faces, checks_only);
    if (grazing.pieces > 0 && !apart.unfused_reason.empty()) {
      // The skin would be several solids: the lenses stay in the lattice, and only the pieces it had go over.
      stats.grazing_kept_reason = "the skin's glued Fuse with the lenses failed (" + apart.unfused_reason + ")";
      stats.grazing_pieces = 0;
      apart = give_loose_pieces_to_skin(shape, out.skin, interior_faces, checks_only);
    }
    report(options, "trim: " + std::to_string(apart.pieces) + " loose pieces of the lattice given to the skin in " +
                        std::to_string(seconds_since(pieces_clock)) + " s");
    out.lattice = apart.lattice;
    out.skin = apart.skin;
    stats.skin_pieces = apart.pieces;
    stats.skin_pieces_volume = apart.pieces_volume;
    if (!apart.unfused_reason.empty()) report(options, "trim: loose pieces left beside the skin: " + apart.unfused_reason);
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

}  // namespace

namespace {

// Where beams have no room between their crowded hubs' collars, the bands of cone left between the collars are
// thin, and OpenCASCADE's section with a curved wall can miss them (docs/brep.md, section 3): what helps there.
// Measured: the octet at beam/node 0.8 with a screw in a cylinder of radius 1.05 fails every attempt, at 0.75
// and 0.7 it trims.
std::string thin_bands_hint(const FlatLattice& f) {
  std::vector<BeamFrustum> frustums = beam_frustums(f);
  const std::vector<char> no_room = place_cuts_between_collars(f, frustums);
  const auto tight = std::count(no_room.begin(), no_room.end(), 1);
  if (tight == 0) return "";
  return "; here " + std::to_string(tight) + " beams have no room between their crowded hubs' collars, and the "
         "thin bands of cone between those the Booleans can miss: beams a little thinner than their nodes help";
}

}  // namespace

TrimResult trim_lattice(const FlatLattice& f, const TopoDS_Shape& body_shape, const TrimOptions& options,
                        Progress& progress) {
  if (options.policy == TrimPolicy::Bridge) return trim::trim_with_bridges(f, body_shape, options, progress);
  // OpenCASCADE's Booleans may fail on the boundary hubs (detected by the checks of each phase); their outcome
  // depends on how the spheres are parametrized and on how the hubs are grouped into clusters. The attempts, in
  // order: as asked; then, when cuts were moved, every cut halfway (larger clusters, other numbers in OpenCASCADE);
  // then the spheres laid out the other way (docs/brep.md, "the attempt ladder"). The progress bar does not go
  // back; the later attempts report nothing.
  struct Attempt {
    SeamPreference seams;
    bool move_cuts;
  };
  std::vector<Attempt> attempts = {{SeamPreference::FewestCrossings, options.move_cuts}};
  if (options.move_cuts) attempts.push_back({SeamPreference::FewestCrossings, false});
  attempts.push_back({SeamPreference::MostCrossings, false});
  std::string failures;
  // Collars a build found beyond the cuts placed for them (CollarPastCut): the same attempt runs again with its
  // cuts placed beyond them, up to kCollarRounds times (the FCC at beam/node 0.5 with a taper in a cylinder: a
  // core fused with collars 1.12 times as far out as planned).
  constexpr int kCollarRounds = 4;
  KnownCollars known;
  for (std::size_t k = 0; k < attempts.size(); ++k) {
    TrimOptions o = options;
    o.move_cuts = attempts[k].move_cuts;
    for (int round = 0;; ++round) {
      try {
        if (k == 0 && round == 0) return trim_attempt(f, body_shape, o, attempts[k].seams, known, progress);
        TrimResult retried = trim_attempt(f, body_shape, o, attempts[k].seams, known, no_progress());
        retried.stats.relaid_out = k > 0;
        retried.stats.relaid_reason = failures;
        progress.finish();
        return retried;
      } catch (const Cancelled&) {
        throw;
      } catch (const ResourceLimit&) {
        throw;  // too large for memory: no other attempt fits either
      } catch (const std::runtime_error& e) {
        progress.check();
        bool learnt = false;
        if (const CollarPastCut* past = dynamic_cast<const CollarPastCut*>(&e))
          for (const CollarPastCut::End& end : past->ends) {
            double& collar = known[2 * end.beam + end.end];
            learnt = learnt || !(collar >= end.collar);
            collar = std::max(collar, end.collar);
          }
        if (learnt && round < kCollarRounds) {
          trim::report(options, "trim: cuts placed again beyond the collars the build found: " + std::string(e.what()));
          continue;
        }
        trim::report(options, "trim: attempt " + std::to_string(k + 1) + " of " + std::to_string(attempts.size()) +
                                  " failed: " + e.what());
        // A failure said once: the attempts often fail alike (the same cluster, the same checks).
        if (failures.find(e.what()) == std::string::npos)
          failures += (failures.empty() ? "" : "; then ") + std::string(e.what());
        break;
      }
    }
  }
  throw std::runtime_error(failures + " (" + std::to_string(attempts.size()) + " attempts: as asked" +
                           (options.move_cuts ? ", every cut halfway" : "") + ", the spheres laid out the other way)" +
                           ". OpenCASCADE's Booleans fail where the body's surface grazes the lattice (runs along a "
                           "beam, or nearly touches a ball): moving or resizing the body slightly helps" +
                           thin_bands_hint(f));
}

}  // namespace steady
