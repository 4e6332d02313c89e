#pragma once
// A layout: where each group (i, j, k) of a box of counts goes. It is the one definition of a lattice's
// placement: every consumer (queries, properties, B-rep, trimming, filters, files) asks the layout, and no
// other code composes a group's similarity.
//
// A layout answers three questions:
//   group_transform(i, j, k)   the similarity placing group (i, j, k), for every group of the box;
//   row_transforms(j, k, out)  the same for a whole row (0..u-1, j, k) at once (bulk listings), with values
//                              bit-identical to group_transform's;
//   steady_brick()             the steady-brick view S(i, j, k) = G o W^k o V^j o U^i (up to an order of the
//                              axes) that the fast paths need (RangeFinder in O(1), block bounds, closed-form
//                              sums), or nullptr: those consumers then fall back to a correct, slower path
//                              (every group evaluated).
// Layouts are immutable and shared (LayoutPtr); a lattice holds one. The kinds that exist, and how the file
// format reads and writes each, are listed once in layout_registry.cpp.
#include <array>
#include <cstdint>
#include <memory>
#include <string>

#include "steady/core/similarity.hpp"

namespace steady {

struct Counts {
  std::int64_t u = 1, v = 1, w = 1;
  std::int64_t groups() const { return u * v * w; }
  std::int64_t along(int axis) const { return axis == 0 ? u : axis == 1 ? v : w; }
  bool operator==(const Counts& o) const { return u == o.u && v == o.v && w == o.w; }
};

// A box of group indices, half-open: [i0, i1) x [j0, j1) x [k0, k1).
struct IndexBlock {
  std::int64_t i0 = 0, i1 = 0, j0 = 0, j1 = 0, k0 = 0, k1 = 0;
  bool empty() const { return i1 <= i0 || j1 <= j0 || k1 <= k0; }
  std::int64_t groups() const { return empty() ? 0 : (i1 - i0) * (j1 - j0) * (k1 - k0); }
  IndexBlock shifted(std::int64_t di, std::int64_t dj, std::int64_t dk) const {
    return {i0 + di, i1 + di, j0 + dj, j1 + dj, k0 + dk, k1 + dk};
  }
};

IndexBlock intersect(const IndexBlock& a, const IndexBlock& b);

// The order in which the three steps apply, first to last, as lattice axes (0 = i along U, 1 = j along V,
// 2 = k along W). {0, 1, 2}: U first, W last, the papers' G o W^k o V^j o U^i.
using AxisOrder = std::array<int, 3>;
constexpr AxisOrder kUVW{0, 1, 2};
// "UVW", "VWU", ...: every permutation of the three letters; InvalidInput naming `field` otherwise.
AxisOrder axis_order_from_string(const std::string& letters, const std::string& field);
std::string to_string(const AxisOrder& order);

// The steady-brick view: in brick axes (a0 the first applied), group (a0, a1, a2) is placed by
//     S = G o X2^a2 o X1^a1 o X0^a0.
// `axes[b]` is the lattice axis of brick axis b: the brick's indices are the lattice's permuted so that the
// first applied step comes first. A lattice whose layout applies its steps in the U V W order is its own
// brick (axes = kUVW); Lattice::brick_lattice() gives the permuted lattice otherwise.
class Layout;
using LayoutPtr = std::shared_ptr<const Layout>;

struct SteadyBrick {
  Similarity placement;               // G
  std::array<Similarity, 3> steps;    // X0, X1, X2 in brick axes (the resolved steps, not their controls)
  AxisOrder axes = kUVW;
  // When reordered: the same groups as a steady brick in brick axes (the layout of the brick lattice).
  LayoutPtr layout_in_brick_axes;

  bool reordered() const { return axes != kUVW; }
  // The step between neighbouring groups along lattice axis a (0 = i along U, 1 = j, 2 = k).
  const Similarity& step_along(int lattice_axis) const {
    for (std::size_t b = 0; b < 3; ++b)
      if (axes[b] == lattice_axis) return steps[b];
    return steps[static_cast<std::size_t>(lattice_axis)];  // unreachable for a permutation
  }
  // The placement formula, written once. Every evaluator of a steady brick (the layout itself, the query
  // paths' power tables, the sums' caches) composes the powers X^n = step.power(n).transform() through
  // these two functions, so that all of them give bit-identical groups.
  static SimilarityTransform row_prefix(const SimilarityTransform& g, const SimilarityTransform& x2_a2,
                                        const SimilarityTransform& x1_a1) {
    return (g * x2_a2) * x1_a1;
  }
  static SimilarityTransform place(const SimilarityTransform& prefix, const SimilarityTransform& x0_a0) {
    return prefix * x0_a0;
  }
};

class Layout {
 public:
  virtual ~Layout() = default;

  // The registry name ("steady-brick", "table", ...): the file format's layout kind.
  virtual std::string kind() const = 0;
  const Counts& counts() const { return counts_; }
  bool contains(std::int64_t i, std::int64_t j, std::int64_t k) const {
    return i >= 0 && i < counts_.u && j >= 0 && j < counts_.v && k >= 0 && k < counts_.w;
  }

  // The similarity placing group (i, j, k); InvalidInput outside the box of counts.
  virtual Similarity group_similarity(std::int64_t i, std::int64_t j, std::int64_t k) const = 0;
  // Its transform, the values every element is evaluated with.
  virtual SimilarityTransform group_transform(std::int64_t i, std::int64_t j, std::int64_t k) const = 0;
  // The transforms of groups (0..u-1, j, k), bit-identical to group_transform; out holds counts().u values.
  virtual void row_transforms(std::int64_t j, std::int64_t k, SimilarityTransform* out) const;

  // The steady-brick view, or nullptr when the layout is not a steady brick.
  virtual const SteadyBrick* steady_brick() const { return nullptr; }

  // The same layout for other counts (FreeCAD's cell counts change; steps given by their cumulative
  // control are resolved again). InvalidInput when the layout cannot have those counts (a table).
  virtual LayoutPtr with_counts(const Counts& counts) const = 0;
  // The same layout moved by G as a whole: group (i, j, k) placed by G o S(i, j, k).
  virtual LayoutPtr placed(const Similarity& G) const = 0;

  // The largest |ln s| of a group's scale, and the mean of ln s over the groups: for the refusal of layouts
  // whose scales leave floating point, and for typical element sizes.
  virtual double max_abs_log_scale() const = 0;
  virtual double mean_log_scale() const = 0;

 protected:
  explicit Layout(const Counts& counts);

 private:
  Counts counts_;
};

}  // namespace steady
