#include "steady/mesh/lattice_mesh.hpp"

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "lattice/hub_catalog.hpp"
#include "lattice/hub_collars.hpp"
#include "mesh/hub_tessellation.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/query/clean_check.hpp"

namespace steady {

namespace {

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

std::string g(double v) {
  std::ostringstream os;
  os << v;
  return os.str();
}

void check_tolerance(const FlatLattice& f, double tolerance) {
  if (!std::isfinite(tolerance) || tolerance <= 0.0)
    fail_input("tolerance", "must be a finite length > 0 (got " + g(tolerance) + ")");
  for (std::int64_t i = 0; i < f.ball_count(); ++i)
    if (tolerance >= 0.25 * f.balls[i].radius)
      fail_input("tolerance", g(tolerance) + " is a quarter of ball " + std::to_string(i) + "'s radius " +
                                  g(f.balls[i].radius) + " or more: use a tolerance below " +
                                  g(0.25 * f.balls[i].radius));
}

void check_clean_for_mesh(const FlatLattice& f) {
  CleanCheckOptions options;
  options.skip_circle_overlaps = true;  // crowded hubs are built as unions
  const CleanReport report = check_clean(f, options);
  if (report.clean()) return;
  std::ostringstream os;
  os << "is not clean (" << report.issue_count << " issue" << (report.issue_count == 1 ? "" : "s") << "): ";
  for (std::size_t i = 0; i < std::min<std::size_t>(3, report.issues.size()); ++i)
    os << (i ? "; " : "") << report.issues[i].describe();
  if (report.issue_count > 3) os << "; ...";
  fail_input("lattice", os.str());
}

struct HubPiece {
  std::int64_t ball = -1;
  std::vector<std::pair<std::int64_t, int>> stumps;  // (beam, end: 0 at a, 1 at b)
  int templ = -1;
  std::uint64_t first_vertex = 0;
};

// Where a beam's strip starts and ends: a hub and one of its loops.
struct BeamEnd {
  std::int64_t hub = -1;
  int slot = -1;
};

// The strip between loop a (counterclockwise about the beam's axis) and loop b (given counterclockwise about the
// opposite direction, as hub b sees its stump): the two polygons merged by angle about the axis, so every
// triangle spans at most one segment of each circle.
void strip_triangles(const std::vector<Vec3>& va, const std::vector<std::uint32_t>& ia, const std::vector<Vec3>& vb,
                     std::vector<std::uint32_t> ib, const Vec3& axis, const Vec3& center, Triangle* out) {
  std::reverse(ib.begin(), ib.end());
  std::vector<Vec3> pb(vb.rbegin(), vb.rend());
  const Vec3 u = glm::normalize(glm::cross(axis, std::abs(axis.x) < 0.6 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
  const Vec3 v = glm::cross(axis, u);
  auto angle = [&](const Vec3& p) { return std::atan2(glm::dot(p - center, v), glm::dot(p - center, u)); };
  auto above = [](double t, double base) {  // t unwrapped into [base, base + 2 pi)
    double r = std::fmod(t - base, 2.0 * M_PI);
    return base + (r < 0.0 ? r + 2.0 * M_PI : r);
  };
  const int na = static_cast<int>(ia.size()), nb = static_cast<int>(ib.size());
  const double a0 = angle(va[0]);
  int j0 = 0;
  double best = 1e300;
  for (int j = 0; j < nb; ++j) {
    const double d = std::abs(above(angle(pb[j]), a0 - M_PI) - a0);
    if (d < best) best = d, j0 = j;
  }
  const double b0 = above(angle(pb[j0]), a0 - M_PI);
  std::vector<double> ta(na + 1), tb(nb + 1);
  for (int i = 0; i < na; ++i) ta[i] = i == 0 ? a0 : above(angle(va[i]), a0);
  ta[na] = a0 + 2.0 * M_PI;
  for (int j = 0; j < nb; ++j) tb[j] = j == 0 ? b0 : above(angle(pb[(j0 + j) % nb]), b0);
  tb[nb] = b0 + 2.0 * M_PI;
  int i = 0, j = 0, n = 0;
  auto A = [&](int k) { return ia[k % na]; };
  auto B = [&](int k) { return ib[(j0 + k) % nb]; };
  while (i < na || j < nb) {
    if (j == nb || (i < na && ta[i + 1] <= tb[j + 1])) {
      out[n++] = {A(i), A(i + 1), B(j)};
      ++i;
    } else {
      out[n++] = {A(i), B(j + 1), B(j)};
      ++j;
    }
  }
}

}  // namespace

TriangleMesh lattice_mesh(const FlatLattice& f, const MeshOptions& options, LatticeMeshStats* stats_out,
                          Progress& progress) {
  LatticeMeshStats stats;
  check_tolerance(f, options.tolerance);
  progress.set_total(100);
  check_clean_for_mesh(f);
  progress.advance(5);
  const std::vector<BeamFrustum> frustums = beam_frustums(f);
  const std::vector<char> absorbed = absorbed_balls(f, frustums);

  // Hubs and their distinct shapes.
  std::vector<HubPiece> hubs;
  std::vector<HubGeometry> geometry;
  std::vector<BeamEnd> ends(2 * f.beam_count());
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    if (absorbed[i]) continue;
    HubPiece h;
    h.ball = i;
    geometry.push_back(hub_geometry(
        f, frustums, i, [&](std::int64_t e) { return frustums[e].exists; }, h.stumps));
    for (std::size_t s = 0; s < h.stumps.size(); ++s)
      ends[2 * h.stumps[s].first + h.stumps[s].second] = {static_cast<std::int64_t>(hubs.size()), static_cast<int>(s)};
    hubs.push_back(std::move(h));
  }
  const HubCatalog catalog = catalog_hubs(geometry);

  // One template per (shape, tolerance level).
  std::map<std::pair<int, int>, int> template_of;
  std::vector<std::pair<int, int>> keys;
  for (std::size_t h = 0; h < hubs.size(); ++h) {
    const int level = tolerance_level(options.tolerance / f.balls[hubs[h].ball].radius);
    const auto key = std::make_pair(catalog.placements[h].shape, level);
    const auto [it, fresh] = template_of.emplace(key, static_cast<int>(keys.size()));
    if (fresh) keys.push_back(key);
    hubs[h].templ = it->second;
    stats.crowded_hubs += geometry[h].kind != 0;
  }
  const auto t0 = std::chrono::steady_clock::now();
  std::vector<HubTemplate> templates(keys.size());
  {
    Progress part(progress, 45, static_cast<std::int64_t>(keys.size()));
    tbb::parallel_for(std::size_t(0), keys.size(), [&](std::size_t t) {
      part.check();
      const auto [shape, level] = keys[t];
      const std::vector<SphereCap>& caps = catalog.shapes[shape];
      const HubGeometry& rep = geometry[catalog.representatives[shape]];
      if (rep.kind == 0) {
        templates[t] = tessellate_clean_hub(caps, level_tolerance(level));
      } else {
        const std::vector<CoreStump> stumps = core_stumps(caps, rep.extras);
        const CoreKind kind = core_kind(rep.kind);
        templates[t] = tessellate_crowded_hub(stumps, place_collars(stumps, kind, kMaxCollarPosition),
                                              level_tolerance(level));
      }
      part.advance();
    });
  }
  stats.template_seconds = seconds_since(t0);

  // Sizes, offsets, and the memory they need.
  const auto t1 = std::chrono::steady_clock::now();
  std::uint64_t vertex_count = 0, triangle_count = 0;
  for (HubPiece& h : hubs) {
    h.first_vertex = vertex_count;
    vertex_count += templates[h.templ].vertices.size();
    triangle_count += templates[h.templ].triangles.size();
  }
  std::vector<std::uint64_t> hub_first_triangle(hubs.size() + 1, 0);
  for (std::size_t h = 0; h < hubs.size(); ++h)
    hub_first_triangle[h + 1] = hub_first_triangle[h] + templates[hubs[h].templ].triangles.size();
  std::vector<std::uint64_t> beam_first_triangle(f.beam_count() + 1, triangle_count);
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    std::uint64_t n = 0;
    if (frustums[e].exists) {
      const BeamEnd& a = ends[2 * e];
      const BeamEnd& b = ends[2 * e + 1];
      if (a.hub < 0 || b.hub < 0) throw std::runtime_error("mesh: beam " + std::to_string(e) + " lost a hub");
      n = templates[hubs[a.hub].templ].loops[a.slot].size() + templates[hubs[b.hub].templ].loops[b.slot].size();
      ++stats.beams;
    }
    beam_first_triangle[e + 1] = beam_first_triangle[e] + n;
  }
  triangle_count = beam_first_triangle[f.beam_count()];
  if (vertex_count > 0xffffffffull)
    throw ResourceLimit("mesh: " + std::to_string(vertex_count) +
                        " vertices exceed the 2^32 an indexed mesh holds: use a larger tolerance or write STL");
  require_memory(vertex_count * sizeof(Vec3) + triangle_count * sizeof(Triangle),
                 "a mesh of " + std::to_string(triangle_count) + " triangles (a larger tolerance makes fewer)");

