#include "steady/properties/radius_scaling.hpp"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <set>
#include <sstream>
#include <tuple>

#include "properties/lattice_sums.hpp"
#include "steady/query/hub_overlaps.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/core/constants.hpp"
#include "steady/core/progress.hpp"

namespace steady {

using namespace detail;

namespace {


// Beam shapes held in memory at most (48 bytes each); beyond, the model is refused (ResourceLimit).
constexpr std::size_t kMaxBeamShapes = 50'000'000;

// A beam at radius scale 1 and the total weight (sum of scale^3) of its similar copies.
struct BeamShape {
  double length, node_a, radius_a, node_b, radius_b, weight;
};

struct HubClass {
  HubShape shape;
  double weight;
};

// Volume of a stump's part outside its node ball, alone: frustum (exit circle to cut) minus the cap.
double stump_volume_alone(double R, double r, double r_other, double L) {
  const double sin_phi = (r - r_other) / L;
  const double cos_phi = std::sqrt((1.0 - sin_phi) * (1.0 + sin_phi));
  const double exit = r * sin_phi + cos_phi * std::sqrt(std::max(0.0, (R - r) * (R + r)));
  const double cut = 0.5 * L;
  const double rho_exit = (r - exit * sin_phi) / cos_phi, rho_cut = (r - cut * sin_phi) / cos_phi;
  const double frustum = kPi * (cut - exit) * (rho_exit * rho_exit + rho_exit * rho_cut + rho_cut * rho_cut) / 3.0;
  const double h = R - exit;
  return frustum - kPi * h * h * (3.0 * R - h) / 3.0;
}

double scale_cubed_sum(const Similarity& step, std::int64_t first, std::int64_t count) {
  const double l3 = 3.0 * step.log_scale();
  return std::exp(l3 * static_cast<double>(first)) * geometric_sum(l3, count);
}

}  // namespace

struct RadiusScaledVolume::Model {
  explicit Model(const Lattice& l) : lattice(l) {}
  Lattice lattice;
  double balls = 0.0;  // volume of all balls at scale 1
  std::vector<BeamShape> beams;
  // Every hub of the lattice is, up to a similarity, a subset of one of these (its node's hub with all
  // its stumps, neighbours outside the lattice included): no overlap among them means none anywhere.
  std::vector<HubShape> full_hubs;
  // The hub classes and their copy weights, for the overlap corrections: built when first needed.
  mutable std::once_flag classes_built;
  mutable std::vector<HubClass> hubs;
  double max_scale = std::numeric_limits<double>::infinity();
  HubPropertiesOptions hub_options;
  bool per_element = false;  // a layout that is not a steady brick: every element its own shape, weight 1
  void build_from_sums();
  void build_per_element();
  void build_hub_classes() const;
};

Lattice with_radius_scale(const Lattice& lattice, double scale) {
  require_positive(scale, "scale");
  LatticeDefinition d = lattice.definition();
  for (TemplateNode& n : d.nodes) n.radius *= scale;
  for (BeamPattern& b : d.beams)
    if (b.has_radii()) {
      *b.from_radius *= scale;
      *b.to_radius *= scale;
    }
  return Lattice(std::move(d));
}

namespace {
// The lattice the model is built on: its steady-brick view when it has one (the same groups), else itself.
const Lattice& lattice_for_sums(const Lattice& lattice) {
  const Lattice* brick = lattice.brick_lattice();
  return brick ? *brick : lattice;
}
}  // namespace

RadiusScaledVolume::RadiusScaledVolume(const Lattice& lattice, const HubPropertiesOptions& hub)
    : model_(std::make_unique<Model>(lattice_for_sums(lattice))) {
  model_->hub_options = hub;
  if (model_->lattice.layout().steady_brick())
    model_->build_from_sums();
  else
    model_->build_per_element();
}

void RadiusScaledVolume::Model::build_per_element() {
  per_element = true;
  // Every ball and beam of a lattice without steady rows: seconds per 10^6 elements, so Ctrl-C is polled.
  for (std::int64_t q = 0; q < lattice.ball_count(); ++q) {
    if ((q & 4095) == 0) poll_progress();
    const double R = lattice.ball(lattice.ball_id(q)).radius;
    balls += 4.0 / 3.0 * kPi * R * R * R;
  }
  for (std::int64_t q = 0; q < lattice.beam_count(); ++q) {
    if ((q & 4095) == 0) poll_progress();
    const BeamId id = lattice.beam_id(q);
    const BeamGeometry g = lattice.beam(id);
    const Ball A = lattice.ball(lattice.beam_start(id)), B = lattice.ball(lattice.beam_end(id));
    const double L = glm::length(B.center - A.center);
    beams.push_back({L, A.radius, g.start.radius, B.radius, g.end.radius, 1.0});
    max_scale = std::min(max_scale, 0.5 * L / std::max(A.radius, B.radius));
    if (g.start.radius != g.end.radius) max_scale = std::min(max_scale, L / std::abs(g.start.radius - g.end.radius));
  }
  full_hubs.resize(static_cast<std::size_t>(lattice.ball_count()));
  Progress* const caller = current_progress();
  tbb::parallel_for(std::int64_t(0), lattice.ball_count(), [&](std::int64_t q) {
    const ProgressScope scope(caller);
    if ((q & 1023) == 0) poll_progress();
    full_hubs[static_cast<std::size_t>(q)] = hub_shape(hub(lattice, lattice.ball_id(q)));
  });
}

void RadiusScaledVolume::Model::build_from_sums() {
  Model& m = *this;
  Context c(m.lattice);
  const LatticeDefinition& def = c.def;
  const Counts& n = lattice.counts();
  const double g3 = std::pow(c.G.scale(), 3);
  // balls
  const double groups = scale_cubed_sum(c.U, 0, n.u) * scale_cubed_sum(c.V, 0, n.v) * scale_cubed_sum(c.W, 0, n.w);
  double template_balls = 0.0;
  for (const TemplateNode& t : def.nodes) template_balls += 4.0 / 3.0 * kPi * t.radius * t.radius * t.radius;
  m.balls = g3 * groups * template_balls;
  std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t, int>> gone;
  for (const NodeId& id : def.omitted) gone.insert({id.i, id.j, id.k, id.n});
  for (const auto& [i, j, k, node] : gone) {
    const double s = c.group(i, j, k).scale, R = def.nodes[node].radius * s;
    m.balls -= g3 * 4.0 / 3.0 * kPi * R * R * R;
  }
  // beams: the distinct shapes of each pattern, as in lattice_properties
  auto add_beam = [&](int p, const SimilarityTransform& ta, const SimilarityTransform& tb, double weight) {
    const BeamPattern& b = def.beams[p];
    const Ball A = node_ball(c, ta, b.from), B = node_ball(c, tb, b.to);
    const double ra = b.has_radii() ? *b.from_radius * ta.scale : A.radius;
    const double rb = b.has_radii() ? *b.to_radius * tb.scale : B.radius;
    const double L = glm::length(B.center - A.center);
    m.beams.push_back({L, A.radius, ra, B.radius, rb, weight});
    m.max_scale = std::min(m.max_scale, 0.5 * L / std::max(A.radius, B.radius));
    if (ra != rb) m.max_scale = std::min(m.max_scale, L / std::abs(ra - rb));
  };
  for (int p = 0; p < lattice.pattern_count(); ++p) {
    if (c.absent[p]) continue;  // no beam of it in the lattice (patterns_without_beams)
    const BeamPattern& b = def.beams[p];
    const IndexBlock starts = pattern_start_groups(n, b);
    const IndexRange ri = range_i(starts), rj = range_j(starts), rk = range_k(starts);
    if (ri.size() == 0 || rj.size() == 0 || rk.size() == 0) continue;
    const SimilarityTransform w_dk = c.w_pow(b.dk);
    const double along_k = g3 * scale_cubed_sum(c.W, rk.lo, rk.size());
    const double along_j = scale_cubed_sum(c.V, rj.lo, rj.size());
    if (c.i_steady(b)) {
      add_beam(p, SimilarityTransform{}, c.group(b.di, b.dj, b.dk),
               along_k * along_j * scale_cubed_sum(c.U, ri.lo, ri.size()));
    } else if (c.j_steady(b)) {
      const SimilarityTransform head = w_dk * c.v_pow(b.dj);
      for (std::int64_t i = ri.lo; i < ri.hi; ++i)
        add_beam(p, c.u_pow(i),
                 head * c.u_pow(i + b.di), along_k * along_j);
    } else {
      if (m.beams.size() + static_cast<std::size_t>(ri.size() * rj.size()) > kMaxBeamShapes)
        throw ResourceLimit("radius scaling: the lattice has more than " + std::to_string(kMaxBeamShapes) +
                            " distinct beam shapes (its W does not commute with V)");
      require_memory(static_cast<std::uint64_t>(ri.size() * rj.size()) * sizeof(BeamShape),
                     "radius scaling: " + std::to_string(ri.size() * rj.size()) + " beam shapes",
                     "scale the radii of a smaller lattice of the same steps");
      std::vector<SimilarityTransform> u_powers(n.u);
      for (std::int64_t i = 0; i < n.u; ++i) u_powers[i] = c.u_pow(i);
      for (std::int64_t j = rj.lo; j < rj.hi; ++j) {
        poll_progress();  // a row of distinct beam shapes each
        const SimilarityTransform vj = c.v_pow(j);
        const SimilarityTransform head = w_dk * c.v_pow(j + b.dj);
        for (std::int64_t i = ri.lo; i < ri.hi; ++i) add_beam(p, vj * u_powers[i], head * u_powers[i + b.di], along_k);
      }
    }
  }
  // one full hub per node and per index of a direction along which its hubs are not similar copies
  struct FullJob {
    int node;
    std::int64_t i, j;
    bool i_steady, j_steady;
  };
  std::vector<FullJob> full_jobs;
  for (int node = 0; node < static_cast<int>(def.nodes.size()); ++node) {
    const std::vector<Incidence> all = incidences(c, node);
    if (all.size() < 2) continue;
    bool i_steady = true, j_steady = true;
    for (const Incidence& s : all) {
      i_steady = i_steady && c.i_steady(def.beams[s.pattern]);
      j_steady = j_steady && c.j_steady(def.beams[s.pattern]);
    }
    i_steady = i_steady && j_steady;
    const std::int64_t count = (i_steady ? 1 : n.u) * (j_steady ? 1 : n.v);
    if (full_jobs.size() + static_cast<std::size_t>(count) > kMaxBeamShapes)
      throw ResourceLimit("radius scaling: the lattice has more than " + std::to_string(kMaxBeamShapes) +
                          " distinct hub shapes (its W does not commute with V)");
    for (std::int64_t i = 0; i < (i_steady ? 1 : n.u); ++i)
      for (std::int64_t j = 0; j < (j_steady ? 1 : n.v); ++j) full_jobs.push_back({node, i, j, i_steady, j_steady});
  }
  m.full_hubs.resize(full_jobs.size());
  Progress* const caller = current_progress();
  tbb::parallel_for(std::size_t(0), full_jobs.size(), [&](std::size_t q) {
    const ProgressScope scope(caller);
    if ((q & 255) == 0) poll_progress();
    const FullJob& job = full_jobs[q];
    const std::vector<Incidence> all = incidences(c, job.node);
    std::vector<SimilarityTransform> other;
    for (const Incidence& s : all)
      other.push_back(c.group(job.i_steady ? s.di : job.i + s.di, job.j_steady ? s.dj : job.j + s.dj, s.dk));
    SimilarityTransform base;
    if (!job.i_steady) base = c.u_pow(job.i);
    if (!job.j_steady) base = c.v_pow(job.j) * base;
    m.full_hubs[q] = hub_shape_at(c, job.node, base, all, other);
  });
  // omitted nodes: the beams they kill, and the hubs around them (actual minus generic)
  std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t, int>> killed;
  for (const auto& [i, j, k, node] : gone)
    for (const Incidence& s : incidences(c, node)) {
      if (!in_lattice(i, s.di, n.u) || !in_lattice(j, s.dj, n.v) || !in_lattice(k, s.dk, n.w)) continue;
      const BeamPattern& b = def.beams[s.pattern];
      killed.insert(s.at_start ? std::make_tuple(i, j, k, s.pattern)
                               : std::make_tuple(i - b.di, j - b.dj, k - b.dk, s.pattern));
    }
  for (const auto& [i, j, k, p] : killed) {
    const BeamPattern& b = def.beams[p];
    add_beam(p, c.group(i, j, k), c.group(i + b.di, j + b.dj, k + b.dk), -g3);
  }
}

void RadiusScaledVolume::Model::build_hub_classes() const {
  if (per_element) {
    for (const HubShape& h : full_hubs) hubs.push_back({h, 1.0});
    return;
  }
  Context c(lattice);
  const LatticeDefinition& def = c.def;
  const Counts& n = lattice.counts();
  const double g3 = std::pow(c.G.scale(), 3);
  // hub classes, as in lattice_properties (built in parallel)
  struct ClassJob {
    int node;
    IndexClass xi, xj, xk;
    bool i_steady, j_steady;
  };
  std::vector<ClassJob> jobs;
  for (int node = 0; node < static_cast<int>(def.nodes.size()); ++node) {
    const std::vector<Incidence> all = incidences(c, node);
    if (all.size() < 2) continue;
    bool i_steady = true, j_steady = true;
    int reach_i = 0, reach_j = 0, reach_k = 0;
    for (const Incidence& s : all) {
      i_steady = i_steady && c.i_steady(def.beams[s.pattern]);
      j_steady = j_steady && c.j_steady(def.beams[s.pattern]);
      reach_i = std::max(reach_i, std::abs(s.di));
      reach_j = std::max(reach_j, std::abs(s.dj));
      reach_k = std::max(reach_k, std::abs(s.dk));
    }
    i_steady = i_steady && j_steady;
    for (const IndexClass& xi : index_classes(n.u, reach_i, i_steady))
      for (const IndexClass& xj : index_classes(n.v, reach_j, j_steady))
        for (const IndexClass& xk : index_classes(n.w, reach_k, true)) jobs.push_back({node, xi, xj, xk, i_steady, j_steady});
  }
  std::vector<HubClass> classes(jobs.size());
  Progress* const caller = current_progress();
  tbb::parallel_for(std::size_t(0), jobs.size(), [&](std::size_t q) {
    const ProgressScope scope(caller);
    if ((q & 255) == 0) poll_progress();
    const ClassJob& job = jobs[q];
    std::vector<Incidence> present;
    std::vector<SimilarityTransform> other;
    for (const Incidence& s : incidences(c, job.node))
      if (in_lattice(job.xi.first, s.di, n.u) && in_lattice(job.xj.first, s.dj, n.v) && in_lattice(job.xk.first, s.dk, n.w))
        present.push_back(s);
    if (present.size() < 2) return;
    for (const Incidence& s : present)
      other.push_back(c.group(job.i_steady ? s.di : job.xi.first + s.di, job.j_steady ? s.dj : job.xj.first + s.dj, s.dk));
    SimilarityTransform base;
    if (!job.i_steady) base = c.u_pow(job.xi.first);
    if (!job.j_steady) base = c.v_pow(job.xj.first) * base;
    double weight = g3 * scale_cubed_sum(c.W, job.xk.first, job.xk.count);
    if (job.i_steady) weight *= scale_cubed_sum(c.U, job.xi.first, job.xi.count);
    if (job.j_steady) weight *= scale_cubed_sum(c.V, job.xj.first, job.xj.count);
    classes[q] = {hub_shape_at(c, job.node, base, present, other), weight};
  });
  for (HubClass& h : classes)
    if (h.shape.stumps.size() >= 2) hubs.push_back(std::move(h));
  // the hubs around omitted nodes: actual minus generic
  std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t, int>> touched;
  for (const NodeId& id : def.omitted) {
    touched.insert({id.i, id.j, id.k, id.n});
    for (const Incidence& s : incidences(c, id.n)) {
      if (!in_lattice(id.i, s.di, n.u) || !in_lattice(id.j, s.dj, n.v) || !in_lattice(id.k, s.dk, n.w)) continue;
      const BeamPattern& b = def.beams[s.pattern];
      touched.insert({id.i + s.di, id.j + s.dj, id.k + s.dk, s.at_start ? b.to : b.from});
    }
  }
  for (const auto& [i, j, k, node] : touched) {
    const NodeId id{i, j, k, node};
    hubs.push_back({actual_hub(c, id, true), -g3});
    if (lattice.node_exists(id)) hubs.push_back({actual_hub(c, id, false), g3});
  }
}

RadiusScaledVolume::~RadiusScaledVolume() = default;
RadiusScaledVolume::RadiusScaledVolume(RadiusScaledVolume&&) noexcept = default;

double RadiusScaledVolume::max_scale() const { return model_->max_scale; }
std::size_t RadiusScaledVolume::beam_shapes() const { return model_->beams.size(); }
std::size_t RadiusScaledVolume::hub_shapes() const { return model_->full_hubs.size(); }

double RadiusScaledVolume::without_overlaps(double s) const {
  const Model& m = *model_;
  // The solver evaluates the volume some tens of times, each over every distinct shape: polled per range.
  Progress* const caller = current_progress();
  const double beams = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m.beams.size(), 4096), 0.0,
      [&](const tbb::blocked_range<std::size_t>& range, double sum) {
        const ProgressScope scope(caller);
        poll_progress();
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          const BeamShape& b = m.beams[k];
          sum += b.weight * (stump_volume_alone(s * b.node_a, s * b.radius_a, s * b.radius_b, b.length) +
                             stump_volume_alone(s * b.node_b, s * b.radius_b, s * b.radius_a, b.length));
        }
        return sum;
      },
      std::plus<double>());
  return s * s * s * m.balls + beams;
}

