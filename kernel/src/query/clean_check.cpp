#include "steady/query/clean_check.hpp"

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

#include "steady/core/errors.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/broad_phase.hpp"
#include "steady/lattice/convex_distance.hpp"
#include "steady/core/progress.hpp"

namespace steady {

const char* to_string(CleanIssueKind kind) {
  switch (kind) {
    case CleanIssueKind::CircleOverlap: return "circle_overlap";
    case CleanIssueKind::BallBall: return "ball_ball";
    case CleanIssueKind::BallBeam: return "ball_beam";
    case CleanIssueKind::BeamBeam: return "beam_beam";
  }
  return "?";
}

std::string CleanIssue::describe() const {
  std::ostringstream os;
  switch (kind) {
    case CleanIssueKind::CircleOverlap:
      os << "on ball " << ball << ", the exit circles of beams " << beam << " and " << other_beam << " meet";
      break;
    case CleanIssueKind::BallBall: os << "balls " << ball << " and " << other_ball << " meet"; break;
    case CleanIssueKind::BallBeam: os << "ball " << ball << " meets beam " << beam << ", which is not incident to it"; break;
    case CleanIssueKind::BeamBeam: os << "beams " << beam << " and " << other_beam << " meet"; break;
  }
  return os.str();
}

namespace {

// An exit cap on a node sphere: unit direction of its center from the node center, and its angular radius.
struct Cap {
  Vec3 direction{0.0};
  double angle = 0.0;
};

Cap exit_cap(const Ball& node, const Circle& circle) {
  const Vec3 offset = circle.center - node.center;
  const double x = glm::dot(offset, circle.normal);  // signed: the circle may lie behind the center
  return {circle.normal, std::atan2(circle.radius, x)};
}

double angle_between(const Vec3& a, const Vec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b));
}

// Distance from a point to the frustum between the disks of a beam, in closed form: the frustum's half
// meridian section is the trapezoid (0,0) (h,0) (h,r1) (0,r0) in (axial, radial) coordinates.
double point_frustum_distance(const Vec3& p, const BeamFrustum& f) {
  const Vec3 axis = f.cone.axis;
  const Vec3 rel = p - f.circle_a.center;
  const double x = glm::dot(rel, axis);
  const double rho = glm::length(rel - x * axis);
  const double h = glm::dot(f.circle_b.center - f.circle_a.center, axis);
  const double r0 = f.circle_a.radius, r1 = f.circle_b.radius;
  const Vec2 q(x, rho);
  // Inside: between the planes and under the slanted side.
  const Vec2 s0(0.0, r0), s1(h, r1);
  const Vec2 side = s1 - s0;
  const double cross = side.x * (q.y - s0.y) - side.y * (q.x - s0.x);  // > 0: above the slanted side
  if (x >= 0.0 && x <= h && cross <= 0.0) return 0.0;
  auto segment_distance = [&](const Vec2& a, const Vec2& b) {
    const Vec2 ab = b - a;
    const double t = std::clamp(glm::dot(q - a, ab) / glm::dot(ab, ab), 0.0, 1.0);
    return glm::length(q - (a + t * ab));
  };
  return std::min({segment_distance(Vec2(0.0, 0.0), s0), segment_distance(s0, s1),
                   segment_distance(s1, Vec2(h, 0.0))});
}

double frustum_scale(const BeamFrustum& f) { return std::min(f.circle_a.radius, f.circle_b.radius); }

Box disk_box(const Circle& c) {
  const Vec3 n = c.normal;
  const Vec3 e(c.radius * std::sqrt(std::max(0.0, 1.0 - n.x * n.x)), c.radius * std::sqrt(std::max(0.0, 1.0 - n.y * n.y)),
               c.radius * std::sqrt(std::max(0.0, 1.0 - n.z * n.z)));
  return {c.center - e, c.center + e};
}

struct Elements {
  std::vector<BeamFrustum> frustums;
  std::vector<char> absorbed;  // per ball
};

Elements prepare(const FlatLattice& f, CleanReport& report) {
  Elements el;
  el.frustums = beam_frustums(f);
  for (std::int64_t e = 0; e < f.beam_count(); ++e)
    if (!el.frustums[e].exists) report.degenerate_beams.push_back(e);
  el.absorbed = absorbed_balls(f, el.frustums);
  for (std::int64_t i = 0; i < f.ball_count(); ++i)
    if (el.absorbed[i]) report.absorbed_balls.push_back(i);
  return el;
}

void check_caps(const FlatLattice& f, const Elements& el, std::int64_t ball, std::vector<CleanIssue>& out) {
  if (el.absorbed[ball]) return;
  std::vector<std::pair<std::int64_t, Cap>> caps;
  for (const std::int64_t* e = f.incident_begin(ball); e != f.incident_end(ball); ++e) {
    const BeamFrustum& fr = el.frustums[*e];
    if (!fr.exists) continue;
    caps.emplace_back(*e, exit_cap(f.balls[ball], f.beams[*e].a == ball ? fr.circle_a : fr.circle_b));
  }
  for (std::size_t s = 0; s < caps.size(); ++s)
    for (std::size_t t = s + 1; t < caps.size(); ++t) {
      const double gap = angle_between(caps[s].second.direction, caps[t].second.direction) - caps[s].second.angle -
                         caps[t].second.angle;
      if (gap < kCleanAngularGap) {
        CleanIssue issue;
        issue.kind = CleanIssueKind::CircleOverlap;
        issue.ball = ball;
        issue.beam = std::min(caps[s].first, caps[t].first);
        issue.other_beam = std::max(caps[s].first, caps[t].first);
        out.push_back(issue);
      }
    }
}

