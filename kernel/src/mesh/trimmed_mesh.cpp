#include "steady/mesh/trimmed_mesh.hpp"

#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <chrono>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "mesh/band_sides.hpp"
#include "mesh/cgal_mesh.hpp"
#include "mesh/float_safe.hpp"
#include "mesh/loop_fan.hpp"
#include "mesh/mesh_plan.hpp"
#include "mesh/vertex_key.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;
double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void check_body(const TriangleMesh* m, const char* field) {
  if (m->triangles.empty()) fail_input(field, "the mesh has no triangles");
  const MeshEdgeReport edges = mesh_edge_report(*m);
  if (!edges.closed_manifold())
    fail_input(field, "the mesh is not a closed, consistently oriented surface (" + std::to_string(edges.border_edges) +
                          " open edges, " + std::to_string(edges.non_manifold_edges) + " non-manifold, " +
                          std::to_string(edges.misoriented_edges) + " misoriented)");
  if (!(mesh_volume(*m) > 0.0)) fail_input(field, "the mesh encloses no volume (its triangles face inward?)");
  if (PMP::does_self_intersect(to_half_edge_mesh<CgalMesh>(*m))) fail_input(field, "the mesh intersects itself");
}

// What closes a loop of a piece where the neighbouring element is not in the piece.
enum class Cap { None, Dropped, Kept };  // no cap (the piece stays open), a cap the Boolean drops, one it keeps

// A piece of the lattice's mesh: hub patches, united groups, strips, and caps closing loops whose other element is
// elsewhere.
struct Piece {
  TriangleMesh mesh;
  std::vector<std::int64_t> hub_base;    // per hub: index of its first vertex, -1 when not in the piece
  std::vector<std::int64_t> group_base;  // per group likewise
  std::vector<Vec3> cap_centers;         // of caps the Boolean keeps (to remove after it)

  explicit Piece(const MeshPlan& plan) : hub_base(plan.hubs.size(), -1), group_base(plan.groups.groups.size(), -1) {}

  // Index in the piece of vertex v of hub h's template (a loop's vertex, for a hub in a group), -1 when the hub is
  // not in the piece.
  std::int64_t vertex_of(const MeshPlan& plan, std::size_t h, std::uint32_t v) const {
    const int g = plan.groups.of_hub[h];
    if (g < 0) return hub_base[h] < 0 ? -1 : hub_base[h] + v;
    if (group_base[g] < 0) return -1;
    return group_base[g] + plan.groups.loop_vertex.at(static_cast<std::uint64_t>(h) << 32 | v);
  }

  void add_group(const MeshPlan& plan, std::size_t g) {
    const TriangleMesh& m = plan.groups.groups[g].mesh;
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    group_base[g] = base;
    mesh.vertices.insert(mesh.vertices.end(), m.vertices.begin(), m.vertices.end());
    for (const Triangle& t : m.triangles) mesh.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }

  void add_hub(const MeshPlan& plan, std::size_t h) {
    const HubTemplate& t = plan.templates[plan.hubs[h].templ];
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    hub_base[h] = base;
    for (std::size_t v = 0; v < t.vertices.size(); ++v) mesh.vertices.push_back(placed_vertex(plan, h, static_cast<std::uint32_t>(v)));
    for (const Triangle& tri : t.triangles) mesh.triangles.push_back({base + tri[0], base + tri[1], base + tri[2]});
  }

  // A fan on the loop (loop_fan.hpp); `reversed`: wound against the loop's order.
  void add_cap(const std::vector<std::uint32_t>& index, bool reversed, Cap cap) {
    const Vec3 center = append_fan(mesh, index, reversed);
    if (cap == Cap::Kept) cap_centers.push_back(center);
  }

  // The loop of beam e's end (0: a, 1: b) as points and indices: the hub's own vertices when it is in the piece,
  // else fresh copies, closed by a cap facing away from the beam unless `cap` is None.
  void loop(const MeshPlan& plan, std::int64_t e, int end, Cap cap, std::vector<Vec3>& points,
            std::vector<std::uint32_t>& index) {
    const MeshBeamEnd& be = plan.ends[2 * e + end];
    const std::vector<std::uint32_t>& loop = plan.templates[plan.hubs[be.hub].templ].loops[be.slot];
    const bool here = vertex_of(plan, be.hub, loop.front()) >= 0;
    for (std::uint32_t v : loop) {
      points.push_back(placed_vertex(plan, be.hub, v));
      if (here) {
        index.push_back(static_cast<std::uint32_t>(vertex_of(plan, be.hub, v)));
      } else {
        index.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
        mesh.vertices.push_back(points.back());
      }
    }
    if (!here && cap != Cap::None) add_cap(index, true, cap);
  }