bool RadiusScaledVolume::overlaps_at(double s) const {
  const Model& m = *model_;
  Progress* const caller = current_progress();
  return tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m.full_hubs.size(), 64), false,
      [&](const tbb::blocked_range<std::size_t>& range, bool any) {
        const ProgressScope scope(caller);
        poll_progress();
        for (std::size_t k = range.begin(); k != range.end() && !any; ++k) any = any_stump_caps_overlap(m.full_hubs[k], s);
        return any;
      },
      [](bool a, bool b) { return a || b; });
}

double RadiusScaledVolume::operator()(double s) const {
  const Model& m = *model_;
  if (!overlaps_at(s)) return without_overlaps(s);
  std::call_once(m.classes_built, [&m] { m.build_hub_classes(); });
  Progress* const caller = current_progress();
  const double hubs = tbb::parallel_reduce(
      tbb::blocked_range<std::size_t>(0, m.hubs.size(), 16), 0.0,
      [&](const tbb::blocked_range<std::size_t>& range, double sum) {
        const ProgressScope scope(caller);
        for (std::size_t k = range.begin(); k != range.end(); ++k) {
          poll_progress();  // each hub with overlapping caps is an adaptive quadrature
          if (!any_stump_caps_overlap(m.hubs[k].shape, s)) continue;
          HubShape h = m.hubs[k].shape;
          h.radius *= s;
          for (HubStump& st : h.stumps) {
            st.radius *= s;
            st.other_radius *= s;
          }
          sum += m.hubs[k].weight * hub_overlap_correction(h, m.hub_options).volume;
        }
        return sum;
      },
      std::plus<double>());
  return without_overlaps(s) + hubs;
}

