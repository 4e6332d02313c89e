#include "mesh/mesh_plan.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <sstream>
#include <string>

#include "lattice/circle_frames.hpp"
#include "lattice/hub_catalog.hpp"
#include "lattice/hub_collars.hpp"
#include "mesh/hub_tessellation.hpp"
#include "query/foreign_contacts.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/query/clean_check.hpp"
#include "steady/core/progress.hpp"

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

// Every beam whose hubs are built fits between their loops, or is short: its two stumps overlap, and its hubs are
// united in a group (each stump's cap lies in the other hub, and the union drops it) when each cap lies in the
// other stump or in the other ball, else refused. Then the groups: hubs joined by `contacts` or by short beams.
// Returns per beam whether its strip (or its group) is placed.
std::vector<char> fit_beams_and_unite(MeshPlan& plan, const std::vector<char>& built, ForeignContacts contacts,
                                      double tolerance, Progress& progress) {
  const FlatLattice& f = *plan.lattice;
  const std::vector<BeamFrustum>& frustums = plan.frustums;
  LatticeMeshStats& stats = plan.stats;
  std::vector<char> placed(f.beam_count(), 0), short_beam(f.beam_count(), 0);
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if ((e & 4095) == 0) progress.check();
    const MeshBeamEnd& a = plan.ends[2 * e];
    const MeshBeamEnd& b = plan.ends[2 * e + 1];
    if (frustums[e].exists && (a.hub < 0 || b.hub < 0))
      throw std::runtime_error("mesh: beam " + std::to_string(e) + " lost a hub");
    if (!frustums[e].exists || !built[plan.hubs[a.hub].templ] || !built[plan.hubs[b.hub].templ]) continue;
    auto position = [&](const MeshBeamEnd& end) {
      return plan.templates[plan.hubs[end.hub].templ].loop_position[end.slot] * f.balls[plan.hubs[end.hub].ball].radius;
    };
    const double at_a = position(a), at_b = position(b), length = frustums[e].cone.length;
    placed[e] = 1;
    if (at_a + at_b < length * (1.0 - 1e-9)) continue;
    // The cap of one stump inside the other's solid: beyond the middle of the other ball's tangent plane and exit
    // circle, where the cone's circles lie in that ball (hub_union.cpp draws its frustums from there).
    const BeamCone& cone = frustums[e].cone;
    const double inside_a = 0.5 * (cone.ra * cone.sin_phi + frustums[e].exit_a);
    const double inside_b = 0.5 * (-cone.rb * cone.sin_phi + frustums[e].exit_b);
    // Or in the other ball, give or take a quarter of the tolerance, on the near side of its center: the union
    // drops what lies inside the sphere's tessellation and keeps the rest of the cap as a ledge within that margin
    // of the exact sphere, where the cone runs inside the ball too (beams thinner than their nodes) or outside it
    // by less than the cap's rim (tangent cones, widening toward the center). The tapered octets at node 0.45,
    // whose collars reach 0.07 (beam/node 0.9) and 0.0005 (1.0, and the hull model) from the other center.
    auto in_other_ball = [&](const MeshBeamEnd& end, double at, const MeshBeamEnd& other) {
      const double x = length - at;
      const double rim = plan.templates[plan.hubs[end.hub].templ].loop_radius[end.slot] *
                         f.balls[plan.hubs[end.hub].ball].radius;
      const double ball = f.balls[plan.hubs[other.hub].ball].radius + 0.25 * tolerance;
      return x > 0.0 && x * x + rim * rim < ball * ball;
    };
    const bool cap_a_inside = length - at_a > inside_b || in_other_ball(a, at_a, b);
    const bool cap_b_inside = length - at_b > inside_a || in_other_ball(b, at_b, a);
    if (!(cap_a_inside && cap_b_inside))
      fail_input("hub", "beam " + std::to_string(e) + " (balls " + std::to_string(f.beams[e].a) + " and " +
                            std::to_string(f.beams[e].b) + ") is too short for the collars of its crowded hubs (" +
                            g(at_a) + " + " + g(at_b) + " of its length " + g(length) +
                            ", reaching past each other into the balls): thinner beams or smaller balls there");
    short_beam[e] = 1;
    contacts.joined.emplace_back(f.beams[e].a, f.beams[e].b);
    if (!stats.short_beams++)
      plan.first_short_beam = "beam " + std::to_string(e) + " (balls " + std::to_string(f.beams[e].a) + " and " +
                              std::to_string(f.beams[e].b) + ": " + g(at_a) + " + " + g(at_b) + " of its length " +
                              g(length) + ")";
  }
  {
    const auto t1 = std::chrono::steady_clock::now();
    Progress part(progress, 30);
    try {
      plan.groups = mesh_groups(plan, contacts, short_beam, part);
    } catch (const std::runtime_error& e) {
      // Two tessellations of one cone overlap along a short beam, and the union's slivers can fold once rounded.
      if (!stats.short_beams || !is_geometry_failure(e)) throw;
      fail_short_beams(plan, std::string("the mesh could not unite their hubs (") + e.what() + ")");
    }
    stats.foreign_groups = static_cast<std::int64_t>(plan.groups.groups.size());
    for (const MeshGroup& group : plan.groups.groups) stats.foreign_hubs += static_cast<std::int64_t>(group.hubs.size());
    stats.group_seconds = seconds_since(t1);
  }
  return placed;
}

}  // namespace