  // Copies of the templates in place, then the strips.
  TriangleMesh mesh;
  mesh.vertices.resize(vertex_count);
  mesh.triangles.resize(triangle_count);
  {
    Progress part(progress, 50, static_cast<std::int64_t>(hubs.size() + f.beam_count()));
    tbb::parallel_for(std::size_t(0), hubs.size(), [&](std::size_t h) {
      const HubTemplate& t = templates[hubs[h].templ];
      const Ball& ball = f.balls[hubs[h].ball];
      const Mat3 m = ball.radius * catalog.placements[h].rotation;
      for (std::size_t v = 0; v < t.vertices.size(); ++v) mesh.vertices[hubs[h].first_vertex + v] = ball.center + m * t.vertices[v];
      const auto base = static_cast<std::uint32_t>(hubs[h].first_vertex);
      Triangle* out = mesh.triangles.data() + hub_first_triangle[h];
      for (const Triangle& tri : t.triangles) *out++ = {base + tri[0], base + tri[1], base + tri[2]};
      if (h % 1024 == 0) part.advance(1024);
    });
    tbb::parallel_for(std::int64_t(0), f.beam_count(), [&](std::int64_t e) {
      if (!frustums[e].exists) return;
      auto loop = [&](const BeamEnd& end, std::vector<Vec3>& points, std::vector<std::uint32_t>& index) {
        const HubPiece& h = hubs[end.hub];
        const HubTemplate& t = templates[h.templ];
        const double position = t.loop_position[end.slot] * f.balls[h.ball].radius;
        for (std::uint32_t v : t.loops[end.slot]) {
          index.push_back(static_cast<std::uint32_t>(h.first_vertex + v));
          points.push_back(mesh.vertices[h.first_vertex + v]);
        }
        return position;
      };
      std::vector<Vec3> pa, pb;
      std::vector<std::uint32_t> ia, ib;
      const double at_a = loop(ends[2 * e], pa, ia), at_b = loop(ends[2 * e + 1], pb, ib);
      const BeamCone& cone = frustums[e].cone;
      if (!(at_a + at_b < cone.length * (1.0 - 1e-9)))
        fail_input("hub", "beam " + std::to_string(e) + " (balls " + std::to_string(f.beams[e].a) + " and " +
                              std::to_string(f.beams[e].b) + ") is too short for the collars of its crowded hubs (" +
                              g(at_a) + " + " + g(at_b) + " of its length " + g(cone.length) + ")");
      strip_triangles(pa, ia, pb, ib, cone.axis, cone.a, mesh.triangles.data() + beam_first_triangle[e]);
      if (e % 1024 == 0) part.advance(1024);
    });
  }
  stats.placing_seconds = seconds_since(t1);
  stats.hubs = static_cast<std::int64_t>(hubs.size());
  stats.distinct_hubs = static_cast<std::int64_t>(catalog.shapes.size());
  stats.templates = static_cast<std::int64_t>(templates.size());
  if (stats_out) *stats_out = stats;
  progress.finish();
  return mesh;
}

TriangleMesh lattice_mesh(const Lattice& lattice, const MeshOptions& options, LatticeMeshStats* stats,
                          Progress& progress) {
  return lattice_mesh(flatten(lattice), options, stats, progress);
}

}  // namespace steady