// Exact test of two elements: element ids below ball_count are balls, the rest beams (id - ball_count).
// closed_form: ball-beam distances in closed form (the fast path) or by GJK with the ball's support map (the twin).
void check_pair(const FlatLattice& f, const Elements& el, std::int64_t x, std::int64_t y, std::vector<CleanIssue>& out,
                bool closed_form = true) {
  const std::int64_t nb = f.ball_count();
  if (x > y) std::swap(x, y);
  if (y < nb) {  // ball - ball
    const Ball &a = f.balls[x], &b = f.balls[y];
    if (el.absorbed[x] || el.absorbed[y]) return;
    const double gap = glm::length(a.center - b.center) - a.radius - b.radius;
    if (gap < kCleanRelativeGap * std::min(a.radius, b.radius)) {
      CleanIssue issue;
      issue.kind = CleanIssueKind::BallBall;
      issue.ball = x;
      issue.other_ball = y;
      out.push_back(issue);
    }
    return;
  }
  if (x < nb) {  // ball - beam
    const std::int64_t e = y - nb;
    const FlatBeam& b = f.beams[e];
    if (b.a == x || b.b == x || el.absorbed[x] || !el.frustums[e].exists) return;
    const Ball& ball = f.balls[x];
    const BeamFrustum& fr = el.frustums[e];
    const double limit = kCleanRelativeGap * std::min(ball.radius, frustum_scale(fr));
    bool meets = false;
    if (closed_form) {
      meets = point_frustum_distance(ball.center, fr) - ball.radius < limit;
    } else {
      const DistanceBounds d = convex_distance(
          [&](const Vec3& v) { return ball.center + ball.radius * v / glm::length(v); },
          [&](const Vec3& v) { return disk_hull_support(fr.circle_a, fr.circle_b, v); }, limit, limit);
      meets = !(d.lower > limit);
    }
    if (meets) {
      CleanIssue issue;
      issue.kind = CleanIssueKind::BallBeam;
      issue.ball = x;
      issue.beam = e;
      out.push_back(issue);
    }
    return;
  }
  // beam - beam
  const std::int64_t e1 = x - nb, e2 = y - nb;
  const FlatBeam &b1 = f.beams[e1], &b2 = f.beams[e2];
  if (b1.a == b2.a || b1.a == b2.b || b1.b == b2.a || b1.b == b2.b) return;  // covered by the caps
  const BeamFrustum &f1 = el.frustums[e1], &f2 = el.frustums[e2];
  if (!f1.exists || !f2.exists) return;
  const double gap = kCleanRelativeGap * std::min(frustum_scale(f1), frustum_scale(f2));
  const DistanceBounds d = convex_distance([&](const Vec3& v) { return disk_hull_support(f1.circle_a, f1.circle_b, v); },
                                           [&](const Vec3& v) { return disk_hull_support(f2.circle_a, f2.circle_b, v); },
                                           gap, gap);
  if (!(d.lower > gap)) {
    CleanIssue issue;
    issue.kind = CleanIssueKind::BeamBeam;
    issue.beam = e1;
    issue.other_beam = e2;
    out.push_back(issue);
  }
}

std::vector<Box> element_boxes(const FlatLattice& f, const Elements& el) {
  const std::int64_t nb = f.ball_count();
  std::vector<Box> boxes(nb + f.beam_count());
  Progress* const caller = current_progress();  // 7 s for 3 * 10^7 elements on a loaded machine: polled
  tbb::parallel_for(std::int64_t(0), static_cast<std::int64_t>(boxes.size()), [&](std::int64_t id) {
    const ProgressScope scope(caller);
    if ((id & 4095) == 0) poll_progress();
    if (id < nb) {
      const Ball& b = f.balls[id];
      const double pad = b.radius * (1.0 + 2.0 * kCleanRelativeGap);
      boxes[id] = {b.center - Vec3(pad), b.center + Vec3(pad)};
      if (el.absorbed[id]) boxes[id] = {b.center, b.center};  // tested through the ball containing it
      return;
    }
    const BeamFrustum& fr = el.frustums[id - nb];
    if (!fr.exists) {
      boxes[id] = {f.balls[f.beams[id - nb].a].center, f.balls[f.beams[id - nb].a].center};
      return;
    }
    const Box a = disk_box(fr.circle_a), b = disk_box(fr.circle_b);
    const Vec3 pad(2.0 * kCleanRelativeGap * std::max(fr.circle_a.radius, fr.circle_b.radius));
    boxes[id] = {glm::min(a.lo, b.lo) - pad, glm::max(a.hi, b.hi) + pad};
  });
  return boxes;
}