bool is_geometry_failure(const std::exception& e) {
  return !dynamic_cast<const ResourceLimit*>(&e) && !dynamic_cast<const Cancelled*>(&e);
}

void fail_short_beams(const MeshPlan& plan, const std::string& why) {
  fail_input("hub", std::to_string(plan.stats.short_beams) + " beams are too short for the collars of their crowded "
                        "hubs (the first: " + plan.first_short_beam + "), and " + why +
                        ": thinner beams or smaller balls there (the B-rep, brep(), builds them)");
}

// The strip between loop a (counterclockwise about the beam's axis) and loop b (given counterclockwise about the
// opposite direction, as hub b sees its stump): the two polygons merged by angle about the axis, so every
// triangle spans at most one segment of each circle.
void strip_triangles(const std::vector<Vec3>& va, const std::vector<std::uint32_t>& ia, const std::vector<Vec3>& vb,
                     std::vector<std::uint32_t> ib, const Vec3& axis, const Vec3& center, Triangle* out) {
  std::reverse(ib.begin(), ib.end());
  std::vector<Vec3> pb(vb.rbegin(), vb.rend());
  const Vec3 u = any_perpendicular(axis), v = glm::cross(axis, u);
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

MeshPlan plan_lattice_mesh(const FlatLattice& f, const MeshOptions& options, Progress& progress,
                           const HubsNeeded& needed) {
  MeshPlan plan;
  plan.lattice = &f;
  LatticeMeshStats& stats = plan.stats;
  check_tolerance(f, options.tolerance);
  progress.set_total(100);
  const ForeignContacts contacts = foreign_contacts(f);  // elements meeting foreign ones, united in groups
  progress.advance(5);
  plan.frustums = beam_frustums(f);
  const std::vector<BeamFrustum>& frustums = plan.frustums;
  const std::vector<char> absorbed = absorbed_balls(f, frustums);

  // Hubs and their distinct shapes.
  std::vector<HubGeometry> geometry;
  plan.ends.assign(2 * f.beam_count(), MeshBeamEnd{});
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    if ((i & 4095) == 0) progress.check();  // one hub after the other: seconds per million
    if (absorbed[i]) continue;
    MeshHub h;
    h.ball = i;
    geometry.push_back(hub_geometry(
        f, frustums, i, [&](std::int64_t e) { return frustums[e].exists; }, h.stumps));
    for (std::size_t s = 0; s < h.stumps.size(); ++s)
      plan.ends[2 * h.stumps[s].first + h.stumps[s].second] = {static_cast<std::int64_t>(plan.hubs.size()),
                                                               static_cast<int>(s)};
    plan.hubs.push_back(std::move(h));
  }
  plan.catalog = catalog_hubs(geometry);
  const HubCatalog& catalog = plan.catalog;

  // One template per (shape, tolerance level).
  std::map<std::pair<int, int>, int> template_of;
  std::vector<std::pair<int, int>> keys;
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) {
    const int level = tolerance_level(options.tolerance / f.balls[plan.hubs[h].ball].radius);
    const auto key = std::make_pair(catalog.placements[h].shape, level);
    const auto [it, fresh] = template_of.emplace(key, static_cast<int>(keys.size()));
    if (fresh) keys.push_back(key);
    plan.hubs[h].templ = it->second;
    stats.crowded_hubs += geometry[h].kind != 0;
  }
  std::vector<char> built(keys.size(), 1);
  if (needed) {
    const std::vector<char> hubs_needed = needed(plan);
    // Where elements meet foreign ones, every template is made: a group needs all its hubs' templates.
    if (contacts.empty()) std::fill(built.begin(), built.end(), 0);
    for (std::size_t h = 0; h < plan.hubs.size(); ++h)
      if (hubs_needed[h]) built[plan.hubs[h].templ] = 1;
  }
  // The templates' memory before any is made: even a streamed STL holds them, and a tolerance far below the radii
  // makes a single template gigabytes and many minutes of work.
  double template_points = 0.0;
  for (std::size_t t = 0; t < keys.size(); ++t)
    if (built[t]) template_points += template_point_bound(level_tolerance(keys[t].second), catalog.shapes[keys[t].first].size());
  require_memory(static_cast<std::uint64_t>(std::min(template_points * kBytesPerTemplatePoint, 1.8e19)),
                 "mesh: the templates of " + std::to_string(std::count(built.begin(), built.end(), 1)) +
                     " distinct hubs (about " + g(template_points) + " points, tessellated once each)",
                 "use a larger tolerance (the points of a hub grow as radius / tolerance), or write a 3MF beam lattice "
                 "(write_3mf(beam_lattice=True))");
  const auto t0 = std::chrono::steady_clock::now();
  plan.templates.resize(keys.size());
  {
    Progress part(progress, 60, static_cast<std::int64_t>(keys.size()));
    tbb::parallel_for(std::size_t(0), keys.size(), [&](std::size_t t) {
      part.check();
      if (!built[t]) {
        part.advance();
        return;
      }
      const auto [shape, level] = keys[t];
      const std::vector<SphereCap>& caps = catalog.shapes[shape];
      const HubGeometry& rep = geometry[catalog.representatives[shape]];
      if (rep.kind == 0) {
        plan.templates[t] = tessellate_clean_hub(caps, level_tolerance(level));
      } else {
        const std::vector<CoreStump> stumps = core_stumps(caps, rep.extras);
        const CoreKind kind = core_kind(rep.kind);
        plan.templates[t] = tessellate_crowded_hub(stumps, place_collars(stumps, kind, kMaxCollarPosition),
                                                   level_tolerance(level));
      }
      part.advance();
    });
  }
  stats.template_seconds = seconds_since(t0);

  const std::vector<char> placed = fit_beams_and_unite(plan, built, contacts, options.tolerance, progress);

  // Sizes and offsets (a grouped hub has its place in its group's mesh).
  for (std::size_t k = 0; k < plan.hubs.size(); ++k) {
    MeshHub& h = plan.hubs[k];
    h.first_vertex = plan.vertex_count;
    h.first_triangle = plan.triangle_count;
    if (plan.groups.of_hub[k] >= 0) continue;
    plan.vertex_count += plan.templates[h.templ].vertices.size();
    plan.triangle_count += plan.templates[h.templ].triangles.size();
  }
  for (MeshGroup& g : plan.groups.groups) {
    g.first_vertex = plan.vertex_count;
    g.first_triangle = plan.triangle_count;
    plan.vertex_count += g.mesh.vertices.size();
    plan.triangle_count += g.mesh.triangles.size();
  }
  plan.beam_first_triangle.assign(f.beam_count() + 1, plan.triangle_count);
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if ((e & 4095) == 0) progress.check();
    std::uint64_t n = 0;
    if (placed[e]) {
      if (!plan.groups.inner[e]) n = strip_size(plan, e);  // an inner beam's strip is in its group's mesh
      ++stats.beams;
    }
    plan.beam_first_triangle[e + 1] = plan.beam_first_triangle[e] + n;
  }
  plan.triangle_count = plan.beam_first_triangle[f.beam_count()];
  stats.hubs = static_cast<std::int64_t>(plan.hubs.size());
  stats.distinct_hubs = static_cast<std::int64_t>(catalog.shapes.size());
  stats.templates = std::count(built.begin(), built.end(), 1);
  stats.triangles = static_cast<std::int64_t>(plan.triangle_count);
  stats.vertices = static_cast<std::int64_t>(plan.vertex_count);
  progress.finish();
  return plan;
}

