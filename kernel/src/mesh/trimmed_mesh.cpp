#include "steady/mesh/trimmed_mesh.hpp"

#include <CGAL/AABB_face_graph_triangle_primitive.h>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/corefinement.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <chrono>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>

#include "mesh/mesh_plan.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Primitive = CGAL::AABB_face_graph_triangle_primitive<Mesh>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
namespace PMP = CGAL::Polygon_mesh_processing;
using Key = std::array<double, 3>;
// The Booleans run with exact constructions, rounded once at the end: the band meets the body's faces (and, with a
// skin, faces of the skin lie on the body's), and rounded intersection points folded triangles there.
using ExactKernel = CGAL::Exact_predicates_exact_constructions_kernel;
using ExactMesh = CGAL::Surface_mesh<ExactKernel::Point_3>;

ExactMesh to_exact(const TriangleMesh& m) {
  ExactMesh out;
  std::vector<ExactMesh::Vertex_index> v;
  v.reserve(m.vertices.size());
  for (const Vec3& p : m.vertices) v.push_back(out.add_vertex(ExactKernel::Point_3(p.x, p.y, p.z)));
  for (const Triangle& t : m.triangles)
    if (out.add_face(v[t[0]], v[t[1]], v[t[2]]) == ExactMesh::null_face())
      throw std::runtime_error("mesh: a triangle could not join the half-edge mesh (not a 2-manifold)");
  return out;
}

Mesh rounded(const ExactMesh& m) {
  Mesh out;
  std::map<std::uint32_t, Mesh::Vertex_index> v;
  for (const auto x : m.vertices()) {
    const auto& p = m.point(x);
    v[x] = out.add_vertex(Point(CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())));
  }
  for (const auto f : m.faces()) {
    std::array<Mesh::Vertex_index, 3> c;
    int k = 0;
    for (const auto x : CGAL::vertices_around_face(m.halfedge(f), m)) c[k++] = v[x];
    out.add_face(c[0], c[1], c[2]);
  }
  return out;
}

Key key(const Vec3& p) { return {p.x, p.y, p.z}; }

Mesh to_cgal(const TriangleMesh& m) {
  Mesh out;
  std::vector<Mesh::Vertex_index> v;
  v.reserve(m.vertices.size());
  for (const Vec3& p : m.vertices) v.push_back(out.add_vertex(Point(p.x, p.y, p.z)));
  for (const Triangle& t : m.triangles)
    if (out.add_face(v[t[0]], v[t[1]], v[t[2]]) == Mesh::null_face())
      throw std::runtime_error("mesh: a triangle could not join the half-edge mesh (not a 2-manifold)");
  return out;
}

void check_body(const TriangleMesh* m, const char* field) {
  if (m->triangles.empty()) fail_input(field, "the mesh has no triangles");
  const MeshEdgeReport edges = mesh_edge_report(*m);
  if (!edges.closed_manifold())
    fail_input(field, "the mesh is not a closed, consistently oriented surface (" + std::to_string(edges.border_edges) +
                          " open edges, " + std::to_string(edges.non_manifold_edges) + " non-manifold, " +
                          std::to_string(edges.misoriented_edges) + " misoriented)");
  if (!(mesh_volume(*m) > 0.0)) fail_input(field, "the mesh encloses no volume (its triangles face inward?)");
  if (PMP::does_self_intersect(to_cgal(*m))) fail_input(field, "the mesh intersects itself");
}

enum class Side { Inside, Crossing, Outside };

// A hub's reach: a ball around its center holding the ball and its half-beams.
double hub_reach(const MeshPlan& plan, std::size_t h) {
  const FlatLattice& f = *plan.lattice;
  double reach = f.balls[plan.hubs[h].ball].radius;
  for (const auto& [e, end] : plan.hubs[h].stumps)
    reach = std::max(reach, 0.5 * plan.frustums[e].cone.length + std::max(f.beams[e].ra, f.beams[e].rb));
  return reach;
}

std::vector<Side> classify_hubs(const MeshPlan& plan, const TriangleMesh& surface) {
  const Mesh m = to_cgal(surface);
  Tree tree(faces(m).first, faces(m).second, m);
  tree.accelerate_distance_queries();
  const CGAL::Side_of_triangle_mesh<Mesh, Kernel> side(tree);
  std::vector<Side> out(plan.hubs.size());
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) {
    const Vec3 c = plan.lattice->balls[plan.hubs[h].ball].center;
    const Point p(c.x, c.y, c.z);
    const double reach = hub_reach(plan, h);
    if (tree.squared_distance(p) <= reach * reach) out[h] = Side::Crossing;
    else out[h] = side(p) == CGAL::ON_BOUNDED_SIDE ? Side::Inside : Side::Outside;
  }
  return out;
}

// A piece of the lattice's mesh: whole hubs, strips, and caps closing strips at hubs that are not in the piece.
struct Piece {
  TriangleMesh mesh;
  std::map<std::int64_t, std::uint32_t> hub_base;  // hub -> index of its first vertex
  std::vector<Vec3> cap_centers;                   // of caps at inside hubs (to remove after the Boolean)

