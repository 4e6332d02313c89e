// Dissertation Table 7.2 / RangeFinder section 7.3: 100 random ball-interference queries (centers uniform
// in the lattice's bounding box, radii 90-110% of the mean ball radius), single thread, on the three
// benchmark lattices (bench_lattices.hpp), naive against every accelerated path that applies, in one run.
// Times are medians of repeats; every path must return the same elements as the naive one.
#include <cstdio>

#include "bench_lattices.hpp"
#include "steady/query/lattice_query.hpp"

using namespace bench;

namespace {

struct PaperRow {
  const char* lattice;
  double naive, uv, u, one;  // seconds per 100 BIQs, dissertation Table 7.2 (-1: not applicable)
};

long hits_of(const LatticeQuery& lq, const std::vector<Ball>& queries, QueryMethod m) {
  long h = 0;
  for (const Ball& q : queries) {
    const BallQueryResult r = lq.query_ball(q, m);
    h += static_cast<long>(r.balls.size() + r.beams.size());
  }
  return h;
}

void run(const char* name, const Lattice& lat, const PaperRow& paper, int repeats_naive, int repeats_fast) {
  const LatticeQuery lq(lat);
  const std::vector<Ball> queries = paper_queries(lat, 100, 42);
  std::printf("\n%s: %lld x %lld x %lld groups, %lld balls, %lld beams\n  plan: %s\n", name,
              static_cast<long long>(lat.counts().u), static_cast<long long>(lat.counts().v),
              static_cast<long long>(lat.counts().w), static_cast<long long>(lat.ball_count()),
              static_cast<long long>(lat.beam_count()), lq.plan().describe().c_str());
  long naive_hits = 0;
  const double naive = median_thread_cpu_seconds(repeats_naive, [&] { naive_hits = hits_of(lq, queries, QueryMethod::Naive); });
  std::printf("  %-34s %11s %10s %9s %6s %14s %9s\n", "method (100 BIQs, 1 thread)", "seconds", "us/query",
              "speed-up", "hits", "paper seconds", "paper x");
  std::printf("  %-34s %11.4f %10.1f %9s %6ld %14.4g %9s\n", "naive O(uvw)", naive, 1e4 * naive, "1x", naive_hits,
              paper.naive, "1x");
  struct Path {
    const char* label;
    QueryMethod method;
    double paper_seconds;
  };
  const Path paths[] = {{"rows O(uv), the paper's", QueryMethod::PaperRows, paper.uv},
                        {"rows O(uv) + row rejection", QueryMethod::Rows, paper.uv},
                        {"slabs O(u), the paper's", QueryMethod::PaperSlabs, paper.u},
                        {"slabs O(u) + slab rejection", QueryMethod::Slabs, paper.u},
                        {"constant O(1)", QueryMethod::Constant, paper.one},
                        {"blocks (hierarchical, any brick)", QueryMethod::Blocks, -1}};
  for (const Path& p : paths) {
    if ((p.method == QueryMethod::Slabs || p.method == QueryMethod::PaperSlabs) && !lq.plan().slabs_valid) continue;
    if (p.method == QueryMethod::Constant && !lq.plan().constant_valid) continue;
    long hits = 0;
    const double t = median_thread_cpu_seconds(repeats_fast, [&] { hits = hits_of(lq, queries, p.method); });
    char paper_x[32] = "-", paper_s[32] = "-", ours_x[32];
    if (p.paper_seconds > 0) {
      std::snprintf(paper_s, sizeof paper_s, "%.4g", p.paper_seconds);
      std::snprintf(paper_x, sizeof paper_x, "%.0fx", paper.naive / p.paper_seconds);
    }
    std::snprintf(ours_x, sizeof ours_x, "%.0fx", naive / t);
    std::printf("  %-34s %11.6f %10.2f %9s %6ld %14s %9s%s\n", p.label, t, 1e4 * t, ours_x, hits, paper_s, paper_x,
                hits == naive_hits ? "" : "   MISMATCH");
  }
}

}  // namespace

int main(int argc, char** argv) {
  const bool long_run = has_flag(argc, argv, "--long");
  std::printf("Ball-interference queries: this machine vs dissertation Table 7.2 (i7-7700K, Java, 1 thread).\n"
              "Times are CPU seconds of the querying thread (other processes sharing the cores do not inflate\n"
              "them), medians of repeats (the naive scan is repeated only with --long); speed-ups are against\n"
              "the naive scan measured in this run. Load average: %s\n",
              load_average().c_str());
  const int rn = long_run ? 3 : 1, rf = long_run ? 9 : 5;
  run("regular BCC", regular_fine(), {"regular", 55.2, 1.60, 0.0558, 0.00586}, rn, rf);
  run("cylindrical BCC", cylindrical_fine(), {"cylindrical", 259, 2.72, 0.0554, -1}, rn, rf);
  run("bent-twisted-tapered", bent_twisted_tapered(), {"fig 7.10", 167, 3.68, -1, -1}, rn, rf);
  return 0;
}