void finish(CleanReport& report, std::vector<CleanIssue>& issues, std::int64_t max_reported) {
  auto key = [](const CleanIssue& i) { return std::make_tuple(int(i.kind), i.ball, i.other_ball, i.beam, i.other_beam); };
  std::sort(issues.begin(), issues.end(), [&](const CleanIssue& a, const CleanIssue& b) { return key(a) < key(b); });
  issues.erase(std::unique(issues.begin(), issues.end(), [&](const CleanIssue& a, const CleanIssue& b) { return key(a) == key(b); }),
               issues.end());
  report.issue_count = static_cast<std::int64_t>(issues.size());
  if (static_cast<std::int64_t>(issues.size()) > max_reported) issues.resize(max_reported);
  report.issues = std::move(issues);
}

}  // namespace

std::vector<char> absorbed_balls(const FlatLattice& f, const std::vector<BeamFrustum>& frustums) {
  std::vector<char> absorbed(f.ball_count(), 0);
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    if ((i & 4095) == 0) poll_progress();  // serial over every ball: a second per 10^7
    if (f.degree(i) == 0) continue;
    bool all_degenerate = true, contained = false;
    for (const std::int64_t* e = f.incident_begin(i); e != f.incident_end(i); ++e) {
      if (frustums[*e].exists) {
        all_degenerate = false;
        break;
      }
      const std::int64_t j = f.other_ball(*e, i);
      const Ball& me = f.balls[i];
      const Ball& other = f.balls[j];
      const double d = glm::length(me.center - other.center);
      const bool in_other = d + me.radius <= other.radius * (1.0 + kCleanRelativeGap);
      // Two balls that contain each other (coincident): the one with the lower index stays, so that one of
      // them is built and not both dropped.
      const bool mutual = d + other.radius <= me.radius * (1.0 + kCleanRelativeGap);
      if (in_other && !(mutual && j > i)) contained = true;
    }
    absorbed[i] = all_degenerate && contained;
  }
  return absorbed;
}

CleanReport check_clean(const FlatLattice& f, const CleanCheckOptions& options) {
  if (options.max_reported < 0)
    fail_input("max_reported", "must be >= 0 (got " + std::to_string(options.max_reported) + ")");
  CleanReport report;
  const Elements el = prepare(f, report);
  tbb::enumerable_thread_specific<std::vector<CleanIssue>> found;
  // Seconds per million elements: cancellable (Ctrl-C) through the caller's current progress.
  Progress* const caller = current_progress();
  if (!options.skip_circle_overlaps)
    tbb::parallel_for(std::int64_t(0), f.ball_count(), [&](std::int64_t i) {
      const ProgressScope scope(caller);
      if ((i & 1023) == 0) poll_progress();
      check_caps(f, el, i, found.local());
    });
  poll_progress();
  const auto pairs = overlapping_box_pairs(element_boxes(f, el));
  report.candidate_pairs = static_cast<std::int64_t>(pairs.size());
  tbb::parallel_for(std::size_t(0), pairs.size(), [&](std::size_t p) {
    const ProgressScope scope(caller);
    if ((p & 1023) == 0) poll_progress();
    check_pair(f, el, pairs[p].first, pairs[p].second, found.local());
  });
  std::vector<CleanIssue> issues;
  for (auto& v : found) issues.insert(issues.end(), v.begin(), v.end());
  finish(report, issues, options.max_reported);
  return report;
}

CleanReport check_clean(const Lattice& lattice, const CleanCheckOptions& options) {
  if (options.max_reported < 0)  // before flattening the lattice
    fail_input("max_reported", "must be >= 0 (got " + std::to_string(options.max_reported) + ")");
  return check_clean(flatten(lattice), options);
}

CleanReport check_clean_brute_force(const FlatLattice& f) {
  CleanReport report;
  const Elements el = prepare(f, report);
  std::vector<CleanIssue> issues;
  for (std::int64_t i = 0; i < f.ball_count(); ++i) check_caps(f, el, i, issues);
  const std::int64_t n = f.ball_count() + f.beam_count();
  for (std::int64_t x = 0; x < n; ++x)
    for (std::int64_t y = x + 1; y < n; ++y) check_pair(f, el, x, y, issues, false);
  report.candidate_pairs = n * (n - 1) / 2;
  finish(report, issues, std::numeric_limits<std::int64_t>::max());
  return report;
}

void require_clean_for_build(const FlatLattice& lattice) {
  CleanCheckOptions options;
  options.skip_circle_overlaps = true;
  const CleanReport report = check_clean(lattice, options);
  if (report.clean()) return;
  std::ostringstream os;
  os << "is not clean (" << report.issue_count << " issue" << (report.issue_count == 1 ? "" : "s") << "): ";
  for (std::size_t i = 0; i < std::min<std::size_t>(3, report.issues.size()); ++i)
    os << (i ? "; " : "") << report.issues[i].describe();
  if (report.issue_count > 3) os << "; ...";
  fail_input("lattice", os.str());
}

}  // namespace steady
