#pragma once
// Queries built on ball interference, parallel over their inputs (TBB):
//   contains   point membership: a ball of radius 0 (closed elements: boundary points are inside)
//   distance   the distance to the lattice (0 inside), when at most `bound`; +inf beyond
//   raycast    the first point of each ray in the lattice: sphere tracing driven by BIQ. At p, the
//              elements meeting the ball (p, R) are exactly those that can meet the segment [p, p + R d];
//              their exact ray entries give the first hit in it, or prove the segment empty so the ray
//              advances by R (R adapts to the number of elements found). Exact, never steps through.
//   voxelize   point membership at the centers of a box's voxels
// All of them accept any InterferenceSource: a lattice (LatticeSource) or a filtered lattice.
#include <cstdint>
#include <limits>

#include "steady/query/lattice_query.hpp"

namespace steady {

// What the derived queries need: the elements meeting a closed ball, and a ball containing them all.
class InterferenceSource {
 public:
  virtual ~InterferenceSource() = default;
  virtual void visit(const Ball& query, HitSink& sink) const = 0;
  // The same for a search that lowers the sink's reach as it goes (distances): a path that visits nearer
  // parts first and prunes by the reach.
  virtual void visit_nearest(const Ball& query, HitSink& sink) const { visit(query, sink); }
  virtual Ball bound() const = 0;
  // A length of the order of the elements' size (first step of rays and distances).
  virtual double element_scale() const = 0;
};

class LatticeSource : public InterferenceSource {
 public:
  explicit LatticeSource(const LatticeQuery& query, QueryMethod method = QueryMethod::Auto);
  void visit(const Ball& query, HitSink& sink) const override { query_.visit(query, sink, method_); }
  void visit_nearest(const Ball& query, HitSink& sink) const override;
  Ball bound() const override { return query_.bound(); }
  double element_scale() const override { return scale_; }

 private:
  const LatticeQuery& query_;
  QueryMethod method_;
  double scale_;
};

// The typical element size of a lattice: its mean template radius times the geometric mean group scale.
double typical_element_size(const Lattice& lattice);

// points: 3 n doubles (x, y, z). Results: n values. Bad input throws InvalidInput naming the parameter.
void contains(const InterferenceSource& source, const double* points, std::size_t n, std::uint8_t* inside);
void distance(const InterferenceSource& source, const double* points, std::size_t n, double bound, double* out);
// directions need not be unit vectors; t is the distance along the unit direction, +inf for no hit
// within max_distance.
void raycast(const InterferenceSource& source, const double* origins, const double* directions, std::size_t n,
             double max_distance, double* t);

// Voxel (ix, iy, iz) of the box [lo, hi] split into shape[0] x shape[1] x shape[2] cells has its center
// at lo + (index + 0.5) (hi - lo) / shape; out[(ix * shape[1] + iy) * shape[2] + iz] (C order).
void voxelize(const InterferenceSource& source, const Vec3& lo, const Vec3& hi, const std::int64_t shape[3],
              std::uint8_t* out);

}  // namespace steady
