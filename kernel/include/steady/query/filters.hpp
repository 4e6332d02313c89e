#pragma once
// Node filters: which nodes of a lattice exist (dissertation chapter 9, RangeFinder's Lattice-in-Lattice).
// A filter keeps or drops nodes; a FilteredLattice (filtered_lattice.hpp) keeps a ball when its node
// exists and passes, and a beam when both its nodes do. Filters are pure predicates of a node (its
// indices and its ball), evaluated lazily on the elements a query touches, or once for every node when
// a mask is asked for; they combine with all_of / any_of / negate.
//
//   index_stencil      a boolean array repeated over the group indices: S[i mod x, j mod y, k mod z]
//                      (optionally per node n)
//   lattice_in_lattice keep a node whose ball meets another (coarse, possibly filtered) lattice: a
//                      ball-interference query per node; cascade by filtering the coarse one too
//   gyroid             keep a node whose center is in a gyroid sheet |g| <= t (or solid g <= t),
//                      g = sin x cos y + sin y cos z + sin z cos x at 2 pi (center - origin) / period
//   inside             keep a node whose center is inside a body: any classifier callable, or a B-rep
//                      solid (steady/brep/body_filter.hpp: inside_brep, boundary counts inside)
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "steady/lattice/lattice.hpp"
#include "steady/query/lattice_query.hpp"

namespace steady {

class FilteredLattice;

class NodeFilter {
 public:
  virtual ~NodeFilter() = default;
  // keep[q] = 1 when node ids[q] (whose ball is balls[q]) passes, 0 otherwise. Called from several
  // threads at once when parallel_safe().
  virtual void evaluate(const Lattice& lattice, const NodeId* ids, const Ball* balls, std::size_t n,
                        std::uint8_t* keep) const = 0;
  virtual bool parallel_safe() const { return true; }
  virtual std::string describe() const = 0;
  // How deeply filters nest inside this one (1 for a filter of its own): evaluation recurses this deep.
  virtual int nesting() const { return 1; }
};

// Combinations nest at most this deep (each level is a stack frame when evaluated); chains of one operator
// (a & b & c ...) do not nest, however long.
constexpr int kMaxFilterNesting = 1000;
using FilterPtr = std::shared_ptr<const NodeFilter>;

// cells: sx * sy * sz values in C order [x][y][z] (or sx * sy * sz * nodes, [x][y][z][n], when
// per_node); nonzero keeps.
FilterPtr index_stencil(std::vector<std::uint8_t> cells, std::int64_t sx, std::int64_t sy, std::int64_t sz,
                        int nodes = 0);
FilterPtr lattice_in_lattice(std::shared_ptr<const FilteredLattice> coarse);
enum class GyroidMode { Sheet, Solid };
FilterPtr gyroid(double period, double thickness, const Vec3& origin = Vec3(0.0), GyroidMode mode = GyroidMode::Sheet);
// classify(points, n, inside): points are 3 n doubles; inside[q] = 1 for points in the body.
using PointClassifier = std::function<void(const double* points, std::size_t n, std::uint8_t* inside)>;
FilterPtr inside(PointClassifier classify, bool parallel_safe, std::string name = "inside a body");
FilterPtr all_of(std::vector<FilterPtr> filters);
FilterPtr any_of(std::vector<FilterPtr> filters);
FilterPtr negate(FilterPtr filter);

}  // namespace steady