Vec3 placed_vertex(const MeshPlan& plan, std::size_t h, std::uint32_t v) {
  const Ball& ball = plan.lattice->balls[plan.hubs[h].ball];
  return ball.center + (ball.radius * plan.catalog.placements[h].rotation) * plan.templates[plan.hubs[h].templ].vertices[v];
}

std::uint64_t mesh_vertex(const MeshPlan& plan, std::size_t h, std::uint32_t v) {
  const int g = plan.groups.of_hub[h];
  if (g < 0) return plan.hubs[h].first_vertex + v;
  return plan.groups.groups[g].first_vertex + plan.groups.loop_vertex.at(static_cast<std::uint64_t>(h) << 32 | v);
}

void place_hub(const MeshPlan& plan, std::size_t h, Vec3* vertices, Triangle* triangles) {
  const HubTemplate& t = plan.templates[plan.hubs[h].templ];
  for (std::size_t v = 0; v < t.vertices.size(); ++v) vertices[v] = placed_vertex(plan, h, static_cast<std::uint32_t>(v));
  const auto base = static_cast<std::uint32_t>(plan.hubs[h].first_vertex);
  for (const Triangle& tri : t.triangles) *triangles++ = {base + tri[0], base + tri[1], base + tri[2]};
}

std::size_t strip_size(const MeshPlan& plan, std::int64_t e) {
  std::size_t n = 0;
  for (int end = 0; end < 2; ++end) {
    const MeshBeamEnd& be = plan.ends[2 * e + end];
    n += plan.templates[plan.hubs[be.hub].templ].loops[be.slot].size();
  }
  return n;
}

