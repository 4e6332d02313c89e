#include "steady/query/hub_overlaps.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>
#include <unordered_map>

#include "steady/lattice/convex_distance.hpp"
#include "steady/lattice/hub.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"

namespace steady {
namespace {

// Pieces are shrunk by this fraction of their size before the distance test, so that pieces which only touch
// (a node ball exactly at its beam's mid-plane, equal balls in contact) are not reported; overlaps deeper than
// ~1e-9 of the size are. The distance test converges to 1e-11 of the size.
constexpr double kShrink = 1e-9;
constexpr double kDistanceTolerance = 1e-11;

// A convex piece of a hub: its ball, or a stump = hull(end ball at the node, cut disk).
struct Piece {
  bool stump = false;
  BeamId beam;            // stumps: the beam, and whether the hub's node is its start
  bool at_start = false;
  Vec3 a{0.0};            // ball center
  double r = 0.0;         // ball radius
  Vec3 m{0.0}, n{0.0};    // cut disk center and normal (away from the node)
  double rho = 0.0;       // cut disk radius
  Vec3 bound_center{0.0};
  double bound_radius = 0.0;
};

struct HubPieces {
  NodeId id;
  Vec3 center{0.0};
  double reach = 0.0;  // bounding sphere about the node center
  std::vector<Piece> pieces;
  // Beams (and whether the node is their start) whose cut was moved into the ball (to a crowded hub's collar): the
  // hub ends at the cut disk, and the ball's cap beyond it belongs to the beam's far stump. (A ball reaching past
  // its beam's mid-plane still overlaps the far hub: the lattice is not clean there.)
  std::vector<std::pair<BeamId, bool>> cut_inside_ball;
};

HubPieces hub_pieces(const Hub& h) {
  HubPieces out;
  out.id = h.node;
  out.center = h.ball.center;
  out.reach = h.ball.radius;
  Piece ball;
  ball.a = h.ball.center;
  ball.r = h.ball.radius;
  ball.bound_center = ball.a;
  ball.bound_radius = ball.r;
  out.pieces.push_back(ball);
  for (const Stump& s : h.stumps) {
    Piece p;
    p.stump = true;
    p.beam = s.beam;
    p.at_start = s.at_start;
    p.a = s.cone.a;
    p.r = s.cone.ra;
    p.m = s.cut.center;
    p.n = s.cut.normal;
    p.rho = s.cut.radius;
    p.bound_center = 0.5 * (p.a + p.m);
    p.bound_radius = std::max(glm::length(p.a - p.bound_center) + p.r,
                              std::sqrt(glm::dot(p.m - p.bound_center, p.m - p.bound_center) + p.rho * p.rho));
    out.reach = std::max(out.reach, glm::length(p.bound_center - out.center) + p.bound_radius);
    out.pieces.push_back(p);
    const bool moved = std::abs(s.cut_position - 0.5 * s.cone.length) > 1e-12 * s.cone.length;
    if (moved && s.cut_position < h.ball.radius) out.cut_inside_ball.emplace_back(s.beam, s.at_start);
  }
  return out;
}

HubPieces hub_pieces(const Lattice& lattice, const NodeId& id) { return hub_pieces(hub(lattice, id)); }

// Farthest point of the shrunk piece along d.
Vec3 support(const Piece& p, double shrink, const Vec3& d) {
  const double len = glm::length(d);
  const Vec3 u = len > 0.0 ? d / len : Vec3(1.0, 0.0, 0.0);
  const Vec3 on_ball = p.a + std::max(0.0, p.r - shrink) * u;
  if (!p.stump) return on_ball;
  const Vec3 across = u - glm::dot(u, p.n) * p.n;
  const double across_len = glm::length(across);
  const Vec3 m = p.m - shrink * p.n;
  const Vec3 on_disk = across_len > 1e-300 ? m + std::max(0.0, p.rho - shrink) * (across / across_len) : m;
  return glm::dot(on_ball, u) >= glm::dot(on_disk, u) ? on_ball : on_disk;
}

bool pieces_overlap(const Piece& p, const Piece& q) {
  if (p.stump && q.stump && p.beam == q.beam && p.at_start != q.at_start) return false;  // share their cut disk
  if (glm::length(p.bound_center - q.bound_center) >= p.bound_radius + q.bound_radius) return false;
  const double size = std::max(p.bound_radius, q.bound_radius);
  const double shrink = kShrink * size, tolerance = kDistanceTolerance * size;
  // GJK (the B-rep clean check's): stops as soon as the shrunk pieces are proven apart or in contact.
  const DistanceBounds d = convex_distance([&](const Vec3& v) { return support(p, shrink, v); },
                                           [&](const Vec3& v) { return support(q, shrink, v); }, tolerance, tolerance);
  return d.intersecting || d.upper <= tolerance;
}

std::string piece_name(const Piece& p) {
  return p.stump ? "stump of beams[" + std::to_string(p.beam.pattern) + "]" : "ball";
}

// Overlap between two hubs: the first overlapping pair of pieces, or empty.
// Whether q is the far stump of a beam of `h` whose cut lies inside h's ball: the two meet only in the ball's cap
// beyond the cut, which is q's, not the hub's.
bool far_stump_past_ball(const HubPieces& h, const Piece& q) {
  return q.stump && std::find(h.cut_inside_ball.begin(), h.cut_inside_ball.end(),
                              std::make_pair(q.beam, !q.at_start)) != h.cut_inside_ball.end();
}

bool hubs_overlap(const HubPieces& x, const HubPieces& y, std::string* detail) {
  if (glm::length(x.center - y.center) >= x.reach + y.reach) return false;
  for (const Piece& p : x.pieces)
    for (const Piece& q : y.pieces)
      if (!(!p.stump && far_stump_past_ball(x, q)) && !(!q.stump && far_stump_past_ball(y, p)) &&
          pieces_overlap(p, q)) {
        if (detail) *detail = piece_name(p) + " / " + piece_name(q);
        return true;
      }
  return false;
}

}  // namespace

bool hubs_overlap(const Hub& a, const Hub& b, std::string* detail) {
  return hubs_overlap(hub_pieces(a), hub_pieces(b), detail);
}

bool cut_disk_meets_other_stumps(const Hub& h, std::size_t stump) {
  const HubPieces pieces = hub_pieces(h);
  Piece disk = pieces.pieces[stump + 1];  // the hull of a point at the disk's center and the disk: the disk
  disk.a = disk.m;
  disk.r = 0.0;
  disk.bound_center = disk.m;
  disk.bound_radius = disk.rho;
  for (std::size_t k = 1; k < pieces.pieces.size(); ++k)
    if (k != stump + 1 && pieces_overlap(disk, pieces.pieces[k])) return true;
  return false;
}

namespace {

struct Collector {
  std::mutex lock;
  HubOverlapReport* report;
  std::size_t max_reports;
  void add(const NodeId& a, const NodeId& b, std::string detail, std::int64_t multiplicity) {
    std::lock_guard<std::mutex> guard(lock);
    report->overlap_count += multiplicity;
    report->overlaps.push_back({a, b, std::move(detail)});
  }
};

// Linear order of node ids, to list overlaps deterministically.
bool before(const NodeId& a, const NodeId& b) {
  return std::tie(a.k, a.j, a.i, a.n) < std::tie(b.k, b.j, b.i, b.n);
}

void finish(HubOverlapReport& report, std::size_t max_reports) {
  for (HubOverlap& o : report.overlaps)
    if (before(o.b, o.a)) std::swap(o.a, o.b);
  std::sort(report.overlaps.begin(), report.overlaps.end(), [](const HubOverlap& x, const HubOverlap& y) {
    return before(x.a, y.a) || (x.a == y.a && before(x.b, y.b));
  });
  if (report.overlaps.size() > max_reports) report.overlaps.resize(max_reports);
}

// Checks every pair (x in `a`, y in `b`) whose bounding spheres meet, through a grid of `b` with cells of the
// median reach; when a and b are the same set, each unordered pair once. Each pair found counts
// `multiplicity` times (the pair stands for that many similar pairs of the lattice).
void check_hubs(const std::vector<HubPieces>& a, const std::vector<HubPieces>& b, bool same, std::int64_t multiplicity,
                Collector& out, Progress& progress) {
  if (a.empty() || b.empty()) return;
  std::vector<double> reaches;
  for (const HubPieces& h : b) reaches.push_back(h.reach);
  std::nth_element(reaches.begin(), reaches.begin() + reaches.size() / 2, reaches.end());
  double cell = 2.0 * std::max(reaches[reaches.size() / 2], 1e-300);
  // A hub covers (2 reach / cell + 1)^3 cells. With reaches far apart (a dilation of 150 a step: balls of 0.1 and
  // of 1e7 in one lattice) the median's cells made one hub cover some 1e20 of them, and the process ran out of
  // memory in seconds (found with fuzz_lattice_json's input of a steep dilation). The cells grow until the hubs of
  // both sets cover at most 64 cells each on average: the grid is only the broad phase, so the pairs are the same.
  auto cells_covered = [&](double size) {
    double total = 0.0;
    for (const std::vector<HubPieces>* set : {&a, &b})
      for (const HubPieces& h : *set) {
        double cells = 1.0;
        for (int axis = 0; axis < 3; ++axis)
          cells *= std::floor((h.center[axis] + h.reach) / size) - std::floor((h.center[axis] - h.reach) / size) + 1.0;
        total += cells;
      }
    return total;
  };
  while (cells_covered(cell) > 64.0 * static_cast<double>(a.size() + b.size()) && std::isfinite(cell)) cell *= 2.0;
  auto key = [](std::int64_t x, std::int64_t y, std::int64_t z) {
    return (static_cast<std::uint64_t>(x) * 73856093u) ^ (static_cast<std::uint64_t>(y) * 19349663u) ^
           (static_cast<std::uint64_t>(z) * 83492791u);
  };
  auto cell_of = [cell](double v) { return static_cast<std::int64_t>(std::floor(v / cell)); };
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
  for (std::size_t h = 0; h < b.size(); ++h) {
    const Vec3 lo = b[h].center - b[h].reach, hi = b[h].center + b[h].reach;
    for (std::int64_t x = cell_of(lo.x); x <= cell_of(hi.x); ++x)
      for (std::int64_t y = cell_of(lo.y); y <= cell_of(hi.y); ++y)
        for (std::int64_t z = cell_of(lo.z); z <= cell_of(hi.z); ++z) grid[key(x, y, z)].push_back(static_cast<std::uint32_t>(h));
  }
  tbb::parallel_for(std::size_t(0), a.size(), [&](std::size_t h) {
    progress.advance();
    const HubPieces& x = a[h];
    const Vec3 lo = x.center - x.reach, hi = x.center + x.reach;
    std::vector<std::uint32_t> seen;
    for (std::int64_t cx = cell_of(lo.x); cx <= cell_of(hi.x); ++cx)
      for (std::int64_t cy = cell_of(lo.y); cy <= cell_of(hi.y); ++cy)
        for (std::int64_t cz = cell_of(lo.z); cz <= cell_of(hi.z); ++cz) {
          const auto it = grid.find(key(cx, cy, cz));
          if (it == grid.end()) continue;
          for (std::uint32_t other : it->second)
            if (!same || other > h) seen.push_back(other);
        }
    std::sort(seen.begin(), seen.end());
    seen.erase(std::unique(seen.begin(), seen.end()), seen.end());
    for (std::uint32_t other : seen) {
      std::string detail;
      if (hubs_overlap(x, b[other], &detail)) out.add(x.id, b[other].id, detail, multiplicity);
    }
  });
}

std::vector<NodeId> slab_nodes(const Lattice& lattice, std::int64_t k) {
  std::vector<NodeId> ids;
  const Counts& c = lattice.counts();
  for (std::int64_t j = 0; j < c.v; ++j)
    for (std::int64_t i = 0; i < c.u; ++i)
      for (int n = 0; n < lattice.node_count(); ++n)
        if (lattice.node_exists({i, j, k, n})) ids.push_back({i, j, k, n});
  return ids;
}

std::vector<HubPieces> pieces_of(const Lattice& lattice, const std::vector<NodeId>& ids) {
  std::vector<HubPieces> hubs(ids.size());
  tbb::parallel_for(std::size_t(0), ids.size(), [&](std::size_t k) { hubs[k] = hub_pieces(lattice, ids[k]); });
  return hubs;
}

// At most this many chunks per slab in the slab window: each chunk costs another construction of the slab's hubs.
constexpr std::int64_t kMaxSlabChunks = 64;

// Bytes the pieces of one hub take, for the memory budget (a ball and one stump per incident pattern end).
std::uint64_t bytes_per_hub(const Lattice& lattice) {
  return sizeof(HubPieces) + sizeof(Piece) * (1 + 2 * static_cast<std::uint64_t>(lattice.pattern_count()));
}

}  // namespace

std::string to_string(const NodeId& id) {
  std::ostringstream os;
  os << "(" << id.i << "," << id.j << "," << id.k << "," << id.n << ")";
  return os.str();
}

std::string HubOverlapReport::describe(std::size_t max_listed) const {
  std::ostringstream os;
  if (!verified) os << "not verified (the lattice is too large to check); ";
  if (overlap_count == 0) {
    os << (verified ? "clean: no two hubs of different nodes overlap" : "no overlap found");
    return os.str();
  }
  os << overlap_count << " pair" << (overlap_count == 1 ? "" : "s") << " of hubs overlap: ";
  for (std::size_t k = 0; k < overlaps.size() && k < max_listed; ++k) {
    if (k) os << "; ";
    os << "hubs " << to_string(overlaps[k].a) << " and " << to_string(overlaps[k].b) << " (" << overlaps[k].detail << ")";
  }
  if (static_cast<std::size_t>(overlap_count) > std::min(overlaps.size(), max_listed)) os << "; ...";
  return os.str();
}

HubOverlapReport check_hub_overlaps(const Lattice& lattice, std::size_t max_reports, Progress& progress, HubOverlapCheckMethod method) {
  // The slab window needs the steady brick's last applied step: with another order of application it runs on
  // the brick lattice, whose hubs are this lattice's, and the report names them in this lattice's indices.
  const Lattice* brick = lattice.brick_lattice();
  if (brick && brick != &lattice) {
    HubOverlapReport report = check_hub_overlaps(*brick, max_reports, progress, method);
    for (HubOverlap& o : report.overlaps) {
      o.a = lattice.from_brick(o.a);
      o.b = lattice.from_brick(o.b);
    }
    return report;
  }
  HubOverlapReport report;
  Collector out{{}, &report, max_reports};
  const std::int64_t count = lattice.ball_count();
  if (!brick && method == HubOverlapCheckMethod::SlabWindow)
    fail_input("method", "the slab window needs a steady-brick layout (this one is " + lattice.layout().kind() + ")");
  const bool all_hubs = method == HubOverlapCheckMethod::AllHubs ||
                        (method == HubOverlapCheckMethod::Automatic && count <= kDirectHubOverlapCheckHubs);
  if (!brick && !all_hubs) {  // too many hubs to compare them all, and no steadiness to lean on
    report.hubs_checked = 0;
    finish(report, max_reports);
    return report;  // not verified
  }
  if (all_hubs) {
    require_memory(static_cast<std::uint64_t>(count) * bytes_per_hub(lattice), "clean check of " + std::to_string(count) + " hubs",
                   "check a smaller lattice of the same steps (the check of a steady lattice does not need every hub)");
    progress.set_total(count);
    std::vector<NodeId> ids(count);
    for (std::int64_t k = 0; k < count; ++k) ids[k] = lattice.ball_id(k);
    const std::vector<HubPieces> hubs = pieces_of(lattice, ids);
    check_hubs(hubs, hubs, true, 1, out, progress);
    report.hubs_checked = count;
    report.verified = true;
    finish(report, max_reports);
    return report;
  }
  // Slab window. Slab k (0 <= k < w) is W^(k - D) of slab D's hubs or a subset of them (border slabs miss
  // the beams that would leave the lattice), D the largest |dk|; so slab k's bounding sphere is W^(k-D) of
  // slab D's, and slabs delta apart can meet only if |W^delta(c) - c| < rho (1 + s^delta), whatever k.
  const Counts& c = lattice.counts();
  int D = 0;
  for (const BeamPattern& b : lattice.definition().beams) D = std::max(D, std::abs(b.dk));
  const std::int64_t w = c.w;
  const std::int64_t rep = std::min<std::int64_t>(D, w - 1);
  // The slabs' hubs are made a chunk at a time (ids in slab order), so that no more than two chunks are held:
  // slabs of 10^6 hubs (a lattice of 10^9) take 1.3 GB each, more than a process limited to 2 GiB may use.
  const std::vector<NodeId> rep_nodes = slab_nodes(lattice, rep);
  const std::int64_t per_slab = static_cast<std::int64_t>(rep_nodes.size());
  const std::uint64_t slab_bytes = static_cast<std::uint64_t>(per_slab) * bytes_per_hub(lattice);
  // Two chunks in half the budget: the other half for the broad phase's grid and what the process maps meanwhile.
  const std::int64_t chunks = std::clamp<std::int64_t>(
      static_cast<std::int64_t>(4 * slab_bytes / std::max<std::uint64_t>(memory_budget_bytes(), 1) + 1), 1,
      std::min<std::int64_t>(kMaxSlabChunks, std::max<std::int64_t>(per_slab, 1)));
  const std::int64_t chunk_size = (per_slab + chunks - 1) / std::max<std::int64_t>(chunks, 1);
  auto chunk_of = [&](const std::vector<NodeId>& ids, std::int64_t c) {
    const std::size_t begin = std::min(ids.size(), static_cast<std::size_t>(c * chunk_size));
    const std::size_t end = std::min(ids.size(), static_cast<std::size_t>((c + 1) * chunk_size));
    return pieces_of(lattice, std::vector<NodeId>(ids.begin() + begin, ids.begin() + end));
  };
  // The representative slab's box (hub bounding spheres); slab rep + delta lies in the box spanned by the
  // images of its corners under W^delta (a similarity maps a box into the box of its corners' images).
  Vec3 lo(std::numeric_limits<double>::max()), hi(-std::numeric_limits<double>::max());
  for (std::int64_t ch = 0; ch < chunks; ++ch)
    for (const HubPieces& h : chunk_of(rep_nodes, ch)) {
      lo = glm::min(lo, h.center - h.reach);
      hi = glm::max(hi, h.center + h.reach);
    }
  auto image_box_meets = [&](const Similarity& S) {
    Vec3 ilo(std::numeric_limits<double>::max()), ihi(-std::numeric_limits<double>::max());
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3 p(corner & 1 ? hi.x : lo.x, corner & 2 ? hi.y : lo.y, corner & 4 ? hi.z : lo.z);
      const Vec3 q = S.apply_point(p);
      ilo = glm::min(ilo, q);
      ihi = glm::max(ihi, q);
    }
    return ilo.x < hi.x && lo.x < ihi.x && ilo.y < hi.y && lo.y < ihi.y && ilo.z < hi.z && lo.z < ihi.z;
  };
  // The (k1, k2) slab pairs to compare: every pair touching a border slab, one interior representative.
  struct SlabPair {
    std::int64_t k1, k2, multiplicity;
  };
  std::vector<SlabPair> pairs;
  const Similarity& W = lattice.layout().steady_brick()->steps[2];  // the last applied step
  for (std::int64_t delta = 0; delta < w; ++delta) {
    if (delta > 0 && per_slab > 0 && !image_box_meets(W.power(static_cast<double>(delta)))) continue;
    for (std::int64_t k = 0; k + delta < w; ++k) {
      const bool border = k < D || k + delta >= w - D;
      if (border) {
        pairs.push_back({k, k + delta, 1});
      } else if (k == D) {
        pairs.push_back({k, k + delta, w - 2 * D - delta});
      }
    }
  }
  const std::int64_t work = 2 * per_slab * static_cast<std::int64_t>(pairs.size());
  report.hubs_checked = work;
  if (work > kMaxHubOverlapCheckHubs) {
    finish(report, max_reports);
    return report;  // not verified
  }
  require_memory(2 * static_cast<std::uint64_t>(chunk_size) * bytes_per_hub(lattice),
                 "clean check of 2 slabs of " + std::to_string(per_slab) + " hubs (in " + std::to_string(chunks) +
                     " chunks each)",
                 "check a smaller lattice of the same steps (fewer groups per slab)");
  progress.set_total(std::max<std::int64_t>(1, per_slab * static_cast<std::int64_t>(pairs.size()) * chunks));
  std::sort(pairs.begin(), pairs.end(), [](const SlabPair& x, const SlabPair& y) {
    return std::tie(x.k1, x.k2) < std::tie(y.k1, y.k2);
  });
  // Every chunk of slab k1 against every chunk of slab k2 (each unordered pair once within one slab): every pair
  // of hubs is compared, as with whole slabs; C chunks cost C times the hubs' construction, not more memory.
  std::int64_t loaded = -1;
  std::vector<NodeId> first_nodes;
  for (const SlabPair& pr : pairs) {
    if (pr.k1 != loaded) {
      first_nodes = slab_nodes(lattice, pr.k1);
      loaded = pr.k1;
    }
    const std::vector<NodeId> second_nodes = pr.k2 == pr.k1 ? std::vector<NodeId>() : slab_nodes(lattice, pr.k2);
    for (std::int64_t a = 0; a < chunks; ++a) {
      const std::vector<HubPieces> first = chunk_of(first_nodes, a);
      if (pr.k2 == pr.k1) {
        check_hubs(first, first, true, pr.multiplicity, out, progress);
        for (std::int64_t b = a + 1; b < chunks; ++b)
          check_hubs(first, chunk_of(first_nodes, b), false, pr.multiplicity, out, progress);
      } else {
        for (std::int64_t b = 0; b < chunks; ++b)
          check_hubs(first, chunk_of(second_nodes, b), false, pr.multiplicity, out, progress);
      }
    }
  }
  report.verified = true;
  finish(report, max_reports);
  return report;
}

HubOverlapReport check_hub_overlaps_brute_force(const Lattice& lattice, std::size_t max_reports) {
  HubOverlapReport report;
  std::vector<HubPieces> hubs;
  for (std::int64_t k = 0; k < lattice.ball_count(); ++k) hubs.push_back(hub_pieces(lattice, lattice.ball_id(k)));
  for (std::size_t a = 0; a < hubs.size(); ++a)
    for (std::size_t b = a + 1; b < hubs.size(); ++b)
      for (const Piece& p : hubs[a].pieces) {
        bool found = false;
        for (const Piece& q : hubs[b].pieces)
          if (pieces_overlap(p, q)) {
            ++report.overlap_count;
            report.overlaps.push_back({hubs[a].id, hubs[b].id, piece_name(p) + " / " + piece_name(q)});
            found = true;
            break;
          }
        if (found) break;
      }
  report.hubs_checked = static_cast<std::int64_t>(hubs.size());
  report.verified = true;
  finish(report, max_reports);
  return report;
}

}  // namespace steady
