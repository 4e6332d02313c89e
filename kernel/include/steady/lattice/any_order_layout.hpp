#pragma once
// The steady brick with its steps applied in any order: with order V W U (V first, U last),
//     S(i, j, k) = G o U^i o W^k o V^j.
// Indices (i, j, k) still count along U, V, W; only the order in which the steps compose changes. The step
// applied last bends, twists or tapers the whole lattice about one centre line, the earlier ones act row by
// row: which is why a designer picks the order.
//
// It is a steady brick in permuted axes: the fast paths run on Lattice::brick_lattice() (the same groups,
// indexed in the order of application) and translate indices back.
#include <memory>

#include "steady/lattice/steady_brick_layout.hpp"

namespace steady {

class AnyOrderLayout final : public Layout {
 public:
  // order: the lattice axes (0 = U, 1 = V, 2 = W) in the order their steps apply, first to last.
  static LayoutPtr make(const Counts& counts, const DirectionControl& u, const DirectionControl& v,
                        const DirectionControl& w, const Similarity& placement, const AxisOrder& order);

  static constexpr const char* kKind = "any-order-brick";
  std::string kind() const override { return kKind; }

  // As defined, by lattice axis (0, 1, 2 = U, V, W).
  const DirectionControl& control(int axis) const;
  const Similarity& step(int axis) const;
  const Similarity& placement() const { return brick_->placement(); }
  const AxisOrder& order() const { return view_.axes; }
  // The same layout as a steady brick in the order of application (brick axis b is lattice axis order[b]).
  const SteadyBrickLayout& brick() const { return *brick_; }

  Similarity group_similarity(std::int64_t i, std::int64_t j, std::int64_t k) const override;
  SimilarityTransform group_transform(std::int64_t i, std::int64_t j, std::int64_t k) const override;
  const SteadyBrick* steady_brick() const override { return &view_; }
  LayoutPtr with_counts(const Counts& counts) const override;
  LayoutPtr placed(const Similarity& G) const override;
  double max_abs_log_scale() const override { return brick_->max_abs_log_scale(); }
  double mean_log_scale() const override { return brick_->mean_log_scale(); }

  AnyOrderLayout(const Counts& counts, std::shared_ptr<const SteadyBrickLayout> brick,
                 const AxisOrder& order);  // use make()

 private:
  int brick_axis(int lattice_axis) const;

  std::shared_ptr<const SteadyBrickLayout> brick_;
  SteadyBrick view_;
};

// The counts, or the three indices, of a box in another axis order: out[b] = in[axes[b]].
Counts permuted(const Counts& counts, const AxisOrder& axes);

}  // namespace steady