namespace {

// A beam's loops in place, with their vertices' indices into the whole mesh.
void strip_loops(const MeshPlan& plan, std::int64_t e, std::vector<Vec3> (&points)[2],
                 std::vector<std::uint32_t> (&index)[2]) {
  for (int end = 0; end < 2; ++end) {
    const MeshBeamEnd& be = plan.ends[2 * e + end];
    for (std::uint32_t v : plan.templates[plan.hubs[be.hub].templ].loops[be.slot]) {
      index[end].push_back(static_cast<std::uint32_t>(mesh_vertex(plan, be.hub, v)));
      points[end].push_back(placed_vertex(plan, be.hub, v));
    }
  }
}

}  // namespace

void place_strip(const MeshPlan& plan, std::int64_t e, Triangle* triangles) {
  std::vector<Vec3> points[2];
  std::vector<std::uint32_t> index[2];
  strip_loops(plan, e, points, index);
  const BeamCone& cone = plan.frustums[e].cone;
  strip_triangles(points[0], index[0], points[1], index[1], cone.axis, cone.a, triangles);
}

void place_strip_corners(const MeshPlan& plan, std::int64_t e, std::array<Vec3, 3>* corners) {
  std::vector<Vec3> points[2];
  std::vector<std::uint32_t> index[2];
  strip_loops(plan, e, points, index);
  // Local indices: loop a first, then loop b.
  const auto na = static_cast<std::uint32_t>(index[0].size());
  for (std::uint32_t i = 0; i < index[0].size(); ++i) index[0][i] = i;
  for (std::uint32_t i = 0; i < index[1].size(); ++i) index[1][i] = na + i;
  std::vector<Triangle> local(index[0].size() + index[1].size());
  const BeamCone& cone = plan.frustums[e].cone;
  strip_triangles(points[0], index[0], points[1], index[1], cone.axis, cone.a, local.data());
  for (const Triangle& t : local) {
    for (int k = 0; k < 3; ++k) (*corners)[k] = t[k] < na ? points[0][t[k]] : points[1][t[k] - na];
    ++corners;
  }
}

}  // namespace steady
