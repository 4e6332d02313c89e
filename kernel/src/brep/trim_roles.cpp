// Trimming, first phases: the bodies, every hub's state against their boundaries, the hubs' and beams' roles, and
// the estimates that share the progress among what follows.
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

#include "brep/trim_phases.hpp"
#include "steady/core/errors.hpp"

namespace steady::trim {
namespace {

// Work units of an attempt (its progress' total) and the fixed shares: the body (its triangulation) and its skin
// (the offset, its triangulation), the hubs' bounding pieces, each classification.
constexpr std::int64_t kTrimUnits = 100000;
constexpr std::int64_t kBodyUnits = 1000, kSkinUnits = 4000, kPiecesUnits = 1000, kClassifyUnits = 4000;
// Estimates of the rest, relative to building one element (ball or beam) = 2, measured on a cubic strut lattice
// in a cylinder (curved bodies: surface-surface intersections; a box's planes make the Booleans several times
// cheaper, and everything fast): per beam whose cut needs an exact distance (cluster split); per crossing hub,
// its cluster's Common with the body, the union with the skin (holes, and the rim clusters' glued Fuse or Cut) or
// else the Cut through the pores, the check of the faces the Booleans produced; per element, the assembly into
// solids.
constexpr std::int64_t kBuildPerElement = 2, kSplitPerBeam = 2, kBooleanPerHub = 2000, kSkinUnionPerHub = 800,
                       kPoresCutPerHub = 3000, kVerifyPerHub = 300, kAssemblePerElement = 3;

}  // namespace

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

namespace {

// Which pieces the triangulation's lower bound of the distance clears (most of them), per hub; `clear` marks the
// hubs it clears whole.
std::vector<std::vector<char>> undecided_pieces(const std::vector<char>& absorbed,
                                                const std::vector<std::vector<Piece>>& pieces, const SolidBody& body,
                                                double clearance, std::vector<char>& clear, Progress& progress) {
  const std::int64_t n = static_cast<std::int64_t>(pieces.size());
  std::vector<std::vector<char>> undecided(n);
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
  return undecided;
}

// Inside / outside / crossing of every (non-absorbed) hub against a body's boundary.
std::vector<HubState> classify_against(const FlatLattice& f, const std::vector<char>& absorbed,
                                       const std::vector<std::vector<Piece>>& pieces, const SolidBody& body,
                                       TrimStats& stats, Progress& progress) {
  const std::int64_t n = f.ball_count();
  // Units: the triangulation's bounds 20, the exact distances 70 (BRepExtrema, serial: most of the time when many
  // hubs lie near the boundary), the regions and their point classifications 10.
  progress.set_total(100);
  std::vector<HubState> state(n, HubState::Absent);
  const double clearance = kClearanceRelative * body.size();
  std::vector<char> clear(n, 0);
  const std::vector<std::vector<char>> undecided = undecided_pieces(absorbed, pieces, body, clearance, clear, progress);
  // The rest need the exact distance (serial).
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
  // The clear hubs' state spreads along beams: one point classification per connected region.
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

}  // namespace

TrimBudget::TrimBudget(Progress& progress) : progress_(progress) { progress_.set_total(kTrimUnits); }

std::int64_t TrimBudget::fixed(std::int64_t units) {
  fixed_ += units;
  return units;
}

std::int64_t TrimBudget::rest(std::int64_t weight) const {
  return static_cast<std::int64_t>(static_cast<double>(kTrimUnits - fixed_) * static_cast<double>(weight) /
                                   static_cast<double>(rest_weight_));
}

Bodies make_bodies(const TopoDS_Shape& body_shape, const TrimOptions& options, TrimBudget& budget) {
  if (!std::isfinite(options.skin) || options.skin < 0.0) {
    std::ostringstream os;
    os << "must be a thickness >= 0 (got " << options.skin << ")";
    fail_input("skin", os.str());
  }
  budget.progress().check();
  Bodies out{SolidBody(body_shape, "body"), std::nullopt, std::nullopt};
  budget.progress().advance(budget.fixed(kBodyUnits));
  if (options.skin > 0.0) {
    Progress part(budget.progress(), budget.fixed(kSkinUnits));
    out.skin = make_skin(out.body, options.skin, part);
    out.inner.emplace(out.skin->inner, "skin");
  }
  return out;
}

HubStates classify(const FlatLattice& f, const std::vector<BeamFrustum>& frustums, const std::vector<char>& absorbed,
                   const Bodies& bodies, TrimStats& stats, TrimBudget& budget) {
  std::vector<std::vector<Piece>> pieces;
  {
    Progress part(budget.progress(), budget.fixed(kPiecesUnits));
    pieces = hub_pieces(f, frustums, part);
  }
  HubStates out;
  {
    Progress part(budget.progress(), budget.fixed(kClassifyUnits));
    out.outer = classify_against(f, absorbed, pieces, bodies.body, stats, part);
  }
  out.inner = out.outer;
  if (bodies.inner) {
    Progress part(budget.progress(), budget.fixed(kClassifyUnits));
    out.inner = classify_against(f, absorbed, pieces, *bodies.inner, stats, part);
  }
  return out;
}

HubCounts count_hubs(const HubStates& states) {
  HubCounts c;
  bool any_in_body = false;
  for (std::size_t i = 0; i < states.outer.size(); ++i) {
    const HubState o = states.outer[i], s = states.inner[i];
    if (o == HubState::Absent) continue;
    any_in_body = any_in_body || o != HubState::Outside;
    c.inside += s == HubState::Inside;
    c.outside += s == HubState::Outside;
    c.crossing += s == HubState::Crossing;
  }
  if (!any_in_body)
    fail_input("body", "the lattice does not meet the body (all " + std::to_string(states.outer.size()) +
                           " hubs lie outside it)");
  return c;
}

HubRoles assign_roles(const FlatLattice& f, const std::vector<BeamFrustum>& frustums, const HubStates& states,
                      const std::vector<char>& no_room, ForeignContacts contacts, const TrimOptions& options,
                      bool has_skin, TrimStats& stats) {
  // Hubs: interior hubs are built whole with no Boolean; band hubs go through the Booleans.
  const std::int64_t n = f.ball_count();
  HubRoles r;
  r.interior.assign(n, 0);
  r.band.assign(n, 0);
  const HubCounts counts = count_hubs(states);
  stats.inside_hubs += counts.inside;
  stats.outside_hubs += counts.outside;
  stats.crossing_hubs += counts.crossing;
  for (std::int64_t i = 0; i < n; ++i) {
    const HubState o = states.outer[i], s = states.inner[i];
    if (o == HubState::Absent) continue;
    if (options.policy == TrimPolicy::Clip) {
      r.interior[i] = s == HubState::Inside;
      r.band[i] = s == HubState::Crossing;
    } else {
      // Whole: only hubs entirely inside the body; with a skin, those crossing its inner boundary fuse with it.
      r.interior[i] = o == HubState::Inside && s == HubState::Inside;
      r.band[i] = has_skin && o == HubState::Inside && s == HubState::Crossing;
    }
  }
  // A beam with no room for a cut between its hubs' collars cannot be glued, or end, at a cut: its two hubs are
  // built in one piece (tight collars, or a group fused as one), so both go through the band's Booleans. Along
  // chains of such beams (a dense octet at beam/node 1.0 has nothing else) the band grows until no interior hub is
  // joined so to a band hub. When clipping with dangling beams kept, a dropped hub joined so to a kept one joins
  // the band too (the Boolean removes it); it pulls in nothing more, and its beams to other dropped hubs, outside
  // like both their hubs' reach, are not kept.
  // The hubs of a foreign contact (and of a beam in one, never cut) are joined the same way.
  r.contacts = std::move(contacts);
  r.no_room = no_room;
  for (std::int64_t e = 0; e < f.beam_count(); ++e)
    r.no_room[e] = r.no_room[e] || (!r.contacts.empty() && r.contacts.involved[e]);
  std::vector<std::pair<std::int64_t, std::int64_t>> joined = r.contacts.joined;
  for (std::int64_t e = 0; e < f.beam_count(); ++e)
    if (r.no_room[e] && frustums[e].exists) joined.emplace_back(f.beams[e].a, f.beams[e].b);
  std::vector<char> pulled_in(n, 0);
  const bool pull_dropped = options.policy == TrimPolicy::Clip && options.dangling == DanglingBeams::Keep;
  for (bool grew = true; grew;) {
    grew = false;
    for (const auto& [a, b] : joined) {
      for (const auto& [kept, other] : {std::pair{a, b}, std::pair{b, a}}) {
        const bool kept_hub = r.band[kept] || r.interior[kept];
        const bool dropped = !r.band[other] && !r.interior[other] && states.outer[other] != HubState::Absent;
        if (r.band[kept] && r.interior[other])
          r.interior[other] = 0;
        else if (pull_dropped && kept_hub && !pulled_in[kept] && dropped)
          pulled_in[other] = 1;
        else
          continue;
        r.band[other] = 1;
        ++stats.joined_band_hubs;
        grew = true;
      }
    }
  }
  r.has_band = std::any_of(r.band.begin(), r.band.end(), [](char c) { return c; });
  const bool nothing_kept = !r.has_band && std::none_of(r.interior.begin(), r.interior.end(), [](char c) { return c; });
  if (nothing_kept) {
    if (options.policy == TrimPolicy::Whole)
      fail_input("policy", "'whole' keeps only hubs entirely inside the body, and none is: the trimmed lattice is empty");
    fail_input("skin", "leaves no room for the lattice: no hub reaches inside the inner offset");
  }
  // Beams: kept unless both hubs are dropped, or one is and dangling beams are removed.
  r.beam_kept.assign(f.beam_count(), 0);
  r.band_beams.assign(f.beam_count(), 0);
  r.interior_beams.assign(f.beam_count(), 0);
  r.open_cuts.assign(f.beam_count(), 0);
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!frustums[e].exists) continue;
    const std::int64_t a = f.beams[e].a, b = f.beams[e].b;
    const bool ka = r.interior[a] || r.band[a], kb = r.interior[b] || r.band[b];
    if ((!ka || pulled_in[a]) && (!kb || pulled_in[b])) continue;
    if ((!ka || !kb) && options.dangling == DanglingBeams::Remove) {
      ++stats.removed_beams;
      continue;
    }
    // Keeping hubs whole, a dangling beam ends at its cut, which such a beam's kept hub covers with its collar.
    if (r.no_room[e] && (!ka || !kb) && options.policy == TrimPolicy::Whole)
      fail_input("dangling", "beam " + std::to_string(e) + " (balls " + std::to_string(a) + " and " +
                                 std::to_string(b) + ") " +
                                 (no_room[e] ? "has no room for a cut between its crowded hubs' collars"
                                             : "meets an element of another node, so it cannot end at a cut") +
                                 ", and only one of its hubs is kept whole: remove dangling beams (dangling='remove'), "
                                 "or clip (policy 'clip'), which keeps both hubs until the Boolean");
    r.beam_kept[e] = 1;
    r.band_beams[e] = r.band[a] || r.band[b];
    r.interior_beams[e] = r.interior[a] || r.interior[b];
    r.open_cuts[e] = (r.band[a] && r.interior[b]) || (r.band[b] && r.interior[a]);
  }
  return r;
}

