#include "steady/lattice/table_layout.hpp"

#include <algorithm>
#include <cmath>

#include "lattice/layout_limits.hpp"
#include "lattice/layout_registry.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"

namespace steady {

TableLayout::TableLayout(const Counts& counts, std::vector<Similarity> similarities)
    : Layout(counts), similarities_(std::move(similarities)) {
  const auto expected = static_cast<std::uint64_t>(counts.u) * static_cast<std::uint64_t>(counts.v) *
                        static_cast<std::uint64_t>(counts.w);
  if (similarities_.size() != expected)
    fail_input("similarities", "a table layout needs one similarity per group (" + std::to_string(expected) +
                                   " for counts " + std::to_string(counts.u) + " x " + std::to_string(counts.v) +
                                   " x " + std::to_string(counts.w) + ", got " +
                                   std::to_string(similarities_.size()) + ")");
  require_representable_scales(max_abs_log_scale(), "similarities");
  require_memory(static_cast<std::uint64_t>(similarities_.size()) * sizeof(SimilarityTransform),
                 "a table layout of " + std::to_string(similarities_.size()) + " similarities",
                 "use a steady layout (a similarity per step), which stores nothing per group");
  transforms_.reserve(similarities_.size());
  for (const Similarity& s : similarities_) transforms_.push_back(s.transform());
}

LayoutPtr TableLayout::make(const Counts& counts, std::vector<Similarity> similarities) {
  return std::make_shared<const TableLayout>(counts, std::move(similarities));
}

LayoutPtr TableLayout::of(const Layout& layout) {
  const Counts& c = layout.counts();
  require_memory(static_cast<std::uint64_t>(c.groups()) * 2 * sizeof(SimilarityTransform),
                 "a table layout of " + std::to_string(c.groups()) + " groups",
                 "keep the steady layout, which stores nothing per group");
  std::vector<Similarity> table;
  table.reserve(static_cast<std::size_t>(c.groups()));
  for (std::int64_t k = 0; k < c.w; ++k)
    for (std::int64_t j = 0; j < c.v; ++j)
      for (std::int64_t i = 0; i < c.u; ++i) table.push_back(layout.group_similarity(i, j, k));
  return make(c, std::move(table));
}

std::size_t TableLayout::slot(std::int64_t i, std::int64_t j, std::int64_t k) const {
  if (!contains(i, j, k)) fail_group_outside(counts(), i, j, k);
  return static_cast<std::size_t>((k * counts().v + j) * counts().u + i);
}

Similarity TableLayout::group_similarity(std::int64_t i, std::int64_t j, std::int64_t k) const {
  return similarities_[slot(i, j, k)];
}

SimilarityTransform TableLayout::group_transform(std::int64_t i, std::int64_t j, std::int64_t k) const {
  return transforms_[slot(i, j, k)];
}

LayoutPtr TableLayout::with_counts(const Counts& counts) const {
  if (counts == this->counts()) return std::make_shared<const TableLayout>(*this);
  fail_input("counts", "a table layout has one similarity per group: give a new table for other counts");
}

LayoutPtr TableLayout::placed(const Similarity& G) const {
  std::vector<Similarity> moved;
  moved.reserve(similarities_.size());
  for (const Similarity& s : similarities_) moved.push_back(G * s);
  return make(counts(), std::move(moved));
}

double TableLayout::max_abs_log_scale() const {
  double m = 0.0;
  for (const Similarity& s : similarities_) m = std::max(m, std::abs(s.log_scale()));
  return m;
}

double TableLayout::mean_log_scale() const {
  double sum = 0.0;
  for (const Similarity& s : similarities_) sum += s.log_scale();
  return similarities_.empty() ? 0.0 : sum / static_cast<double>(similarities_.size());
}

}  // namespace steady

// ---- file format: {"kind": "table", "similarities": [one per group, i fastest, then j, then k]} --------

namespace steady::detail {
namespace {

json write_table(const Layout& layout) {
  json all = json::array();
  for (const Similarity& s : static_cast<const TableLayout&>(layout).similarities()) {
    json one = write_similarity(s);
    one.erase("description");  // one per group: the file stays small
    all.push_back(one);
  }
  return {{"similarities", all}};
}

LayoutPtr read_table(const json& fields, const Counts& counts, const std::string& path) {
  refuse_unknown_keys(fields, path, {"kind", "similarities"});
  const std::string at = (path.empty() ? "" : path + ".") + "similarities";
  const json& values = member(fields, "similarities", path);
  if (!values.is_array()) fail_input(at, "expected an array of similarities, one per group");
  std::vector<Similarity> table;
  table.reserve(values.size());
  for (std::size_t q = 0; q < values.size(); ++q)
    table.push_back(read_similarity(values[q], at + "[" + std::to_string(q) + "]", false));
  return TableLayout::make(counts, std::move(table));
}

}  // namespace

LayoutCodec table_layout_codec() { return {TableLayout::kKind, &write_table, &read_table}; }

}  // namespace steady::detail
