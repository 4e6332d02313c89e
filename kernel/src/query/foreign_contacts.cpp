#include "query/foreign_contacts.hpp"

#include <algorithm>
#include <limits>
#include <sstream>

#include "steady/query/clean_check.hpp"

namespace steady {

ForeignContacts foreign_contacts(const FlatLattice& f) {
  CleanCheckOptions options;
  options.skip_circle_overlaps = true;
  options.max_reported = std::numeric_limits<std::int64_t>::max();  // every contact joins hubs
  const CleanReport report = check_clean(f, options);
  ForeignContacts out;
  out.issue_count = report.issue_count;
  out.involved.assign(f.beam_count(), 0);
  auto beam_balls = [&](std::int64_t e) {
    out.involved[e] = 1;
    out.joined.emplace_back(f.beams[e].a, f.beams[e].b);
    return f.beams[e].a;
  };
  for (const CleanIssue& issue : report.issues) {
    switch (issue.kind) {
      case CleanIssueKind::BallBall: out.joined.emplace_back(issue.ball, issue.other_ball); break;
      case CleanIssueKind::BallBeam: out.joined.emplace_back(issue.ball, beam_balls(issue.beam)); break;
      case CleanIssueKind::BeamBeam: out.joined.emplace_back(beam_balls(issue.beam), beam_balls(issue.other_beam)); break;
      case CleanIssueKind::CircleOverlap: break;
    }
  }
  // A beam in many contacts was listed once per contact: each pair once is enough for every join.
  for (auto& [a, b] : out.joined)
    if (b < a) std::swap(a, b);
  std::sort(out.joined.begin(), out.joined.end());
  out.joined.erase(std::unique(out.joined.begin(), out.joined.end()), out.joined.end());
  std::ostringstream os;
  for (std::size_t i = 0; i < std::min<std::size_t>(3, report.issues.size()); ++i)
    os << (i ? "; " : "") << report.issues[i].describe();
  if (report.issue_count > 3) os << "; ...";
  out.description = os.str();
  return out;
}

}  // namespace steady
