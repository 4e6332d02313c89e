#include "steady/lattice/steady_brick_layout.hpp"

#include <cmath>

#include "lattice/layout_limits.hpp"
#include "lattice/layout_registry.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/tolerance.hpp"

namespace steady {
namespace {

Similarity step_from(const DirectionControl& c, std::int64_t count) {
  if (c.control == StepControl::Incremental) return c.similarity;
  if (count <= 1) return Similarity::identity();  // no increment in a single-group row
  return c.similarity.power(1.0 / static_cast<double>(count - 1));
}

}  // namespace

SteadyBrickLayout::SteadyBrickLayout(const Counts& counts, const std::array<DirectionControl, 3>& controls,
                                     const Similarity& placement)
    : Layout(counts), controls_(controls) {
  for (int a = 0; a < 3; ++a) steps_[a] = step_from(controls_[a], counts.along(a));
  brick_.placement = placement;
  brick_.steps = steps_;
  brick_.axes = kUVW;
  require_representable_scales(max_abs_log_scale(), "U, V, W");
  // A step that maps nothing anywhere puts every group of its direction in the same place.
  const char* names[3] = {"U", "V", "W"};
  for (int a = 0; a < 3; ++a)
    if (counts.along(a) > 1 && steps_[a].map_distance(Similarity::identity()) <= kLengthTolerance)
      fail_input(names[a], "the step is the identity: the " + std::to_string(counts.along(a)) +
                               " groups along " + names[a] + " would all lie in the same place (give a step, or count 1)");
  for (int a = 0; a < 3; ++a) {
    const std::int64_t n = counts.along(a);
    if (n > detail::kMaxCachedLayoutPowers) continue;
    powers_[a].resize(static_cast<std::size_t>(n));
    for (std::int64_t t = 0; t < n; ++t) powers_[a][t] = steps_[a].power(static_cast<double>(t)).transform();
  }
}

SteadyBrickLayout::~SteadyBrickLayout() = default;

std::shared_ptr<const SteadyBrickLayout> SteadyBrickLayout::make(const Counts& counts, const DirectionControl& u,
                                                                 const DirectionControl& v, const DirectionControl& w,
                                                                 const Similarity& placement) {
  return std::make_shared<const SteadyBrickLayout>(counts, std::array<DirectionControl, 3>{u, v, w}, placement);
}

std::shared_ptr<const SteadyBrickLayout> SteadyBrickLayout::steps(const Counts& counts, const Similarity& U,
                                                                  const Similarity& V, const Similarity& W,
                                                                  const Similarity& placement) {
  return make(counts, {U, StepControl::Incremental}, {V, StepControl::Incremental}, {W, StepControl::Incremental},
              placement);
}

SimilarityTransform SteadyBrickLayout::power(int axis, std::int64_t n) const {
  const auto& table = powers_[static_cast<std::size_t>(axis)];
  if (n >= 0 && n < static_cast<std::int64_t>(table.size())) return table[static_cast<std::size_t>(n)];
  return steps_[static_cast<std::size_t>(axis)].power(static_cast<double>(n)).transform();
}

Similarity SteadyBrickLayout::group_similarity(std::int64_t i, std::int64_t j, std::int64_t k) const {
  if (!contains(i, j, k)) fail_group_outside(counts(), i, j, k);
  return brick_.placement * steps_[2].power(static_cast<double>(k)) * steps_[1].power(static_cast<double>(j)) *
         steps_[0].power(static_cast<double>(i));
}

SimilarityTransform SteadyBrickLayout::group_transform(std::int64_t i, std::int64_t j, std::int64_t k) const {
  if (!contains(i, j, k)) fail_group_outside(counts(), i, j, k);
  return SteadyBrick::place(SteadyBrick::row_prefix(brick_.placement.transform(), power(2, k), power(1, j)),
                            power(0, i));
}

void SteadyBrickLayout::row_transforms(std::int64_t j, std::int64_t k, SimilarityTransform* out) const {
  if (!contains(0, j, k)) fail_group_outside(counts(), 0, j, k);
  const SimilarityTransform prefix = SteadyBrick::row_prefix(brick_.placement.transform(), power(2, k), power(1, j));
  const auto& u_powers = powers_[0];
  if (static_cast<std::int64_t>(u_powers.size()) == counts().u) {  // the common case, without copying powers
    for (std::size_t i = 0; i < u_powers.size(); ++i) out[i] = SteadyBrick::place(prefix, u_powers[i]);
    return;
  }
  for (std::int64_t i = 0; i < counts().u; ++i) out[i] = SteadyBrick::place(prefix, power(0, i));
}

LayoutPtr SteadyBrickLayout::with_counts(const Counts& counts) const {
  return make(counts, controls_[0], controls_[1], controls_[2], brick_.placement);
}

LayoutPtr SteadyBrickLayout::placed(const Similarity& G) const {
  return make(counts(), controls_[0], controls_[1], controls_[2], G * brick_.placement);
}

double SteadyBrickLayout::max_abs_log_scale() const {
  double s = std::abs(brick_.placement.log_scale());
  for (int a = 0; a < 3; ++a) s += std::abs(steps_[a].log_scale()) * static_cast<double>(counts().along(a) - 1);
  return s;
}

double SteadyBrickLayout::mean_log_scale() const {
  double s = brick_.placement.log_scale();
  for (int a = 0; a < 3; ++a) s += 0.5 * static_cast<double>(counts().along(a) - 1) * steps_[a].log_scale();
  return s;
}

}  // namespace steady

// ---- file format: {"kind": "steady-brick", "U", "V", "W" (with their control), "placement"} ------------

namespace steady::detail {
namespace {

json write_steady_brick(const Layout& layout) {
  const auto& brick = static_cast<const SteadyBrickLayout&>(layout);
  return write_steady_fields({brick.control(0), brick.control(1), brick.control(2), brick.placement()});
}

LayoutPtr read_steady_brick(const json& fields, const Counts& counts, const std::string& path) {
  refuse_unknown_keys(fields, path, {"kind", "U", "V", "W", "placement"});
  const SteadyFields f = read_steady_fields(fields, path);
  return SteadyBrickLayout::make(counts, f.u, f.v, f.w, f.placement);
}

}  // namespace

LayoutCodec steady_brick_layout_codec() { return {SteadyBrickLayout::kKind, &write_steady_brick, &read_steady_brick}; }

}  // namespace steady::detail