  void add_strip(const MeshPlan& plan, std::int64_t e, const std::array<Cap, 2>& caps) {
    std::vector<Vec3> points[2];
    std::vector<std::uint32_t> index[2];
    for (int end = 0; end < 2; ++end) loop(plan, e, end, caps[end], points[end], index[end]);
    const std::size_t first = mesh.triangles.size();
    mesh.triangles.resize(first + index[0].size() + index[1].size());
    const BeamCone& cone = plan.frustums[e].cone;
    strip_triangles(points[0], index[0], points[1], index[1], cone.axis, cone.a, mesh.triangles.data() + first);
  }

  // Closes the hole of hub h (in the piece) where beam e's strip is not, facing away from the hub.
  void cap_hub_loop(const MeshPlan& plan, std::size_t h, std::int64_t e, int end, Cap cap) {
    const std::vector<std::uint32_t>& loop = plan.templates[plan.hubs[h].templ].loops[plan.ends[2 * e + end].slot];
    std::vector<std::uint32_t> index;
    for (std::uint32_t v : loop) index.push_back(static_cast<std::uint32_t>(vertex_of(plan, h, v)));
    add_cap(index, false, cap);
  }
};

// Where the rounded band folds, its needles shorter than this fraction of the tolerance collapse (float_safe.hpp):
// the surface moves by at most that much.
constexpr double kNeedleCollapseFraction = 0.1;

constexpr const char* kCapGone = "mesh: the surface cut into an element classified clear of it (a cap is gone)";

// The band through one Boolean. Without a skin: band ∩ body. With one, the part is (lattice ∩ body) ∪ skin, which
// is (lattice ∩ inner) ∪ skin since the skin is body minus inner: the band is cut at the inner surface only, and
// its outside goes to the skin. The inner solid minus the band, turned over, is the band inside the inner surface
// and the inner surface outside the band; the body's own surface joins unchanged. So no face of the band meets
// the body's, and the Boolean is on the inner surface only.
TriangleMesh band_boolean(const TriangleMesh& band, const std::vector<Vec3>& kept_caps, const TrimmedMeshRequest& request) {
  if (!request.inner) {
    if (band.triangles.empty()) return {};
    ExactMesh band_mesh = to_half_edge_mesh<ExactMesh>(band), body = to_half_edge_mesh<ExactMesh>(*request.body), result;
    if (!PMP::corefine_and_compute_intersection(band_mesh, body, result))
      throw std::runtime_error("mesh: CGAL could not cut the lattice's boundary band at the body's surface");
    return without_kept_caps(result, kept_caps, false, kCapGone);
  }
  ExactMesh inner = to_half_edge_mesh<ExactMesh>(*request.inner);
  if (band.triangles.empty()) return without_kept_caps(inner, {}, true, kCapGone);
  ExactMesh band_mesh = to_half_edge_mesh<ExactMesh>(band), result;
  if (!PMP::corefine_and_compute_difference(inner, band_mesh, result))
    throw std::runtime_error("mesh: CGAL could not cut the lattice's boundary band at the skin's inner surface");
  return without_kept_caps(result, kept_caps, true, kCapGone);
}

// The inside part and the band's result (and with a skin, the body's surface) as one mesh. Joined along the loops
// between them: the band's copies of those vertices are bit for bit the inside part's.
TriangleMesh joined(TriangleMesh inside, const TriangleMesh& band, const TriangleMesh* outer) {
  TriangleMesh out = std::move(inside);
  std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> band_vertex;
  band_vertex.reserve(band.vertices.size());
  for (std::uint32_t i = 0; i < band.vertices.size(); ++i) band_vertex.emplace(vertex_key(band.vertices[i]), i);
  std::vector<std::uint32_t> to_out(band.vertices.size(), UINT32_MAX);
  for (std::uint32_t i = 0; i < out.vertices.size(); ++i) {
    const auto it = band_vertex.find(vertex_key(out.vertices[i]));
    if (it != band_vertex.end() && to_out[it->second] == UINT32_MAX) to_out[it->second] = i;
  }
  for (std::size_t i = 0; i < band.vertices.size(); ++i)
    if (to_out[i] == UINT32_MAX) to_out[i] = static_cast<std::uint32_t>(out.vertices.size()), out.vertices.push_back(band.vertices[i]);
  for (const Triangle& t : band.triangles) out.triangles.push_back({to_out[t[0]], to_out[t[1]], to_out[t[2]]});
  if (outer) {
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    out.vertices.insert(out.vertices.end(), outer->vertices.begin(), outer->vertices.end());
    for (const Triangle& t : outer->triangles) out.triangles.push_back({base + t[0], base + t[1], base + t[2]});
  }
  return out;
}

