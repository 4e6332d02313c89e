#pragma once
// The papers' benchmark lattices (RangeFinder section 7, dissertation Table 7.2) with the parameters the
// papers do not publish chosen here (spacing 1, ball radii ~ 0.1 of a cell):
//   regular      75^3 groups, body-centred cubic: 2 balls, 14 beam patterns, translations
//   cylindrical  32 x 128 x 128 groups, the same template: U a dilation about a point of the axis (radial
//                growth with square cells), V a rotation of 2 pi / 128 about the axis, W an axial translation
//   bent-twisted-tapered  100^3 groups, 1 ball, 3 patterns: U a swirl (bend by 90 degrees, taper 0.7),
//                V a screw (twist by 45 degrees), W a swirl (twist 54 degrees, flare 1.3), cumulative
//   regular coarse 9^3 and warped coarse 8^3 (1 ball, 3 patterns), cylindrical coarse 5 x 17 x 9, for the
//   Lattice-in-Lattice constructions of the dissertation's Table 7.1.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include <sys/resource.h>
#include <time.h>

#include "sample_lattices.hpp"
#include "steady/core/constants.hpp"
#include "steady/lattice/lattice.hpp"

namespace bench {

using namespace steady;

using test::bcc_patterns;
using test::cubic_patterns;

inline Lattice regular_fine(std::int64_t n = 75) { return test::regular_bcc({n, n, n}, 1.0, 0.1, 0.08); }
inline Lattice cylindrical(Counts c, double inner_radius, int nodes) {
  return test::cylindrical(c, inner_radius, nodes, true, 0.1, 0.08);
}
inline Lattice cylindrical_fine() { return cylindrical({32, 128, 128}, 20.0, 2); }
inline Lattice cylindrical_coarse() { return cylindrical({5, 17, 9}, 20.0, 1); }
inline Lattice bent_twisted_tapered(std::int64_t n = 100, double radius = 0.12) {
  return test::bent_twisted_tapered({n, n, n}, 1.0, radius);
}
inline Lattice regular_coarse(std::int64_t n, double spacing, double radius) {
  return test::regular_cubic({n, n, n}, spacing, radius);
}

// The axis-aligned bounding box of a lattice's balls (beams lie in the hulls of their balls).
inline void bounding_box(const Lattice& lat, Vec3& lo, Vec3& hi) {
  std::vector<double> c(3 * static_cast<std::size_t>(lat.ball_count())), r(static_cast<std::size_t>(lat.ball_count()));
  lat.balls(c.data(), r.data());
  lo = Vec3(1e300);
  hi = Vec3(-1e300);
  for (std::int64_t b = 0; b < lat.ball_count(); ++b) {
    const Vec3 p(c[3 * b], c[3 * b + 1], c[3 * b + 2]);
    lo = glm::min(lo, p - Vec3(r[b]));
    hi = glm::max(hi, p + Vec3(r[b]));
  }
}

inline double mean_ball_radius(const Lattice& lat) {
  std::vector<double> c(3 * static_cast<std::size_t>(lat.ball_count())), r(static_cast<std::size_t>(lat.ball_count()));
  lat.balls(c.data(), r.data());
  double s = 0.0;
  for (double x : r) s += x;
  return s / static_cast<double>(r.size());
}

// The papers' query set: centers uniform in the bounding box, radii uniform in 90-110% of the mean ball radius.
inline std::vector<Ball> paper_queries(const Lattice& lat, int count, std::uint64_t seed) {
  Vec3 lo, hi;
  bounding_box(lat, lo, hi);
  const double mean = mean_ball_radius(lat);
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::vector<Ball> q;
  for (int i = 0; i < count; ++i)
    q.push_back({lo + Vec3(u01(rng), u01(rng), u01(rng)) * (hi - lo), mean * (0.9 + 0.2 * u01(rng))});
  return q;
}

// CPU seconds of the whole process (all threads): on a shared machine, CPU time / threads is what the
// wall time would be on idle cores.
inline double process_cpu_seconds() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

inline std::string load_average() {
  std::FILE* f = std::fopen("/proc/loadavg", "r");
  char buf[64] = "?";
  if (f) {
    if (!std::fgets(buf, sizeof buf, f)) buf[0] = 0;
    std::fclose(f);
  }
  std::string s(buf);
  return s.substr(0, s.find(' ', s.find(' ', s.find(' ') + 1) + 1));
}

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// CPU seconds of the calling thread: single-threaded measurements that other processes on the same
// cores do not inflate.
inline double thread_cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

template <class F>
double median_thread_cpu_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const double t0 = thread_cpu_seconds();
    f();
    t.push_back(thread_cpu_seconds() - t0);
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

template <class F>
double median_seconds(int repeats, F&& f) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    t.push_back(seconds_since(t0));
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

inline bool has_flag(int argc, char** argv, const std::string& flag) {
  for (int a = 1; a < argc; ++a)
    if (flag == argv[a]) return true;
  return false;
}

}  // namespace bench
