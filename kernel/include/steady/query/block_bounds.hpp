#pragma once
// Conservative bounds of whole index blocks of a steady brick, in closed form from its similarities:
// no element is evaluated and nothing is stored per element.
//
// A point p of the template (a node center) lands at f(i,j,k) = G W^k V^j U^i p in group (i,j,k). For a
// block of groups around its center (ic, jc, kc) (half-integers allowed: real powers), the triangle
// inequality splits |f(i,j,k) - f(ic,jc,kc)| into one term per direction, and each term is the chord of
// a one-parameter similarity flow x(t) = X^t(y), bounded by its arc length. The speed along such a flow
// is exactly e^(sigma t) |xi(y)| (the flow carries its own velocity field: d/dt X^t(y) = D X^t . xi(y),
// and the linear part of X^t is e^(sigma t) times a rotation), with xi(y) = sigma y + omega x y + v the
// generator's velocity at y. So, with A(sigma, h) = (e^(|sigma| h) - 1) / |sigma| (= h when sigma = 0)
// the largest |integral_0^t e^(sigma s) ds| over |t| <= h:
//     |f - f_c| <= s_G [ |xi_W(r0)| A_W(hk) + max_k s_W^k ( |xi_V(q0)| A_V(hj)
//                                                + max_j s_V^j |xi_U(p0)| A_U(hi) ) ]
// where p0 = U^ic p, q0 = V^jc p0, r0 = W^kc q0, and hi, hj, hk are the block's half-lengths. A ball of
// radius r grows to at most r s_G max(s_U^i s_V^j s_W^k) over the block. The bound is tight for small
// blocks (chord ~ arc) and costs four point transforms and three velocity evaluations, whatever the
// block's size: the basis of the hierarchical ball-interference query (LatticeQuery, method "blocks").
#include <cstdint>
#include <memory>

#include "steady/core/ball.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {


struct BlockBound {
  Ball ball;           // contains the transformed template ball of every group in the block
  double spread[3]{};  // the part of the radius due to the i, j and k extents (where to split)
};

class BlockBounds {
 public:
  // `margin`: how far beyond the lattice's index range blocks may reach (beam ends of templates). The
  // lattice's layout must be a steady brick in the U V W order (InvalidInput otherwise).
  explicit BlockBounds(const Lattice& lattice, std::int64_t margin = 0);
  ~BlockBounds();
  BlockBounds(BlockBounds&&) noexcept;
  BlockBounds& operator=(BlockBounds&&) noexcept;

  // A ball containing S(i,j,k)(Ball{point, radius}) for every group (i,j,k) of the (non-empty) block;
  // point and radius in template coordinates.
  BlockBound bound(const Vec3& point, double radius, const IndexBlock& block) const;

  // The template's bounding ball (all nodes), in template coordinates.
  const Ball& template_bound() const;
  // A ball containing every ball and beam of the lattice.
  Ball lattice_bound() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace steady
