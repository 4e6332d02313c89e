// Trimming: where the beams between boundary hubs are cut, and the clusters of boundary hubs that leaves.
//
// Band hubs are clipped in independent clusters, in parallel: a beam between two band hubs is split at its cut
// (each side closed by its own disk) when that disk is clear of every boundary the Booleans use, so each side
// comes out of its Boolean untouched or wholly deleted and the two sides can be glued again. Where halfway is
// not clear, another place along the beam may be (docs/brep.md, "moved cuts").
#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "brep/trim_phases.hpp"
#include "core/disjoint_sets.hpp"

namespace steady::trim {
namespace {

// Places tried for a beam's cut when halfway is not clear of the boundary, as fractions of the way between its
// stumps' starts: nearest the middle first, never nearer a start than a tenth of the way.
constexpr double kMovedCutPlaces[] = {0.35, 0.65, 0.2, 0.8, 0.1, 0.9};

// Where the cuts of the beams between band hubs may go.
class CutPlacer {
 public:
  CutPlacer(const FlatLattice& f, const HubRoles& roles, const SolidBody* boundary, double clearance,
            std::vector<BeamFrustum>& frustums, TrimStats& stats, const KnownCollars& known)
      : f_(f), roles_(roles), boundary_(boundary), clearance_(clearance), frustums_(frustums), stats_(stats),
        known_(known) {}

  // A cut is clear when its disk keeps off the boundary the Booleans use.
  bool clear(const Circle& cut) {
    if (!boundary_ || boundary_->distance_lower_bound(cut.center) > cut.radius + clearance_) return true;
    ++stats_.exact_distance_tests;
    return boundary_->exact_distance(cut.center) > cut.radius + clearance_;
  }

  // A clear place for the cut of beam e between its stumps' starts (kept a tenth of the way off them), or NaN.
  double clear_cut_fraction(std::int64_t e) {
    BeamFrustum fr = frustums_[e];
    const double from = stump_start(f_.beams[e].a, e), to = fr.cone.length - stump_start(f_.beams[e].b, e);
    if (!(from < to)) return std::nan("");
    for (const double u : kMovedCutPlaces) {
      fr.cut_fraction = (from + u * (to - from) - fr.exit_a) / fr.length();
      if (fr.cut_fraction > 0.0 && fr.cut_fraction < 1.0 && clear(fr.cut_circle())) return fr.cut_fraction;
    }
    return std::nan("");
  }

 private:
  // Where a boundary hub's stumps start (exit circles, or a crowded hub's collars), for the beams its build has.
  double stump_start(std::int64_t ball, std::int64_t e) {
    auto found = starts_.find(ball);
    if (found == starts_.end()) found = starts_.emplace(ball, stump_starts(f_, frustums_, roles_.band_beams, ball)).first;
    const double planned = found->second[f_.incident_slot(ball, e)];
    const auto built = known_.find(2 * e + (f_.beams[e].a == ball ? 0 : 1));
    return built != known_.end() && !(planned >= built->second) ? built->second : planned;
  }

  const FlatLattice& f_;
  const HubRoles& roles_;
  const SolidBody* boundary_;
  double clearance_;
  std::vector<BeamFrustum>& frustums_;
  TrimStats& stats_;
  const KnownCollars& known_;
  std::unordered_map<std::int64_t, std::vector<double>> starts_;
};

}  // namespace

CutPlan place_cuts(const FlatLattice& f, const HubRoles& roles, const Bodies& bodies, const TrimOptions& options,
                   std::vector<BeamFrustum>& frustums, TrimStats& stats, Progress& progress,
                   const KnownCollars& known) {
  CutPlan plan;
  // Clip: the clusters meet the body, or with a skin its inner offset. Whole with a skin: the band is fused with
  // the skin in one Boolean and is not split.
  if (options.policy == TrimPolicy::Clip) plan.boundary = bodies.inner ? &*bodies.inner : &bodies.body;
  plan.split.assign(f.beam_count(), 0);
  plan.moved.assign(f.beam_count(), 0);
  DisjointSets roots(static_cast<std::size_t>(f.ball_count()));
  CutPlacer placer(f, roles, plan.boundary, kClearanceRelative * bodies.body.size(), frustums, stats, known);
  // Where each cut was before this step (halfway, or between crowded hubs' collars), to go back to.
  std::vector<double> first_place(f.beam_count());
  for (std::int64_t e = 0; e < f.beam_count(); ++e) first_place[e] = frustums[e].cut_fraction;
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!roles.beam_kept[e] || !roles.band[f.beams[e].a] || !roles.band[f.beams[e].b]) continue;
    progress.advance();
    if (!plan.boundary || roles.no_room[e]) {  // no room: built whole, its hubs in one cluster
      roots.join(f.beams[e].a, f.beams[e].b);
      continue;
    }
    if (placer.clear(frustums[e].cut_circle())) {
      plan.split[e] = 1;
      continue;
    }
    // Halfway is not clear: another place along the beam may be (a beam crossing the boundary is clear of it
    // some way off the crossing), so that the boundary hubs of a lattice whose beams run near the body's
    // surface stay in small clusters (docs/brep.md, "moved cuts").
    const double t = options.move_cuts ? placer.clear_cut_fraction(e) : std::nan("");
    if (!std::isnan(t)) {
      frustums[e].cut_fraction = t;
      plan.split[e] = plan.moved[e] = 1;
    } else {
      roots.join(f.beams[e].a, f.beams[e].b);
    }
  }
  // The band hubs of a foreign contact are built in one group (foreign_groups.hpp): one cluster.
  for (const auto& [a, b] : roles.contacts.joined)
    if (roles.band[a] && roles.band[b]) roots.join(a, b);
  // A clear cut inside one cluster stays whole: its two disks would be coincident faces of one Boolean argument.
  for (std::int64_t e = 0; e < f.beam_count(); ++e)
    if (plan.split[e] && roots.root(f.beams[e].a) == roots.root(f.beams[e].b)) {
      plan.split[e] = plan.moved[e] = 0;
      frustums[e].cut_fraction = first_place[e];
    }
  stats.moved_cuts = std::count(plan.moved.begin(), plan.moved.end(), 1);
  plan.cut_fractions.resize(f.beam_count());
  for (std::int64_t e = 0; e < f.beam_count(); ++e) plan.cut_fractions[e] = frustums[e].cut_fraction;
  plan.cluster_root.resize(f.ball_count());
  for (std::int64_t i = 0; i < f.ball_count(); ++i) plan.cluster_root[i] = static_cast<std::int64_t>(roots.root(i));
  progress.finish();
  return plan;
}

Clusters group_clusters(const BrepPieces& band, const CutPlan& plan) {
  Clusters out;
  for (std::size_t k = 0; k < band.faces.size(); ++k) {
    const std::int64_t root = plan.cluster_root[band.face_owner[k]];
    auto [it, inserted] = out.index.emplace(root, static_cast<int>(out.faces.size()));
    if (inserted) out.faces.emplace_back();
    out.faces[it->second].push_back(band.faces[k]);
  }
  return out;
}

}  // namespace steady::trim
