#include "steady/query/block_bounds.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "lattice/power_table.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

// One direction's flow: generator (sigma, omega, v) in template coordinates, its half-step powers, and
// the arc-length factors A(sigma, h) by block length.
struct Flow {
  double sigma = 0.0;
  Vec3 omega{0.0}, velocity{0.0};
  detail::PowerTable powers;
  std::int64_t lo = 0;  // first index covered
  std::vector<double> arc;  // arc[len - 1] = A(sigma, (len - 1) / 2)
  std::vector<double> scale;  // scale[t - lo] = e^(sigma t)

  Flow(const Similarity& step, std::int64_t first, std::int64_t last)
      : sigma(step.log_scale()),
        omega(step.rotation_vector()),
        velocity(step.velocity()),
        powers(step, first, last),
        lo(first) {
    const std::int64_t lengths = std::min<std::int64_t>(last - first + 1, detail::kMaxPowerTableEntries);
    arc.resize(static_cast<std::size_t>(std::max<std::int64_t>(lengths, 1)));
    for (std::size_t len = 1; len <= arc.size(); ++len) arc[len - 1] = arc_factor(0.5 * static_cast<double>(len - 1));
    scale.resize(static_cast<std::size_t>(lengths));
    for (std::size_t t = 0; t < scale.size(); ++t) scale[t] = std::exp(sigma * static_cast<double>(first + static_cast<std::int64_t>(t)));
  }
  // The largest scale s^t over t in [t0, t1].
  double max_scale(std::int64_t t0, std::int64_t t1) const {
    const std::int64_t t = sigma > 0.0 ? t1 : t0;
    const std::int64_t slot = t - lo;
    if (slot >= 0 && slot < static_cast<std::int64_t>(scale.size())) return scale[static_cast<std::size_t>(slot)];
    return std::exp(sigma * static_cast<double>(t));
  }
  double arc_factor(double half) const {
    const double a = std::abs(sigma);
    return a == 0.0 ? half : std::expm1(a * half) / a;
  }
  double arc_for(std::int64_t len) const {
    return len <= static_cast<std::int64_t>(arc.size()) ? arc[static_cast<std::size_t>(len - 1)]
                                                          : arc_factor(0.5 * static_cast<double>(len - 1));
  }
  // |xi(y)|: the speed of the flow at y.
  double speed(const Vec3& y) const { return glm::length(sigma * y + glm::cross(omega, y) + velocity); }
};

}  // namespace

struct BlockBounds::Impl {
  SimilarityTransform g;
  double g_scale;
  Flow u, v, w;
  Ball templ;
  Counts counts;

  Impl(const SteadyBrick& brick, const Lattice& lat, std::int64_t margin)
      : g(brick.placement.transform()),
        g_scale(brick.placement.scale()),
        u(brick.steps[0], -margin, lat.counts().u - 1 + margin),
        v(brick.steps[1], -margin, lat.counts().v - 1 + margin),
        w(brick.steps[2], -margin, lat.counts().w - 1 + margin),
        counts(lat.counts()) {
    const auto& nodes = lat.definition().nodes;
    Vec3 lo(nodes[0].center), hi(nodes[0].center);
    for (const auto& n : nodes) {
      lo = glm::min(lo, n.center);
      hi = glm::max(hi, n.center);
    }
    templ.center = 0.5 * (lo + hi);
    templ.radius = 0.0;
    for (const auto& n : nodes) templ.radius = std::max(templ.radius, glm::length(n.center - templ.center) + n.radius);
  }

  BlockBound bound(const Vec3& point, double radius, const IndexBlock& b) const {
    // Block centers as half-integers: twice the center index.
    const std::int64_t ti = b.i0 + b.i1 - 1, tj = b.j0 + b.j1 - 1, tk = b.k0 + b.k1 - 1;
    const Vec3 p0 = u.powers.apply_half(ti, point);
    const Vec3 q0 = v.powers.apply_half(tj, p0);
    const Vec3 r0 = w.powers.apply_half(tk, q0);
    const double sw = w.max_scale(b.k0, b.k1 - 1), swv = sw * v.max_scale(b.j0, b.j1 - 1);
    const double swvu = swv * u.max_scale(b.i0, b.i1 - 1);
    BlockBound out;
    out.spread[2] = g_scale * w.speed(r0) * w.arc_for(b.k1 - b.k0);
    out.spread[1] = g_scale * sw * v.speed(q0) * v.arc_for(b.j1 - b.j0);
    out.spread[0] = g_scale * swv * u.speed(p0) * u.arc_for(b.i1 - b.i0);
    out.ball.center = g.apply_point(r0);
    out.ball.radius = out.spread[0] + out.spread[1] + out.spread[2] + radius * g_scale * swvu;
    return out;
  }
};

namespace {
const SteadyBrick& own_brick(const Lattice& lattice) {
  const SteadyBrick* brick = lattice.layout().steady_brick();
  if (!brick || brick->reordered())
    fail_input("lattice", "block bounds need a steady brick in the U V W order (use Lattice::brick_lattice())");
  return *brick;
}
}  // namespace

BlockBounds::BlockBounds(const Lattice& lattice, std::int64_t margin)
    : impl_(std::make_unique<Impl>(own_brick(lattice), lattice, margin)) {}
BlockBounds::~BlockBounds() = default;
BlockBounds::BlockBounds(BlockBounds&&) noexcept = default;
BlockBounds& BlockBounds::operator=(BlockBounds&&) noexcept = default;

BlockBound BlockBounds::bound(const Vec3& point, double radius, const IndexBlock& block) const {
  return impl_->bound(point, radius, block);
}

const Ball& BlockBounds::template_bound() const { return impl_->templ; }

Ball BlockBounds::lattice_bound() const {
  // Every ball lies in a group's image of the template ball, every beam in the hull of two of them.
  const Counts& c = impl_->counts;
  const IndexBlock all{0, c.u, 0, c.v, 0, c.w};
  return impl_->bound(impl_->templ.center, impl_->templ.radius, all).ball;
}

}  // namespace steady