  void add_hub(const MeshPlan& plan, std::size_t h) {
    const HubTemplate& t = plan.templates[plan.hubs[h].templ];
    const auto base = static_cast<std::uint32_t>(mesh.vertices.size());
    hub_base[static_cast<std::int64_t>(h)] = base;
    for (std::size_t v = 0; v < t.vertices.size(); ++v) mesh.vertices.push_back(placed_vertex(plan, h, static_cast<std::uint32_t>(v)));
    for (const Triangle& tri : t.triangles) mesh.triangles.push_back({base + tri[0], base + tri[1], base + tri[2]});
  }

  // The loop of beam e's end (0: a, 1: b) as points and indices: the hub's own vertices when it is in the piece,
  // else fresh copies closed by a fan cap (facing away from the beam) around the loop's centroid.
  void loop(const MeshPlan& plan, std::int64_t e, int end, bool record_cap, std::vector<Vec3>& points,
            std::vector<std::uint32_t>& index) {
    const MeshBeamEnd& be = plan.ends[2 * e + end];
    const std::vector<std::uint32_t>& loop = plan.templates[plan.hubs[be.hub].templ].loops[be.slot];
    const auto it = hub_base.find(be.hub);
    Vec3 centroid(0.0);
    for (std::uint32_t v : loop) {
      points.push_back(placed_vertex(plan, be.hub, v));
      centroid += points.back();
      if (it != hub_base.end()) {
        index.push_back(it->second + v);
      } else {
        index.push_back(static_cast<std::uint32_t>(mesh.vertices.size()));
        mesh.vertices.push_back(points.back());
      }
    }
    if (it != hub_base.end()) return;
    centroid /= static_cast<double>(loop.size());
    const auto c = static_cast<std::uint32_t>(mesh.vertices.size());
    mesh.vertices.push_back(centroid);
    for (std::size_t i = 0; i < index.size(); ++i) mesh.triangles.push_back({c, index[(i + 1) % index.size()], index[i]});
    if (record_cap) cap_centers.push_back(centroid);
  }

  void add_strip(const MeshPlan& plan, std::int64_t e, const std::vector<Side>& sides) {
    std::vector<Vec3> points[2];
    std::vector<std::uint32_t> index[2];
    for (int end = 0; end < 2; ++end)
      loop(plan, e, end, sides[plan.ends[2 * e + end].hub] == Side::Inside, points[end], index[end]);
    const std::size_t first = mesh.triangles.size();
    mesh.triangles.resize(first + index[0].size() + index[1].size());
    const BeamCone& cone = plan.frustums[e].cone;
    strip_triangles(points[0], index[0], points[1], index[1], cone.axis, cone.a, mesh.triangles.data() + first);
  }
};

// The band after its Boolean, without the caps at inside hubs (their fans, left untouched by the Boolean), as an
// indexed mesh.
TriangleMesh without_caps(const Mesh& m, const std::vector<Vec3>& centers) {
  std::map<Key, Mesh::Vertex_index> at;
  for (const auto v : m.vertices()) at.emplace(Key{m.point(v).x(), m.point(v).y(), m.point(v).z()}, v);
  std::vector<char> dropped(m.number_of_faces() + m.number_of_removed_faces(), 0);
  std::vector<char> is_center(m.number_of_vertices() + m.number_of_removed_vertices(), 0);
  for (const Vec3& c : centers) {
    const auto it = at.find(key(c));
    if (it == at.end())
      throw std::runtime_error("mesh: the body cut into a hub classified inside (a cap of its beam is gone)");
    is_center[it->second] = 1;
    for (const auto f : CGAL::faces_around_target(m.halfedge(it->second), m)) {
      if (f == Mesh::null_face()) throw std::runtime_error("mesh: a cap at an inside hub was opened by the Boolean");
      dropped[f] = 1;
    }
  }
  TriangleMesh out;
  std::map<std::uint32_t, std::uint32_t> number;
  for (const auto f : m.faces()) {
    if (dropped[f]) continue;
    Triangle t;
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      if (is_center[v]) throw std::runtime_error("mesh: a cap's center is left in the band");
      const auto [it, fresh] = number.emplace(static_cast<std::uint32_t>(v), static_cast<std::uint32_t>(out.vertices.size()));
      if (fresh) out.vertices.emplace_back(m.point(v).x(), m.point(v).y(), m.point(v).z());
      t[k++] = it->second;
    }
    out.triangles.push_back(t);
  }
  return out;
}

// The skin: the body's surface and its inner offset turned inward, one closed shell around a void.
TriangleMesh skin_shell(const TriangleMesh& body, const TriangleMesh& inner) {
  TriangleMesh skin = body;
  const auto base = static_cast<std::uint32_t>(skin.vertices.size());
  skin.vertices.insert(skin.vertices.end(), inner.vertices.begin(), inner.vertices.end());
  for (const Triangle& t : inner.triangles) skin.triangles.push_back({base + t[0], base + t[2], base + t[1]});
  return skin;
}

}  // namespace

