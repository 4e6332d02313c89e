#pragma once
// A steady brick lattice: balls and conical beams laid out by similarities.
//
// Group (i, j, k), 0 <= i < u, 0 <= j < v, 0 <= k < w, is the template placed by
//     S(i, j, k) = G o W^k o V^j o U^i        (U applied first, G last)
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

struct Counts {
  std::int64_t u = 1, v = 1, w = 1;
};

// How a direction's similarity is given: the step between neighbouring groups, or the cumulative
// similarity from the first group to the last, whose 1/(count-1) power is the step (the papers'
// interpolating control: the end groups stay where the designer put them when counts change).
enum class StepControl { Incremental, Cumulative };

struct DirectionControl {
  Similarity similarity;
  StepControl control = StepControl::Incremental;
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
  Counts counts;
  DirectionControl u, v, w;
  Similarity placement;          // G
  std::vector<NodeId> omitted;   // designer's omissions
};

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

  const LatticeDefinition& definition() const { return def_; }
  const Counts& counts() const { return def_.counts; }
  int node_count() const { return static_cast<int>(def_.nodes.size()); }    // per group
  int pattern_count() const { return static_cast<int>(def_.beams.size()); }
  const Similarity& step_u() const { return step_u_; }
  const Similarity& step_v() const { return step_v_; }
  const Similarity& step_w() const { return step_w_; }
  const Similarity& placement() const { return def_.placement; }

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
  Similarity step_u_, step_v_, step_w_;
  std::vector<std::int64_t> omitted_linear_;               // sorted, unique
  std::vector<PatternRange> pattern_ranges_;
  std::vector<std::vector<std::int64_t>> killed_beams_;    // per pattern, sorted local indices
  std::vector<std::int64_t> pattern_offsets_;              // beam index of each pattern's first beam
  std::int64_t ball_count_ = 0;
  std::int64_t beam_count_ = 0;
};

}  // namespace steady
