#pragma once
// The steady brick: three steps U, V, W (along i, j, k) and a placement G,
//     S(i, j, k) = G o W^k o V^j o U^i        (U applied first, G last),
// the papers' steady lattice. (Another order of application is any_order_layout.hpp.)
//
// A direction's step is given either as the step between neighbouring groups (incremental) or as the
// similarity from the first group to the last (cumulative, the papers' interpolating control: its
// 1/(count-1) power is the step, so the end groups stay where the designer put them when counts change).
#include <vector>

#include "steady/lattice/layout.hpp"

namespace steady {

enum class StepControl { Incremental, Cumulative };

struct DirectionControl {
  Similarity similarity;
  StepControl control = StepControl::Incremental;
};

class SteadyBrickLayout final : public Layout {
 public:
  // InvalidInput naming the field for counts < 1 or scales that compound beyond floating point over the
  // counts.
  static std::shared_ptr<const SteadyBrickLayout> make(const Counts& counts, const DirectionControl& u,
                                                       const DirectionControl& v, const DirectionControl& w,
                                                       const Similarity& placement = Similarity::identity());
  // Incremental steps.
  static std::shared_ptr<const SteadyBrickLayout> steps(const Counts& counts, const Similarity& U,
                                                        const Similarity& V, const Similarity& W,
                                                        const Similarity& placement = Similarity::identity());

  static constexpr const char* kKind = "steady-brick";
  std::string kind() const override { return kKind; }

  // As defined (axis 0, 1, 2 = U, V, W), and the resolved steps between neighbouring groups.
  const DirectionControl& control(int axis) const { return controls_[static_cast<std::size_t>(axis)]; }
  const Similarity& step(int axis) const { return steps_[static_cast<std::size_t>(axis)]; }
  const Similarity& placement() const { return brick_.placement; }

  Similarity group_similarity(std::int64_t i, std::int64_t j, std::int64_t k) const override;
  SimilarityTransform group_transform(std::int64_t i, std::int64_t j, std::int64_t k) const override;
  void row_transforms(std::int64_t j, std::int64_t k, SimilarityTransform* out) const override;
  const SteadyBrick* steady_brick() const override { return &brick_; }
  LayoutPtr with_counts(const Counts& counts) const override;
  LayoutPtr placed(const Similarity& G) const override;
  double max_abs_log_scale() const override;
  double mean_log_scale() const override;

  SteadyBrickLayout(const Counts& counts, const std::array<DirectionControl, 3>& controls,
                    const Similarity& placement);  // use make()
  ~SteadyBrickLayout() override;

 private:
  SimilarityTransform power(int axis, std::int64_t n) const;

  std::array<DirectionControl, 3> controls_;
  std::array<Similarity, 3> steps_;
  SteadyBrick brick_;
  // Integer powers of each step over its count, step.power(n).transform() exactly (when not too long).
  std::array<std::vector<SimilarityTransform>, 3> powers_;
};

}  // namespace steady