// The inside part (elements clear inside the trimming surface) and the band (elements that may cross it, closed
// by caps where they meet the others).
std::pair<Piece, Piece> pieces(const MeshPlan& plan, const BandSides& sides) {
  Piece inside(plan), band(plan);
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) {
    if (plan.groups.of_hub[h] >= 0) continue;
    if (sides.patches[h] == Side::Inside) inside.add_hub(plan, h);
    else if (sides.patches[h] == Side::Crossing) band.add_hub(plan, h);
  }
  for (std::size_t g = 0; g < plan.groups.groups.size(); ++g) {
    const Side side = sides.patches[plan.groups.groups[g].hubs.front()];  // the group's (group_sides)
    if (side == Side::Inside) inside.add_group(plan, g);
    else if (side == Side::Crossing) band.add_group(plan, g);
  }
  // A cap where a band element meets an inside one stays clear of the surface (inside that element's bounding
  // ball), so the Boolean keeps it and it is removed after; a cap at an outside element is dropped by the Boolean.
  const auto cap_at = [](Side other) { return other == Side::Inside ? Cap::Kept : Cap::Dropped; };
  for (std::int64_t e = 0; e < static_cast<std::int64_t>(sides.strips.size()); ++e) {
    if (!plan.frustums[e].exists || plan.groups.inner[e]) continue;  // an inner beam is in its group's mesh
    const Side a = sides.patches[plan.ends[2 * e].hub], b = sides.patches[plan.ends[2 * e + 1].hub];
    if (sides.strips[e] == Side::Inside) inside.add_strip(plan, e, {Cap::None, Cap::None});
    else if (sides.strips[e] == Side::Crossing) band.add_strip(plan, e, {cap_at(a), cap_at(b)});
  }
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) {
    if (sides.patches[h] != Side::Crossing) continue;
    for (const auto& [e, end] : plan.hubs[h].stumps)
      if (!plan.groups.inner[e] && sides.strips[e] != Side::Crossing)
        band.cap_hub_loop(plan, h, e, end, cap_at(sides.strips[e]));
  }
  return {std::move(inside), std::move(band)};
}

// A group is one piece: Inside or Outside when all its hubs' patches and inner beams' strips are, else Crossing;
// each of its hubs then takes the group's side (which the strips leaving it and their caps go by).
void group_sides(const MeshPlan& plan, BandSides& sides) {
  const MeshGroups& groups = plan.groups;
  std::vector<char> not_inside(groups.groups.size(), 0), not_outside(groups.groups.size(), 0);
  auto see = [&](int g, Side s) {
    not_inside[g] |= s != Side::Inside;
    not_outside[g] |= s != Side::Outside;
  };
  for (std::size_t h = 0; h < plan.hubs.size(); ++h)
    if (groups.of_hub[h] >= 0) see(groups.of_hub[h], sides.patches[h]);
  for (std::size_t e = 0; e < sides.strips.size(); ++e)
    if (groups.inner[e]) see(groups.of_hub[plan.ends[2 * e].hub], sides.strips[e]);
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) {
    const int g = groups.of_hub[h];
    if (g >= 0) sides.patches[h] = !not_inside[g] ? Side::Inside : !not_outside[g] ? Side::Outside : Side::Crossing;
  }
}

