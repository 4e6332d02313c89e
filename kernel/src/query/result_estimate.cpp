// How large a ball-interference result will be, before any element is visited: the up-front memory check of
// query_ball (a huge radius on a 10^9-element lattice once ran for minutes and ended in std::bad_alloc).
//
// The estimate is a lower bound (elements the query surely meets), so a refusal is never wrong: a query ball
// holding the lattice's bound meets every element; otherwise index blocks whose balls' bound lies inside the
// query ball contribute all their balls and the beams that start there (a beam touches its start ball, so it
// meets the query too). Blocks are refined breadth first up to kEstimateBlocks bounds, well under a millisecond.
#include <deque>

#include "query/query_internal.hpp"

namespace steady::detail {

namespace {
constexpr std::int64_t kEstimateBlocks = 4096;

// Balls and beams that start in a block (before omissions).
std::int64_t elements_of(const QueryState& q, const IndexBlock& b) {
  std::int64_t n = b.groups() * q.lattice.node_count();
  for (const IndexBlock& starts : q.pattern_starts) n += intersect(b, starts).groups();
  return n;
}

// Elements of the groups whose balls are surely inside `query` (before omissions), refined breadth first.
std::int64_t elements_surely_inside(const QueryState& q, const Ball& query) {
  const Counts& c = q.lattice.counts();
  const Ball& templ = q.bounds->template_bound();
  std::int64_t sure = 0, visited = 0;
  std::deque<IndexBlock> queue{IndexBlock{0, c.u, 0, c.v, 0, c.w}};
  while (!queue.empty() && visited++ < kEstimateBlocks) {
    const IndexBlock b = queue.front();
    queue.pop_front();
    const Ball bound = q.bounds->bound(templ.center, templ.radius, b).ball;
    const double d = glm::length(bound.center - query.center);
    if (d - bound.radius > query.radius) continue;
    if (d + bound.radius <= query.radius) {
      sure += elements_of(q, b);
      continue;
    }
    const std::int64_t len[3] = {b.i1 - b.i0, b.j1 - b.j0, b.k1 - b.k0};
    const int axis = len[0] >= len[1] && len[0] >= len[2] ? 0 : (len[1] >= len[2] ? 1 : 2);
    if (len[axis] < 2) continue;
    IndexBlock lo = b, hi = b;
    if (axis == 0) lo.i1 = hi.i0 = b.i0 + len[0] / 2;
    if (axis == 1) lo.j1 = hi.j0 = b.j0 + len[1] / 2;
    if (axis == 2) lo.k1 = hi.k0 = b.k0 + len[2] / 2;
    queue.push_back(lo);
    queue.push_back(hi);
  }
  return sure;
}
}  // namespace

std::int64_t elements_surely_hit(const QueryState& q, const Ball& query) {
  const Lattice& lat = q.lattice;
  if (glm::length(q.bound.center - query.center) + q.bound.radius <= query.radius)
    return lat.ball_count() + lat.beam_count();
  if (!q.bounds) return 0;
  // Every omitted node may be one of the sure balls, and take a beam of each pattern end with it.
  const std::int64_t omitted = lat.counts().groups() * lat.node_count() - lat.ball_count();
  const std::int64_t per_omission = 1 + 2 * static_cast<std::int64_t>(q.pattern_starts.size());
  return std::max<std::int64_t>(0, elements_surely_inside(q, query) - omitted * per_omission);
}

}  // namespace steady::detail
