#include "steady/query/filters.hpp"


#include <cmath>
#include <sstream>

#include "steady/core/errors.hpp"
#include "steady/query/filtered_lattice.hpp"

namespace steady {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;

class IndexStencil : public NodeFilter {
 public:
  IndexStencil(std::vector<std::uint8_t> cells, std::int64_t sx, std::int64_t sy, std::int64_t sz, int nodes)
      : cells_(std::move(cells)), sx_(sx), sy_(sy), sz_(sz), nodes_(nodes) {}
  void evaluate(const Lattice&, const NodeId* ids, const Ball*, std::size_t n, std::uint8_t* keep) const override {
    auto wrap = [](std::int64_t a, std::int64_t m) { return ((a % m) + m) % m; };
    for (std::size_t q = 0; q < n; ++q) {
      const NodeId& id = ids[q];
      std::int64_t cell = (wrap(id.i, sx_) * sy_ + wrap(id.j, sy_)) * sz_ + wrap(id.k, sz_);
      if (nodes_ > 0) cell = cell * nodes_ + wrap(id.n, nodes_);
      keep[q] = cells_[static_cast<std::size_t>(cell)] ? 1 : 0;
    }
  }
  std::string describe() const override {
    std::ostringstream os;
    os << "index stencil " << sx_ << "x" << sy_ << "x" << sz_ << (nodes_ > 0 ? " per node" : "");
    return os.str();
  }

 private:
  std::vector<std::uint8_t> cells_;
  std::int64_t sx_, sy_, sz_;
  int nodes_;
};

class LatticeInLattice : public NodeFilter {
 public:
  explicit LatticeInLattice(std::shared_ptr<const FilteredLattice> coarse) : coarse_(std::move(coarse)) {}
  void evaluate(const Lattice&, const NodeId*, const Ball* balls, std::size_t n, std::uint8_t* keep) const override {
    for (std::size_t q = 0; q < n; ++q) keep[q] = coarse_->touches(balls[q]) ? 1 : 0;
  }
  bool parallel_safe() const override {
    return !coarse_->filter() || coarse_->materialized() || coarse_->filter()->parallel_safe();
  }
  std::string describe() const override {
    return "lattice in lattice (" + std::to_string(coarse_->lattice().ball_count()) + "-ball coarse lattice" +
           (coarse_->filter() ? ", itself filtered by " + coarse_->filter()->describe() : std::string()) + ")";
  }
  int nesting() const override { return 1 + (coarse_->filter() ? coarse_->filter()->nesting() : 0); }

 private:
  std::shared_ptr<const FilteredLattice> coarse_;
};

class Gyroid : public NodeFilter {
 public:
  Gyroid(double period, double thickness, const Vec3& origin, GyroidMode mode)
      : scale_(kTwoPi / period), thickness_(thickness), origin_(origin), mode_(mode) {}
  void evaluate(const Lattice&, const NodeId*, const Ball* balls, std::size_t n, std::uint8_t* keep) const override {
    for (std::size_t q = 0; q < n; ++q) {
      const Vec3 p = (balls[q].center - origin_) * scale_;
      const double g = std::sin(p.x) * std::cos(p.y) + std::sin(p.y) * std::cos(p.z) + std::sin(p.z) * std::cos(p.x);
      keep[q] = (mode_ == GyroidMode::Sheet ? std::abs(g) <= thickness_ : g <= thickness_) ? 1 : 0;
    }
  }
  std::string describe() const override {
    std::ostringstream os;
    os << "gyroid " << (mode_ == GyroidMode::Sheet ? "sheet |g| <= " : "solid g <= ") << thickness_ << ", period "
       << kTwoPi / scale_;
    return os.str();
  }

 private:
  double scale_, thickness_;
  Vec3 origin_;
  GyroidMode mode_;
};

class InsideCallable : public NodeFilter {
 public:
  InsideCallable(PointClassifier f, bool parallel_safe, std::string name)
      : f_(std::move(f)), parallel_safe_(parallel_safe), name_(std::move(name)) {}
  void evaluate(const Lattice&, const NodeId*, const Ball* balls, std::size_t n, std::uint8_t* keep) const override {
    std::vector<double> pts(3 * n);
    for (std::size_t q = 0; q < n; ++q) {
      pts[3 * q] = balls[q].center.x;
      pts[3 * q + 1] = balls[q].center.y;
      pts[3 * q + 2] = balls[q].center.z;
    }
    f_(pts.data(), n, keep);
  }
  bool parallel_safe() const override { return parallel_safe_; }
  std::string describe() const override { return name_; }

 private:
  PointClassifier f_;
  bool parallel_safe_;
  std::string name_;
};

// And / or / not of filters. A chain a & b & c ... built one operator at a time (as `f = f & g` in a loop
// does) is kept as a list that shares the earlier links, so it costs O(1) to extend and is evaluated,
// described and destroyed by iteration, whatever its length; only genuine nesting (an `or` inside an
// `and` inside ...) recurses, and it is bounded by kMaxFilterNesting.
class Combined : public NodeFilter {
 public:
  enum class Op { All, Any, Not };
  Combined(Op op, std::shared_ptr<const Combined> earlier, std::vector<FilterPtr> parts)
      : op_(op), earlier_(std::move(earlier)), parts_(std::move(parts)) {
    nesting_ = earlier_ ? earlier_->nesting_ : 1;
    for (const FilterPtr& f : parts_) nesting_ = std::max(nesting_, 1 + f->nesting());
    parallel_safe_ = !earlier_ || earlier_->parallel_safe_;
    for (const FilterPtr& f : parts_) parallel_safe_ = parallel_safe_ && f->parallel_safe();
  }
  ~Combined() override {
    // Unlink the chain iteratively: the recursive destruction of a long chain would overflow the stack.
    std::shared_ptr<const Combined> next = std::move(earlier_);
    while (next && next.use_count() == 1) next = std::move(const_cast<Combined&>(*next).earlier_);
  }
  Op op() const { return op_; }