namespace {

// Brent's method for f(x) = 0 on [a, b] with f(a) f(b) < 0 (Brent 1973: inverse quadratic interpolation,
// secant steps, bisection whenever they would not shrink the bracket fast enough).
template <class F>
double brent_root(const F& f, double a, double b, double fa, double fb, double tolerance, int* evaluations) {
  double c = a, fc = fa, d = b - a, e = d;
  for (int iteration = 0; iteration < 200; ++iteration) {
    if ((fb > 0.0) == (fc > 0.0)) {
      c = a;
      fc = fa;
      d = e = b - a;
    }
    if (std::abs(fc) < std::abs(fb)) {
      a = b;
      b = c;
      c = a;
      fa = fb;
      fb = fc;
      fc = fa;
    }
    const double tol = 2.0 * std::numeric_limits<double>::epsilon() * std::abs(b) + 0.5 * tolerance;
    const double m = 0.5 * (c - b);
    if (std::abs(m) <= tol || fb == 0.0) return b;
    if (std::abs(e) >= tol && std::abs(fa) > std::abs(fb)) {
      const double s = fb / fa;
      double p, q;
      if (a == c) {
        p = 2.0 * m * s;
        q = 1.0 - s;
      } else {
        const double r = fb / fc, t = fa / fc;
        p = s * (2.0 * m * t * (t - r) - (b - a) * (r - 1.0));
        q = (t - 1.0) * (r - 1.0) * (s - 1.0);
      }
      if (p > 0.0) q = -q; else p = -p;
      if (2.0 * p < std::min(3.0 * m * q - std::abs(tol * q), std::abs(e * q))) {
        e = d;
        d = p / q;
      } else {
        d = m;
        e = m;
      }
    } else {
      d = m;
      e = m;
    }
    a = b;
    fa = fb;
    b += std::abs(d) > tol ? d : (m > 0.0 ? tol : -tol);
    fb = f(b);
    ++*evaluations;
  }
  return b;
}

std::string number(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

}  // namespace

namespace {

// Solves volume(scale) = target for a monotone volume function (Brent on log volume against log scale).
template <class Volume>
double solve_scale(const Volume& volume, double max_scale, double target, double tolerance, int* evaluations) {
  auto g = [&](double x) { return std::log(volume(std::exp(x))) - std::log(target); };
  const double x_max = std::log(max_scale);
  double x0 = 0.0;
  if (std::isfinite(x_max) && x0 > x_max) x0 = x_max - 1e-9;
  double g0 = g(x0);
  ++*evaluations;
  // Bracket from the power-law guess, stepping out until the sign changes.
  double x1 = x0 - g0 / 2.5;
  if (std::isfinite(x_max)) x1 = std::min(x1, x_max);
  double g1 = g(x1);
  ++*evaluations;
  double step = x1 - x0;
  while ((g0 > 0.0) == (g1 > 0.0) && g1 != 0.0) {
    if (std::isfinite(x_max) && x1 >= x_max)
      fail_input("target_volume", number(target) + " is beyond the largest volume the lattice reaches before a node "
                                                   "ball crosses a beam's mid-plane (" +
                                      number(volume(max_scale)) + " at radius scale " + number(max_scale) + ")");
    x0 = x1;
    g0 = g1;
    step *= 2.0;
    x1 = x0 + (step == 0.0 ? (g0 > 0.0 ? -1.0 : 1.0) : step);
    if (std::isfinite(x_max)) x1 = std::min(x1, x_max);
    g1 = g(x1);
    ++*evaluations;
    if (*evaluations > 200) fail_input("target_volume", "could not be bracketed");
  }
  // |g| <= tolerance is the volume's relative tolerance; in x the same (dg/dx is 2 to 3).
  return std::exp(g1 == 0.0 ? x1 : brent_root(g, x0, x1, g0, g1, 0.3 * tolerance, evaluations));
}

}  // namespace

RadiusScaleSolution radius_scale_for_volume(const Lattice& lattice, double target, const RadiusScaleOptions& options) {
  require_positive(target, "target_volume");
  const RadiusScaledVolume volume(lattice, options.hub);
  RadiusScaleSolution out;
  // Balls and beams alone first: exact wherever no hub's stumps overlap, which is checked at the solution
  // (once); only if some do is the search repeated with the overlap corrections (quadrature) included.
  out.scale = solve_scale([&](double s) { return volume.without_overlaps(s); }, volume.max_scale(), target,
                          options.relative_tolerance, &out.evaluations);
  if (volume.overlaps_at(out.scale)) {
    out.scale = solve_scale(volume, volume.max_scale(), target, options.relative_tolerance, &out.evaluations);
    out.volume = volume(out.scale);
  } else {
    out.volume = volume.without_overlaps(out.scale);
  }
  if (options.check_clean) {
    Progress* const caller = current_progress();
    const HubOverlapReport report =
        check_hub_overlaps(with_radius_scale(lattice, out.scale), 5, caller ? *caller : no_progress());
    if (report.overlap_count > 0)
      fail_input("target_volume", number(target) + " needs radius scale " + number(out.scale) +
                                      ", where the lattice is not clean: " + report.describe(3));
    out.clean_verified = report.verified;
  }
  return out;
}

RadiusScaleSolution radius_scale_for_density(const Lattice& lattice, double relative_density, double envelope,
                                             const RadiusScaleOptions& options) {
  require_positive(relative_density, "relative_density");
  require_positive(envelope, "envelope_volume");
  if (relative_density > 1.0) fail_input("relative_density", "must be at most 1 (got " + number(relative_density) + ")");
  return radius_scale_for_volume(lattice, relative_density * envelope, options);
}

RadiusScaleSolution radius_scale_for_mass(const Lattice& lattice, double mass, double density,
                                          const RadiusScaleOptions& options) {
  require_positive(mass, "mass");
  require_positive(density, "density");
  return radius_scale_for_volume(lattice, mass / density, options);
}

double cell_envelope_volume(const Lattice& lattice) {
  const Lattice* brick_lattice = lattice.brick_lattice();
  if (!brick_lattice)
    fail_input("lattice", "its layout (" + lattice.layout().kind() + ") has no cell: give the envelope volume of a body "
                          "instead");
  const SteadyBrick& brick = *brick_lattice->layout().steady_brick();
  const Similarity &U = brick.steps[0], &V = brick.steps[1], &W = brick.steps[2];
  const LatticeDefinition& d = lattice.definition();
  Vec3 o(0.0);
  for (const TemplateNode& n : d.nodes) o += n.center;
  o /= static_cast<double>(d.nodes.size());
  const Vec3 a = U.apply_point(o) - o, b = V.apply_point(o) - o, c = W.apply_point(o) - o;
  const double cell = std::abs(glm::dot(a, glm::cross(b, c)));
  const double scale = std::max({glm::length(a), glm::length(b), glm::length(c)});
  if (!(cell > 1e-12 * scale * scale * scale))
    fail_input("lattice", "its steps U, V, W span no volume (a direction without a step?): give the envelope volume "
                          "of a body instead");
  const Counts& n = brick_lattice->counts();
  return std::pow(brick.placement.scale(), 3) * cell * scale_cubed_sum(U, 0, n.u) * scale_cubed_sum(V, 0, n.v) *
         scale_cubed_sum(W, 0, n.w);
}

}  // namespace steady
