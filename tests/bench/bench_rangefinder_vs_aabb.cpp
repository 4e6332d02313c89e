// The honest trade-off against a bounding-volume hierarchy: CGAL's AABB tree over the explicit balls and
// beams (one axis-aligned box per element, the query ball's box as the query, then the same exact
// tests) against the implicit queries (no element stored). Build time, memory (resident set growth)
// and time per ball-interference query, on the same 100 random queries. The default run uses a 60^3
// bent-twisted-tapered lattice and a 40^3 regular one; --long the papers' 100^3 and 75^3.
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <cstdio>
#include <fstream>
#include <unistd.h>

#include "bench_lattices.hpp"
#include "steady/query/interference.hpp"
#include "steady/query/lattice_query.hpp"

using namespace bench;
using K = CGAL::Exact_predicates_inexact_constructions_kernel;

namespace {

// One lattice element as a box: its index (balls first, then beams after ball_count) and bounding box.
struct ElementBox {
  using Id = std::int64_t;
  using Point = K::Point_3;
  using Datum = K::Iso_cuboid_3;
  Id index = 0;
  Datum box;
  ElementBox() = default;
  ElementBox(Id i, const Datum& b) : index(i), box(b) {}
  template <class Iterator>
  explicit ElementBox(Iterator it) : index(it->index), box(it->box) {}
  Id id() const { return index; }
  const Datum& datum() const { return box; }
  Point reference_point() const { return box.min(); }
};
using Traits = CGAL::AABB_traits<K, ElementBox>;
using Tree = CGAL::AABB_tree<Traits>;

double resident_mb() {
  std::ifstream f("/proc/self/statm");
  long pages = 0, resident = 0;
  f >> pages >> resident;
  return static_cast<double>(resident) * static_cast<double>(sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

K::Iso_cuboid_3 box_of(const Vec3& lo, const Vec3& hi) { return {K::Point_3(lo.x, lo.y, lo.z), K::Point_3(hi.x, hi.y, hi.z)}; }

void run(const char* name, const Lattice& lat) {
  const std::vector<Ball> queries = paper_queries(lat, 100, 7);
  std::printf("\n%s: %lld balls, %lld beams\n", name, static_cast<long long>(lat.ball_count()),
              static_cast<long long>(lat.beam_count()));
  // --- implicit ---
  const double mem0 = resident_mb();
  auto t0 = std::chrono::steady_clock::now();
  const LatticeQuery lq(lat);
  const double implicit_build = seconds_since(t0);
  const double implicit_mem = resident_mb() - mem0;
  long implicit_hits = 0;
  const double implicit_query = median_thread_cpu_seconds(5, [&] {
    implicit_hits = 0;
    for (const Ball& q : queries) {
      const BallQueryResult r = lq.query_ball(q);
      implicit_hits += static_cast<long>(r.balls.size() + r.beams.size());
    }
  });
  // --- explicit elements and CGAL's AABB tree ---
  const double mem1 = resident_mb();
  t0 = std::chrono::steady_clock::now();
  const std::int64_t nb = lat.ball_count(), ne = lat.beam_count();
  std::vector<double> centers(3 * static_cast<std::size_t>(nb)), radii(static_cast<std::size_t>(nb));
  lat.balls(centers.data(), radii.data());
  std::vector<std::int64_t> a(static_cast<std::size_t>(ne)), b(static_cast<std::size_t>(ne));
  std::vector<double> ra(static_cast<std::size_t>(ne)), rb(static_cast<std::size_t>(ne));
  lat.beams(a.data(), b.data(), ra.data(), rb.data());
  auto center = [&](std::int64_t x) { return Vec3(centers[3 * x], centers[3 * x + 1], centers[3 * x + 2]); };
  std::vector<ElementBox> boxes;
  boxes.reserve(static_cast<std::size_t>(nb + ne));
  for (std::int64_t x = 0; x < nb; ++x) boxes.emplace_back(x, box_of(center(x) - Vec3(radii[x]), center(x) + Vec3(radii[x])));
  for (std::int64_t x = 0; x < ne; ++x) {
    const Vec3 p = center(a[x]), q = center(b[x]);
    boxes.emplace_back(nb + x, box_of(glm::min(p - Vec3(ra[x]), q - Vec3(rb[x])), glm::max(p + Vec3(ra[x]), q + Vec3(rb[x]))));
  }
  const double listing = seconds_since(t0);
  t0 = std::chrono::steady_clock::now();
  Tree tree(boxes.begin(), boxes.end());
  tree.build();
  const double tree_build = seconds_since(t0);
  const double explicit_mem = resident_mb() - mem1;
  long tree_hits = 0;
  std::vector<std::int64_t> found;
  const double tree_query = median_thread_cpu_seconds(5, [&] {
    tree_hits = 0;
    for (const Ball& q : queries) {
      found.clear();
      tree.all_intersected_primitives(box_of(q.center - Vec3(q.radius), q.center + Vec3(q.radius)), std::back_inserter(found));
      for (std::int64_t x : found) {
        const bool hit = x < nb ? ball_meets_ball(q, Ball{center(x), radii[x]})
                                : ball_meets_beam(q, BeamGeometry{{center(a[x - nb]), ra[x - nb]}, {center(b[x - nb]), rb[x - nb]}});
        tree_hits += hit;
      }
    }
  });
  std::printf("  %-34s %12s %12s %16s %8s\n", "", "build s", "memory MB", "per query us", "hits");
  std::printf("  %-34s %12.4f %12.1f %16.2f %8ld   (method %s)\n", "implicit (LatticeQuery, auto)", implicit_build,
              implicit_mem, 1e6 * implicit_query / queries.size(), implicit_hits, to_string(lq.plan().automatic));
  std::printf("  %-34s %12.4f %12.1f %16.2f %8ld%s\n", "CGAL AABB tree over element boxes", listing + tree_build,
              explicit_mem, 1e6 * tree_query / queries.size(), tree_hits,
              tree_hits == implicit_hits ? "" : "   MISMATCH");
  std::printf("  (tree build %.3f s after listing the elements in %.3f s)\n", tree_build, listing);
  const double per_query_gain = tree_query - implicit_query;
  if (per_query_gain > 0)
    std::printf("  the implicit query is faster per query; the tree never pays back its build\n");
  else
    std::printf("  the tree pays back its build after %.0f queries\n",
                (listing + tree_build - implicit_build) / (-per_query_gain / queries.size()));
}

}  // namespace

int main(int argc, char** argv) {
  const bool long_run = has_flag(argc, argv, "--long");
  std::printf("Implicit ball-interference queries vs CGAL's AABB tree over the explicit elements (1 thread;\n"
              "query times are CPU seconds of the thread, build times wall seconds). Load average: %s\n",
              load_average().c_str());
  run("bent-twisted-tapered", bent_twisted_tapered(long_run ? 100 : 60));
  run("regular BCC", regular_fine(long_run ? 75 : 40));
  return 0;
}