  void evaluate(const Lattice& lat, const NodeId* ids, const Ball* balls, std::size_t n, std::uint8_t* keep) const override {
    if (op_ == Op::Not) {
      parts_[0]->evaluate(lat, ids, balls, n, keep);
      for (std::size_t q = 0; q < n; ++q) keep[q] = keep[q] ? 0 : 1;
      return;
    }
    std::vector<std::uint8_t> part(n);
    for (std::size_t q = 0; q < n; ++q) keep[q] = op_ == Op::All ? 1 : 0;
    for (const Combined* link = this; link; link = link->earlier_.get())
      for (const FilterPtr& f : link->parts_) {
        f->evaluate(lat, ids, balls, n, part.data());
        for (std::size_t q = 0; q < n; ++q) keep[q] = op_ == Op::All ? (keep[q] && part[q]) : (keep[q] || part[q]);
      }
  }
  bool parallel_safe() const override { return parallel_safe_; }
  int nesting() const override { return nesting_; }
  std::string describe() const override {
    if (op_ == Op::Not) return "not (" + parts_[0]->describe() + ")";
    std::vector<const Combined*> links;  // earliest first
    for (const Combined* link = this; link; link = link->earlier_.get()) links.push_back(link);
    std::string s;
    for (auto it = links.rbegin(); it != links.rend(); ++it)
      for (const FilterPtr& f : (*it)->parts_)
        s += (s.empty() ? "(" : op_ == Op::All ? " and (" : " or (") + f->describe() + ")";
    return s;
  }

 private:
  Op op_;
  std::shared_ptr<const Combined> earlier_;  // the chain's earlier parts (same op), or null
  std::vector<FilterPtr> parts_;
  int nesting_ = 1;
  bool parallel_safe_ = true;
};

// `and` / `or` of a list: a list starting with a combination of the same op extends that chain.
FilterPtr combine(Combined::Op op, std::vector<FilterPtr> filters) {
  std::shared_ptr<const Combined> earlier;
  if (filters.size() > 1)
    if (auto first = std::dynamic_pointer_cast<const Combined>(filters.front()); first && first->op() == op) {
      earlier = first;
      filters.erase(filters.begin());
    }
  // Not const-qualified as made: the destructor may move a sole owner's link (see ~Combined).
  std::shared_ptr<const Combined> combined = std::make_shared<Combined>(op, std::move(earlier), std::move(filters));
  if (combined->nesting() > kMaxFilterNesting)
    fail_input("filters", "nested " + std::to_string(combined->nesting()) + " levels deep (at most " +
                              std::to_string(kMaxFilterNesting) +
                              "): combine many filters in one list (all_of / any_of) instead of nesting them");
  return combined;
}

void require_filters(const std::vector<FilterPtr>& f, const char* field) {
  if (f.empty()) fail_input(field, "needs at least one filter");
  for (std::size_t q = 0; q < f.size(); ++q)
    if (!f[q]) fail_input(std::string(field) + "[" + std::to_string(q) + "]", "is not a filter");
}

}  // namespace

FilterPtr index_stencil(std::vector<std::uint8_t> cells, std::int64_t sx, std::int64_t sy, std::int64_t sz, int nodes) {
  if (sx < 1 || sy < 1 || sz < 1) fail_input("stencil", "every dimension must be >= 1");
  if (nodes < 0) fail_input("stencil", "the node dimension must be >= 0");
  const std::int64_t size = sx * sy * sz * std::max(1, nodes);
  if (static_cast<std::int64_t>(cells.size()) != size)
    fail_input("stencil", "has " + std::to_string(cells.size()) + " cells, expected " + std::to_string(size));
  return std::make_shared<IndexStencil>(std::move(cells), sx, sy, sz, nodes);
}

FilterPtr lattice_in_lattice(std::shared_ptr<const FilteredLattice> coarse) {
  if (!coarse) fail_input("coarse", "is not a lattice");
  if (coarse->lattice().ball_count() == 0) fail_input("coarse", "the coarse lattice is empty");
  auto lil = std::make_shared<LatticeInLattice>(std::move(coarse));
  if (lil->nesting() > kMaxFilterNesting)
    fail_input("coarse", "its filters nest " + std::to_string(lil->nesting()) + " levels deep (at most " +
                             std::to_string(kMaxFilterNesting) + ")");
  return lil;
}

FilterPtr gyroid(double period, double thickness, const Vec3& origin, GyroidMode mode) {
  require_positive(period, "period");
  require_finite(thickness, "thickness");
  for (int c = 0; c < 3; ++c) require_finite(origin[c], "origin");
  return std::make_shared<Gyroid>(period, thickness, origin, mode);
}

FilterPtr inside(PointClassifier classify, bool parallel_safe, std::string name) {
  if (!classify) fail_input("classify", "is not callable");
  return std::make_shared<InsideCallable>(std::move(classify), parallel_safe, std::move(name));
}

FilterPtr all_of(std::vector<FilterPtr> filters) {
  require_filters(filters, "filters");
  return combine(Combined::Op::All, std::move(filters));
}

FilterPtr any_of(std::vector<FilterPtr> filters) {
  require_filters(filters, "filters");
  return combine(Combined::Op::Any, std::move(filters));
}

FilterPtr negate(FilterPtr filter) {
  std::vector<FilterPtr> f{std::move(filter)};
  require_filters(f, "filter");
  return combine(Combined::Op::Not, std::move(f));
}

}  // namespace steady
