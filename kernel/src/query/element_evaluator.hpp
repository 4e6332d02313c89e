#pragma once
// Evaluates lattice elements from power tables, bit-identical to Lattice::ball and Lattice::beam (the layout's
// placement formula, SteadyBrick::row_prefix and place, over the same powers), so every query path tests
// exactly the geometry the lattice lists and the naive and accelerated answers can be compared element for
// element. The power tables exist for a steady brick in its own axes (steady()); for any other layout only
// the groups inside the lattice are evaluated, through the layout.
#include <cstdint>

#include "lattice/power_table.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady::detail {

class ElementEvaluator {
 public:
  // Tables cover the lattice's indices extended by `margin` on both sides (templates of beams that end
  // outside the lattice); beyond that powers come from the generator.
  ElementEvaluator(const Lattice& lattice, std::int64_t margin);

  const Lattice& lattice() const { return *lattice_; }
  // Whether the power tables (u(), v(), w(), row_prefix) exist: the fast paths' precondition.
  bool steady() const { return steady_; }
  const PowerTable& u() const { return u_; }
  const PowerTable& v() const { return v_; }
  const PowerTable& w() const { return w_; }
  const SimilarityTransform& placement() const { return g_; }

  // (G W^k) V^j, the prefix Lattice::group_transform multiplies by U^i (steady() only).
  SimilarityTransform row_prefix(std::int64_t j, std::int64_t k) const {
    return SteadyBrick::row_prefix(g_, w_.at(k), v_.at(j));
  }
  SimilarityTransform group(std::int64_t i, std::int64_t j, std::int64_t k) const {
    if (!steady_) return lattice_->group_transform(i, j, k);
    return SteadyBrick::place(row_prefix(j, k), u_.at(i));
  }
  // The ball of node n under a group transform.
  Ball node_ball(const SimilarityTransform& group, int n) const {
    const TemplateNode& t = lattice_->definition().nodes[static_cast<std::size_t>(n)];
    return group.apply(Ball{t.center, t.radius});
  }
  Ball node_ball(std::int64_t i, std::int64_t j, std::int64_t k, int n) const { return node_ball(group(i, j, k), n); }
  // Pattern p's beam from the balls of its two nodes (the beam's own radii replace theirs, if given).
  BeamGeometry beam_from_nodes(const Ball& start_node, const Ball& end_node, int p) const {
    const BeamPattern& b = lattice_->definition().beams[static_cast<std::size_t>(p)];
    BeamGeometry g{start_node, end_node};
    if (b.has_radii()) {
      const auto& nodes = lattice_->definition().nodes;
      g.start.radius = *b.from_radius * g.start.radius / nodes[static_cast<std::size_t>(b.from)].radius;
      g.end.radius = *b.to_radius * g.end.radius / nodes[static_cast<std::size_t>(b.to)].radius;
    }
    return g;
  }
  BeamGeometry beam(std::int64_t i, std::int64_t j, std::int64_t k, int p) const {
    const BeamPattern& b = lattice_->definition().beams[static_cast<std::size_t>(p)];
    return beam_from_nodes(node_ball(i, j, k, b.from), node_ball(i + b.di, j + b.dj, k + b.dk, b.to), p);
  }

 private:
  const Lattice* lattice_;
  bool steady_ = false;
  SimilarityTransform g_;
  PowerTable u_, v_, w_;
};

}  // namespace steady::detail
