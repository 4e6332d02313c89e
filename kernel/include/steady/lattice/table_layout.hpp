#pragma once
// A layout that is not steady at all: one similarity per group, from a table (a designer's map, a sampled
// field, groups placed by hand). Nothing about it is assumed: no steady-brick view, so queries, sums and
// bounds take their general paths (every group evaluated). Memory: one similarity per group.
#include <vector>

#include "steady/lattice/layout.hpp"

namespace steady {

class TableLayout final : public Layout {
 public:
  // similarities: counts.groups() values, group (i, j, k) at ((k * v) + j) * u + i. InvalidInput naming the
  // field for a wrong size, counts < 1, or scales beyond floating point.
  static LayoutPtr make(const Counts& counts, std::vector<Similarity> similarities);
  // A table of the groups of any other layout (for tests, and to freeze a layout).
  static LayoutPtr of(const Layout& layout);

  static constexpr const char* kKind = "table";
  std::string kind() const override { return kKind; }
  const std::vector<Similarity>& similarities() const { return similarities_; }

  Similarity group_similarity(std::int64_t i, std::int64_t j, std::int64_t k) const override;
  SimilarityTransform group_transform(std::int64_t i, std::int64_t j, std::int64_t k) const override;
  LayoutPtr with_counts(const Counts& counts) const override;
  LayoutPtr placed(const Similarity& G) const override;
  double max_abs_log_scale() const override;
  double mean_log_scale() const override;

  TableLayout(const Counts& counts, std::vector<Similarity> similarities);  // use make()

 private:
  std::size_t slot(std::int64_t i, std::int64_t j, std::int64_t k) const;

  std::vector<Similarity> similarities_;
  std::vector<SimilarityTransform> transforms_;
};

}  // namespace steady
