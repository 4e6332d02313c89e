// Clean check: the grid broad phase plus exact tests against the brute-force twin (all pairs, exact tests), and
// the grid alone up to 10^5 beams (10^6 with --long). Medians of repeats; both measured in this run.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "steady/query/clean_check.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "brick_definition.hpp"

using namespace steady;

namespace {

// A gently swirled cubic strut lattice with n^3 groups (about 3 n^3 beams), clean.
Lattice cubic(std::int64_t n) {
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, 0.25}};
  d.beams = {{0, 1, 0, 0, 0, 0.1, 0.1}, {0, 0, 1, 0, 0, 0.1, 0.12}, {0, 0, 0, 1, 0, 0.12, 0.1}};
  d.counts = {n, n, n};
  d.u = {Similarity::swirl(0.01, {0, 0, 1}, {0, -100, 0}, 1.001)};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  return Lattice(std::move(d));
}

template <class F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  const bool long_run = argc > 1 && std::strcmp(argv[1], "--long") == 0;
  std::printf("%8s %10s %10s %12s %12s %10s %8s\n", "beams", "balls", "pairs", "grid [s]", "brute [s]", "ratio", "clean");
  for (std::int64_t n : {7, 10, 14}) {
    const FlatLattice f = flatten(cubic(n));
    CleanReport fast, slow;
    const double tf = median_seconds(3, [&] { fast = check_clean(f); });
    const double ts = median_seconds(1, [&] { slow = check_clean_brute_force(f); });
    std::printf("%8lld %10lld %10lld %12.4f %12.4f %9.0fx %8s%s\n", (long long)f.beam_count(), (long long)f.ball_count(),
                (long long)fast.candidate_pairs, tf, ts, ts / tf, fast.clean() ? "yes" : "no",
                fast.issue_count == slow.issue_count ? "" : "  MISMATCH");
  }
  std::vector<std::int64_t> sizes = {22, 32, 47};
  if (long_run) sizes.push_back(70);
  std::vector<double> xs, ys;
  for (std::int64_t n : sizes) {
    const FlatLattice f = flatten(cubic(n));
    CleanReport r;
    const double t = median_seconds(3, [&] { r = check_clean(f); });
    std::printf("%8lld %10lld %10lld %12.4f %12s %10s %8s\n", (long long)f.beam_count(), (long long)f.ball_count(),
                (long long)r.candidate_pairs, t, "-", "-", r.clean() ? "yes" : "no");
    xs.push_back(std::log(double(f.beam_count())));
    ys.push_back(std::log(t));
  }
  double mx = 0, my = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    mx += xs[i] / xs.size();
    my += ys[i] / ys.size();
  }
  double sxy = 0, sxx = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    sxy += (xs[i] - mx) * (ys[i] - my);
    sxx += (xs[i] - mx) * (xs[i] - mx);
  }
  std::printf("growth exponent of the grid check (least squares on log-log): %.2f\n", sxy / sxx);
}