WorkWeights work_weights(const FlatLattice& f, const HubRoles& r, const TrimOptions& options, bool unite) {
  WorkWeights w;
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    w.band_hubs += r.band[i];
    w.interior_elements += r.interior[i];
  }
  w.band_elements = w.band_hubs;
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!r.beam_kept[e]) continue;
    w.interior_elements += r.interior_beams[e];
    w.band_elements += r.band_beams[e];
    w.band_band_beams += r.band[f.beams[e].a] && r.band[f.beams[e].b];
  }
  const bool clip = options.policy == TrimPolicy::Clip;
  w.split = kSplitPerBeam * w.band_band_beams;
  w.build_band = kBuildPerElement * w.band_elements;
  w.build_interior = kBuildPerElement * w.interior_elements;
  w.boolean = r.has_band ? (clip ? kBooleanPerHub : kBuildPerElement) * w.band_hubs : 0;
  w.skin_union = r.has_band && unite ? (clip ? kSkinUnionPerHub : kPoresCutPerHub) * w.band_hubs : 0;
  w.verify = r.has_band && options.verify_booleans ? kVerifyPerHub * w.band_hubs : 0;
  w.assemble = kAssemblePerElement * (w.band_elements + w.interior_elements) + 1;
  return w;
}

}  // namespace steady::trim
