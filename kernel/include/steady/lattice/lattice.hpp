#pragma once
// A lattice: balls and conical beams laid out by similarities.
//
// Group (i, j, k), 0 <= i < u, 0 <= j < v, 0 <= k < w, is the template placed by the similarity S(i, j, k)
// its layout gives (layout.hpp): for the papers' steady brick, S(i, j, k) = G o W^k o V^j o U^i.
// Ball n of group (i,j,k) is S(i,j,k) applied to template node n (its radius scales with S).
// Beam pattern (n1, di, dj, dk, n2) joins ball n1 of group (i,j,k) to ball n2 of group (i+di, j+dj, k+dk),
// for every (i,j,k) where both groups exist and neither ball is omitted. Without its own radii a beam is
// the convex hull of its two balls (the papers' model); with radii (r1, r2), given in template units and
// scaled with their groups like the balls, it is the frustum between those two circles' spheres.
//
// Nothing is stored per element: any ball, beam or group is evaluated in O(1) from the definition
// (O(log m) with m omitted nodes).
//
// Stable order (the indices every query returns):
//   balls: by group, k slowest, then j, then i, then node n fastest; omitted nodes are skipped.
//   beams: by pattern p slowest, then by start group (k, j, i) over the groups where the beam exists;
//          beams touching omitted nodes are skipped.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "steady/core/ball.hpp"
#include "steady/core/similarity.hpp"
#include "steady/lattice/layout.hpp"
#include "steady/lattice/steady_brick_layout.hpp"

namespace steady {

struct TemplateNode {
  Vec3 center{0.0};
  double radius = 1.0;
};

struct BeamPattern {
  int from = 0;            // n1: node of the start group
  int di = 0, dj = 0, dk = 0;  // offset of the end group
  int to = 0;              // n2: node of the end group
  // Beam end radii in template units; absent: the beam is the convex hull of its two balls.
  std::optional<double> from_radius;
  std::optional<double> to_radius;
  bool has_radii() const { return from_radius.has_value(); }
};

struct NodeId {
  std::int64_t i = 0, j = 0, k = 0;
  int n = 0;
  bool operator==(const NodeId& o) const { return i == o.i && j == o.j && k == o.k && n == o.n; }
};

struct BeamId {
  std::int64_t i = 0, j = 0, k = 0;  // start group
  int pattern = 0;
  bool operator==(const BeamId& o) const { return i == o.i && j == o.j && k == o.k && pattern == o.pattern; }
};

// A beam's geometry: its two end balls (centers at the nodes, radii the beam's end radii). The solid
// beam is the convex hull of the two balls; in the explicit-radii model it is clipped by the nodes.
struct BeamGeometry {
  Ball start, end;
};

struct LatticeDefinition {
  std::vector<TemplateNode> nodes;
  std::vector<BeamPattern> beams;
  LayoutPtr layout;              // where each group goes; its counts are the lattice's
  std::vector<NodeId> omitted;   // designer's omissions
};

// The start groups (i, j, k) of a pattern's beams: those whose end group (i + di, j + dj, k + dk) exists too.
IndexBlock pattern_start_groups(const Counts& counts, const BeamPattern& pattern);

class Lattice {
 public:
  // Validates the definition; throws InvalidInput naming the offending field.
  explicit Lattice(LatticeDefinition definition);

  // Builds a lattice with incremental steps U, V, W and placement G.
  static Lattice incremental(std::vector<TemplateNode> nodes, std::vector<BeamPattern> beams, Counts counts,
                             const Similarity& U, const Similarity& V, const Similarity& W,
                             const Similarity& G = Similarity::identity());
  // Builds a lattice from the cumulative similarities (first group to last) of each direction.
  static Lattice interpolating(std::vector<TemplateNode> nodes, std::vector<BeamPattern> beams, Counts counts,
                               const Similarity& U_total, const Similarity& V_total, const Similarity& W_total,
                               const Similarity& G = Similarity::identity());
  // Builds a lattice from four frames: `base` places group (0,0,0) (the template is given in its
  // coordinates), and end_u, end_v, end_w place groups (u-1,0,0), (0,v-1,0), (0,0,w-1).
  static Lattice from_frames(std::vector<TemplateNode> nodes, std::vector<BeamPattern> beams, Counts counts,
                             const Frame& base, const Frame& end_u, const Frame& end_v, const Frame& end_w);

  // Builds the steady brick lattice with its steps applied in `order` (first applied first): with order
  // V W U, S(i, j, k) = G o U^i o W^k o V^j (any_order_layout.hpp); indices still count along U, V, W.
  static Lattice ordered(std::vector<TemplateNode> nodes, std::vector<BeamPattern> beams, Counts counts,
                         const DirectionControl& U, const DirectionControl& V, const DirectionControl& W,
                         const Similarity& G, const AxisOrder& order, std::vector<NodeId> omitted = {});

