#include "steady/lattice/any_order_layout.hpp"

#include "lattice/layout_limits.hpp"
#include "lattice/layout_registry.hpp"
#include "steady/core/errors.hpp"

namespace steady {

Counts permuted(const Counts& counts, const AxisOrder& axes) {
  return {counts.along(axes[0]), counts.along(axes[1]), counts.along(axes[2])};
}

AnyOrderLayout::AnyOrderLayout(const Counts& counts, std::shared_ptr<const SteadyBrickLayout> brick,
                               const AxisOrder& order)
    : Layout(counts), brick_(std::move(brick)) {
  view_ = *brick_->steady_brick();
  view_.axes = order;
  view_.layout_in_brick_axes = brick_;
}

LayoutPtr AnyOrderLayout::make(const Counts& counts, const DirectionControl& u, const DirectionControl& v,
                               const DirectionControl& w, const Similarity& placement, const AxisOrder& order) {
  bool seen[3] = {false, false, false};
  for (int axis : order) {
    if (axis < 0 || axis > 2 || seen[axis]) fail_input("order", "must name each of U, V and W once");
    seen[axis] = true;
  }
  const DirectionControl by_axis[3] = {u, v, w};
  // The brick's axes are the lattice's in the order of application; its counts follow.
  auto brick = SteadyBrickLayout::make(permuted(counts, order), by_axis[order[0]], by_axis[order[1]],
                                       by_axis[order[2]], placement);
  return std::make_shared<const AnyOrderLayout>(counts, std::move(brick), order);
}

int AnyOrderLayout::brick_axis(int lattice_axis) const {
  for (int b = 0; b < 3; ++b)
    if (view_.axes[b] == lattice_axis) return b;
  return -1;  // unreachable: the order is a permutation
}

const DirectionControl& AnyOrderLayout::control(int axis) const { return brick_->control(brick_axis(axis)); }
const Similarity& AnyOrderLayout::step(int axis) const { return brick_->step(brick_axis(axis)); }

Similarity AnyOrderLayout::group_similarity(std::int64_t i, std::int64_t j, std::int64_t k) const {
  if (!contains(i, j, k)) fail_group_outside(counts(), i, j, k);
  const std::int64_t index[3] = {i, j, k};
  return brick_->group_similarity(index[view_.axes[0]], index[view_.axes[1]], index[view_.axes[2]]);
}

SimilarityTransform AnyOrderLayout::group_transform(std::int64_t i, std::int64_t j, std::int64_t k) const {
  if (!contains(i, j, k)) fail_group_outside(counts(), i, j, k);
  const std::int64_t index[3] = {i, j, k};
  return brick_->group_transform(index[view_.axes[0]], index[view_.axes[1]], index[view_.axes[2]]);
}

LayoutPtr AnyOrderLayout::with_counts(const Counts& counts) const {
  return make(counts, control(0), control(1), control(2), placement(), view_.axes);
}

LayoutPtr AnyOrderLayout::placed(const Similarity& G) const {
  return make(counts(), control(0), control(1), control(2), G * placement(), view_.axes);
}

}  // namespace steady

// ---- file format: the steady brick's fields, plus "order" ("VWU": first applied first) ---------------

namespace steady::detail {
namespace {

json write_any_order(const Layout& layout) {
  const auto& any = static_cast<const AnyOrderLayout&>(layout);
  json j = write_steady_fields({any.control(0), any.control(1), any.control(2), any.placement()});
  j["order"] = to_string(any.order());
  return j;
}

LayoutPtr read_any_order(const json& fields, const Counts& counts, const std::string& path) {
  refuse_unknown_keys(fields, path, {"kind", "U", "V", "W", "placement", "order"});
  const std::string at = path.empty() ? "order" : path + ".order";
  const json& order = member(fields, "order", path);
  if (!order.is_string()) fail_input(at, "expected a string such as \"VWU\"");
  const SteadyFields f = read_steady_fields(fields, path);
  return AnyOrderLayout::make(counts, f.u, f.v, f.w, f.placement, axis_order_from_string(order.get<std::string>(), at));
}

}  // namespace

LayoutCodec any_order_layout_codec() { return {AnyOrderLayout::kKind, &write_any_order, &read_any_order}; }

}  // namespace steady::detail
