#include "steady/lattice/layout.hpp"

#include <algorithm>

#include "lattice/layout_limits.hpp"
#include "steady/core/errors.hpp"

namespace steady {

IndexBlock intersect(const IndexBlock& a, const IndexBlock& b) {
  return {std::max(a.i0, b.i0), std::min(a.i1, b.i1), std::max(a.j0, b.j0),
          std::min(a.j1, b.j1), std::max(a.k0, b.k0), std::min(a.k1, b.k1)};
}

AxisOrder axis_order_from_string(const std::string& letters, const std::string& field) {
  AxisOrder order{};
  bool seen[3] = {false, false, false};
  const std::string expected = " (expected the letters U, V and W once each, first applied first, as in \"VWU\")";
  if (letters.size() != 3) fail_input(field, "\"" + letters + "\" is not an order of the steps" + expected);
  for (std::size_t b = 0; b < 3; ++b) {
    const char c = letters[b];
    const int axis = c == 'U' || c == 'u' ? 0 : c == 'V' || c == 'v' ? 1 : c == 'W' || c == 'w' ? 2 : -1;
    if (axis < 0 || seen[axis]) fail_input(field, "\"" + letters + "\" is not an order of the steps" + expected);
    seen[axis] = true;
    order[b] = axis;
  }
  return order;
}

std::string to_string(const AxisOrder& order) {
  std::string s;
  for (int axis : order) s += "UVW"[axis];
  return s;
}

Layout::Layout(const Counts& counts) : counts_(counts) {
  const char* names[3] = {"counts.u", "counts.v", "counts.w"};
  for (int a = 0; a < 3; ++a)
    if (counts.along(a) < 1) fail_input(names[a], "must be >= 1 (got " + std::to_string(counts.along(a)) + ")");
}

void Layout::row_transforms(std::int64_t j, std::int64_t k, SimilarityTransform* out) const {
  for (std::int64_t i = 0; i < counts_.u; ++i) out[i] = group_transform(i, j, k);
}

void require_representable_scales(double max_abs_log_scale, const std::string& field) {
  if (!(max_abs_log_scale <= detail::kMaxGroupLogScale))
    fail_input(field, "the scales compound beyond floating point over the counts (a group's scale reaches exp(" +
                          std::to_string(max_abs_log_scale) + "))");
}

void fail_group_outside(const Counts&, std::int64_t i, std::int64_t j, std::int64_t k) {
  fail_input("group", "(" + std::to_string(i) + ", " + std::to_string(j) + ", " + std::to_string(k) +
                          ") is outside the lattice");
}

}  // namespace steady