  const LatticeDefinition& definition() const { return def_; }
  const Layout& layout() const { return *def_.layout; }
  const Counts& counts() const { return def_.layout->counts(); }
  int node_count() const { return static_cast<int>(def_.nodes.size()); }    // per group
  int pattern_count() const { return static_cast<int>(def_.beams.size()); }
  // The same lattice with another layout (the template and omissions kept; InvalidInput when an omitted node
  // falls outside the new counts).
  Lattice with_layout(LayoutPtr layout) const;
  // The same lattice moved by G as a whole (its layout's placed(G)).
  Lattice placed(const Similarity& G) const { return with_layout(def_.layout->placed(G)); }

  // --- the steady-brick view of the fast paths -------------------------------------------------------
  // The lattice whose layout is the steady-brick view of this one in brick axes (the steps applied in the
  // U V W order): *this when the layout is a steady brick in that order, the same groups re-indexed when
  // its steps apply in another order, nullptr when the layout is not a steady brick. Fast paths run on it
  // and translate the indices they report with from_brick().
  const Lattice* brick_lattice() const;
  NodeId to_brick(const NodeId& id) const;
  NodeId from_brick(const NodeId& id) const;
  BeamId to_brick(const BeamId& id) const;
  BeamId from_brick(const BeamId& id) const;

  // --- evaluation, O(1) -------------------------------------------------------------------------
  bool group_exists(std::int64_t i, std::int64_t j, std::int64_t k) const;
  SimilarityTransform group_transform(std::int64_t i, std::int64_t j, std::int64_t k) const;
  Similarity group_similarity(std::int64_t i, std::int64_t j, std::int64_t k) const;
  bool node_exists(const NodeId& id) const;
  Ball ball(const NodeId& id) const;  // throws if the group is out of range (omission is not checked)
  bool beam_exists(const BeamId& id) const;
  BeamGeometry beam(const BeamId& id) const;  // throws if the beam does not exist
  NodeId beam_start(const BeamId& id) const;
  NodeId beam_end(const BeamId& id) const;

  // --- stable indexing ----------------------------------------------------------------------------
  std::int64_t ball_count() const { return ball_count_; }
  std::int64_t beam_count() const { return beam_count_; }
  std::int64_t ball_index(const NodeId& id) const;  // -1 when the node does not exist
  NodeId ball_id(std::int64_t index) const;         // throws on an out-of-range index
  std::int64_t beam_index(const BeamId& id) const;  // -1 when the beam does not exist
  BeamId beam_id(std::int64_t index) const;

  // --- bulk, in the stable order, parallel --------------------------------------------------------
  // centers: 3 * ball_count() doubles; radii: ball_count() doubles.
  void balls(double* centers, double* radii) const;
  // start/end: ball indices; radii: the beam end radii. Each array beam_count() long.
  void beams(std::int64_t* start, std::int64_t* end, double* start_radius, double* end_radius) const;
  // Sequential visit in the stable order.
  void for_each_ball(const std::function<void(std::int64_t index, const NodeId&, const Ball&)>& visit) const;
  void for_each_beam(const std::function<void(std::int64_t index, const BeamId&, const BeamGeometry&)>& visit) const;

  // The bytes a full listing of balls and beams takes; used to refuse listings beyond memory.
  std::uint64_t listing_bytes() const;

 private:
  struct PatternRange {  // the box of start groups where pattern p's beams exist
    std::int64_t i0, i1, j0, j1, k0, k1;
    std::int64_t size() const { return (i1 - i0) * (j1 - j0) * (k1 - k0); }
    std::int64_t local(std::int64_t i, std::int64_t j, std::int64_t k) const {
      return ((k - k0) * (j1 - j0) + (j - j0)) * (i1 - i0) + (i - i0);
    }
  };
  void validate() const;
  void build_indexing();
  std::int64_t node_linear(const NodeId& id) const;
  NodeId node_from_linear(std::int64_t linear) const;

  LatticeDefinition def_;
  std::shared_ptr<const Lattice> brick_;                   // when the layout's steps apply in another order
  std::vector<std::int64_t> omitted_linear_;               // sorted, unique
  std::vector<PatternRange> pattern_ranges_;
  std::vector<std::vector<std::int64_t>> killed_beams_;    // per pattern, sorted local indices
  std::vector<std::int64_t> pattern_offsets_;              // beam index of each pattern's first beam
  std::int64_t ball_count_ = 0;
  std::int64_t beam_count_ = 0;
};

}  // namespace steady