TriangleMesh trimmed_lattice_mesh(const FlatLattice& f, const MeshOptions& options, const TrimmedMeshRequest& request,
                                  TrimmedMeshStats* stats_out, Progress& progress) {
  if (!request.body) fail_input("body", "a trimmed mesh needs the body's mesh");
  check_body(request.body, "body");
  if (request.inner) check_body(request.inner, "inner");
  progress.set_total(100);
  TrimmedMeshStats stats;
  MeshPlan plan;
  {
    Progress part(progress, 40);
    plan = plan_lattice_mesh(f, options, part);
  }
  const TriangleMesh& trim = request.inner ? *request.inner : *request.body;
  const std::vector<Side> sides = classify_hubs(plan, trim);
  progress.advance(10);

  Piece inside, band;
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) {
    if (sides[h] == Side::Inside) ++stats.inside_hubs, inside.add_hub(plan, h);
    else if (sides[h] == Side::Crossing) ++stats.crossing_hubs, band.add_hub(plan, h);
    else ++stats.outside_hubs;
  }
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!plan.frustums[e].exists) continue;
    const Side a = sides[plan.ends[2 * e].hub], b = sides[plan.ends[2 * e + 1].hub];
    if (a == Side::Inside && b == Side::Inside) inside.add_strip(plan, e, sides);
    else if (!(a == Side::Outside && b == Side::Outside)) band.add_strip(plan, e, sides);
  }
  stats.band_triangles = static_cast<std::int64_t>(band.mesh.triangles.size());

  // The band through its Boolean(s): intersected with the body, and with a skin united with the skin first.
  const auto t0 = std::chrono::steady_clock::now();
  TriangleMesh band_done;
  if (!band.mesh.triangles.empty() || request.inner) {
    ExactMesh band_mesh = to_exact(band.mesh), result;
    if (request.inner) {
      // Hubs of the band (crossing, or at a band beam's end) near the body's outer surface stick out of it: the
      // band is cut there first, then united with the skin (so the skin goes through one Boolean, not two).
      const std::vector<Side> outer = classify_hubs(plan, *request.body);
      bool sticks_out = false;
      for (std::size_t h = 0; h < plan.hubs.size(); ++h)
        sticks_out = sticks_out || (sides[h] == Side::Crossing && outer[h] != Side::Inside);
      for (std::int64_t e = 0; e < f.beam_count() && !sticks_out; ++e) {
        if (!plan.frustums[e].exists) continue;
        const std::int64_t a = plan.ends[2 * e].hub, b = plan.ends[2 * e + 1].hub;
        const bool in_band = !(sides[a] == Side::Inside && sides[b] == Side::Inside) &&
                             !(sides[a] == Side::Outside && sides[b] == Side::Outside);
        sticks_out = in_band && (outer[a] != Side::Inside || outer[b] != Side::Inside);
      }
      if (sticks_out && !band.mesh.triangles.empty()) {
        ExactMesh body = to_exact(*request.body), clipped;
        if (!PMP::corefine_and_compute_intersection(band_mesh, body, clipped))
          throw std::runtime_error("mesh: CGAL could not cut the lattice's boundary band at the body's surface");
        band_mesh = std::move(clipped);
      }
      ExactMesh skin = to_exact(skin_shell(*request.body, *request.inner));
      if (band.mesh.triangles.empty()) {
        result = std::move(skin);
      } else if (!PMP::corefine_and_compute_union(band_mesh, skin, result)) {
        throw std::runtime_error("mesh: CGAL could not unite the lattice's boundary band with the skin");
      }
    } else {
      ExactMesh body = to_exact(*request.body);
      if (!PMP::corefine_and_compute_intersection(band_mesh, body, result))
        throw std::runtime_error("mesh: CGAL could not cut the lattice's boundary band at the body's surface");
    }
    band_done = without_caps(rounded(result), band.cap_centers);
  }
  stats.boolean_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  progress.advance(40);

  // Joined along the inside hubs' circles: the band's copies of those vertices are bit for bit the inside part's.
  TriangleMesh out = std::move(inside.mesh);
  std::map<Key, std::uint32_t> shared;
  for (std::uint32_t i = 0; i < out.vertices.size(); ++i) shared.emplace(key(out.vertices[i]), i);
  std::vector<std::uint32_t> to_out(band_done.vertices.size());
  for (std::size_t i = 0; i < band_done.vertices.size(); ++i) {
    const auto it = shared.find(key(band_done.vertices[i]));
    if (it != shared.end()) {
      to_out[i] = it->second;
    } else {
      to_out[i] = static_cast<std::uint32_t>(out.vertices.size());
      out.vertices.push_back(band_done.vertices[i]);
    }
  }
  for (const Triangle& t : band_done.triangles) out.triangles.push_back({to_out[t[0]], to_out[t[1]], to_out[t[2]]});
  stats.mesh = plan.stats;
  stats.mesh.vertices = static_cast<std::int64_t>(out.vertices.size());
  stats.mesh.triangles = static_cast<std::int64_t>(out.triangles.size());
  if (stats_out) *stats_out = stats;
  progress.finish();
  return out;
}

}  // namespace steady