// Moves the band's vertices that graze the surface clear of it, by a gap of 16 floats' resolution at the band's
// largest coordinate, with their copies in the inside part and the kept caps' centers (the join and the caps'
// removal match bit for bit). Returns how many moved.
std::int64_t keep_clear(const TrimSurface& surface, Piece& inside, Piece& band) {
  double largest = 0.0;
  for (const Vec3& v : band.mesh.vertices) largest = std::max({largest, std::abs(v.x), std::abs(v.y), std::abs(v.z)});
  const auto moves = surface.clear_places(band.mesh.vertices, std::ldexp(largest, -19));
  if (moves.empty()) return 0;
  std::unordered_map<VertexKey, Vec3, VertexKeyHash> place;
  for (const auto& [i, p] : moves) place.emplace(vertex_key(band.mesh.vertices[i]), p);
  for (std::vector<Vec3>* points : {&band.mesh.vertices, &inside.mesh.vertices, &band.cap_centers})
    for (Vec3& v : *points) {
      const auto it = place.find(vertex_key(v));
      if (it != place.end()) v = it->second;
    }
  return static_cast<std::int64_t>(moves.size());
}

}  // namespace

TriangleMesh trimmed_lattice_mesh(const FlatLattice& f, const MeshOptions& options, const TrimmedMeshRequest& request,
                                  TrimmedMeshStats* stats_out, Progress& progress) {
  if (!request.body) fail_input("body", "a trimmed mesh needs the body's mesh");
  auto clock = std::chrono::steady_clock::now();
  TrimmedMeshStats stats;
  check_body(request.body, "body");
  if (request.inner) check_body(request.inner, "inner");
  stats.check_seconds = seconds_since(clock);
  progress.set_total(100);
  MeshPlan plan;
  clock = std::chrono::steady_clock::now();
  const TrimSurface surface(request.inner ? *request.inner : *request.body);
  std::vector<Side> hubs;
  {
    // Templates only for the hubs that are placed or hold a loop of a placed strip.
    Progress part(progress, 40);
    plan = plan_lattice_mesh(
        f, options, part,
        [&](const MeshPlan& p) {
          hubs = surface.hubs(p);
          return hubs_needed(p, hubs);
        });
  }
  stats.plan_seconds = seconds_since(clock);
  clock = std::chrono::steady_clock::now();
  BandSides sides = surface.elements(plan, hubs);
  group_sides(plan, sides);
  stats.inside_hubs = sides.inside_hubs, stats.crossing_hubs = sides.crossing_hubs, stats.outside_hubs = sides.outside_hubs;
  stats.classify_seconds = seconds_since(clock);
  progress.advance(10);

  clock = std::chrono::steady_clock::now();
  auto [inside, band] = pieces(plan, sides);
  stats.band_triangles = static_cast<std::int64_t>(band.mesh.triangles.size());
  stats.moved_clear = keep_clear(surface, inside, band);
  stats.pieces_seconds = seconds_since(clock);
  clock = std::chrono::steady_clock::now();
  TriangleMesh band_done;
  try {
    band_done = band_boolean(band.mesh, band.cap_centers, request);
    stats.boolean_seconds = seconds_since(clock);
    clock = std::chrono::steady_clock::now();
    // Every writer stores floats: the band is rounded and repaired here, the rest (edges far above a float's
    // resolution) only rounded; the join still matches bit for bit, both sides rounded alike.
    stats.float_removed_triangles =
        make_float_safe(band_done, "the trimmed band", kNeedleCollapseFraction * options.tolerance);
  } catch (const std::runtime_error& e) {
    // Where the body cuts a group of short beams' hubs, the cut can meet what is left of the slivers between the
    // two tessellations of a short beam's cone: said as the short beams' refusal, which names what helps.
    if (!plan.stats.short_beams || !is_geometry_failure(e)) throw;
    fail_short_beams(plan, std::string("the body's cut through their united hubs failed (") + e.what() + ")");
  }
  round_to_floats(inside.mesh);
  stats.float_seconds = seconds_since(clock);
  progress.advance(40);

  clock = std::chrono::steady_clock::now();
  TriangleMesh out = joined(std::move(inside.mesh), band_done, request.inner ? request.body : nullptr);
  round_to_floats(out);  // the body's surface, appended as given
  stats.join_seconds = seconds_since(clock);
  stats.mesh = plan.stats;
  stats.mesh.vertices = static_cast<std::int64_t>(out.vertices.size());
  stats.mesh.triangles = static_cast<std::int64_t>(out.triangles.size());
  if (stats_out) *stats_out = stats;
  progress.finish();
  return out;
}

}  // namespace steady
