#pragma once
// A lattice seen through a node filter. Index semantics (docs/queries.md): nothing is renumbered.
// Queries return indices into the *unfiltered* Lattice::balls() / beams() (stable whatever the filter),
// and ball_mask() / beam_mask() say which of those exist after filtering (1 kept, 0 dropped); a dense
// numbering, when wanted, is the running count of a mask. A ball is kept when its node exists and passes
// the filter; a beam when both of its nodes are kept.
//
// Evaluation is lazy: a query filters the elements it finds, evaluating the filter on their nodes only.
// materialize() evaluates every node once (in parallel) and keeps the mask, one byte per ball: what a
// Lattice-in-Lattice construction computes, and what a coarse level of a cascade should do before it
// filters a finer lattice (every fine node then costs a lookup instead of a filter evaluation).
#include <atomic>
#include <memory>
#include <vector>

#include "steady/query/filters.hpp"
#include "steady/query/queries.hpp"

namespace steady {

class FilteredLattice : public InterferenceSource {
 public:
  explicit FilteredLattice(Lattice lattice, FilterPtr filter = nullptr, QueryMethod method = QueryMethod::Auto);
  FilteredLattice(const FilteredLattice&) = delete;
  FilteredLattice& operator=(const FilteredLattice&) = delete;

  const Lattice& lattice() const { return *lattice_; }
  const LatticeQuery& query() const { return *query_; }
  const FilterPtr& filter() const { return filter_; }
  QueryMethod method() const { return method_; }

  // Does the node exist and pass? (The mask when materialized, the filter otherwise.)
  bool keeps(const NodeId& id) const;

  void materialize();
  bool materialized() const { return !mask_.empty() || lattice_->ball_count() == 0; }
  // Masks over Lattice::balls() (ball_count() bytes) and Lattice::beams() (beam_count() bytes), computed
  // in parallel (from the kept mask when materialized).
  void ball_mask(std::uint8_t* out) const;
  void beam_mask(std::uint8_t* out) const;
  // Beam mask from a ball mask, without re-evaluating the filter.
  void beam_mask_from(const std::uint8_t* balls, std::uint8_t* out) const;

  // InterferenceSource: the unfiltered query's hits whose nodes are kept.
  void visit(const Ball& query, HitSink& sink) const override;
  void visit_nearest(const Ball& query, HitSink& sink) const override;
  Ball bound() const override { return query_->bound(); }
  double element_scale() const override { return scale_; }
  BallQueryResult query_ball(const Ball& query) const;
  bool touches(const Ball& query) const;

 private:
  void visit_with(const Ball& query, HitSink& sink, QueryMethod method) const;

  std::unique_ptr<Lattice> lattice_;
  std::unique_ptr<LatticeQuery> query_;
  FilterPtr filter_;
  QueryMethod method_;
  double scale_;
  std::vector<std::uint8_t> mask_;  // per ball, when materialized
};

}  // namespace steady
