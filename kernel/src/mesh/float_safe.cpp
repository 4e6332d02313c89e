#include "mesh/float_safe.hpp"

#include <CGAL/Polygon_mesh_processing/repair_degeneracies.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Polygon_mesh_processing/shape_predicates.h>
#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <set>
#include <type_traits>
#include <utility>
#include <stdexcept>
#include <string>
#include <vector>

#include "mesh/cgal_mesh.hpp"

namespace steady {

namespace PMP = CGAL::Polygon_mesh_processing;

namespace {
// Through memory: at -O3 with -frounding-math, GCC 12 vectorized the three narrowings of a Vec3 and dropped two
// of them (seen in the disassembly: x and y came back unrounded).
double to_float(double d) {
  volatile float f = static_cast<float>(d);
  return f;
}

constexpr int kUnfoldRounds = 8;

// Collapses edge e unless both its ends are on the border, keeping the border end where one is (the loops where the
// band joins the rest must match it bit for bit), else the lesser point, and the link condition (the mesh stays
// 2-manifold). What is kept depends on the points only, not on how the mesh is numbered.
bool collapse(CgalMesh& m, CgalMesh::Edge_index e) {
  const auto h = m.halfedge(e);
  const auto a = m.source(h), b = m.target(h);
  const bool a_border = static_cast<bool>(CGAL::is_border(a, m)), b_border = static_cast<bool>(CGAL::is_border(b, m));
  if ((a_border && b_border) || !CGAL::Euler::does_satisfy_link_condition(e, m)) return false;
  const bool keep_a = a_border || (!b_border && m.point(a) < m.point(b));
  const auto kept_point = keep_a ? m.point(a) : m.point(b);
  m.point(CGAL::Euler::collapse_edge(e, m)) = kept_point;
  return true;
}

// Edges or faces in the order of their points (each element's points sorted, then compared in turn), so that the
// collapses below give the same mesh however the Boolean before them numbered it (its order varies with threads).
template <class Element>
void sort_by_points(const CgalMesh& m, std::vector<Element>& elements) {
  const auto points_of = [&](Element x) {
    std::vector<CgalKernel::Point_3> p;
    if constexpr (std::is_same_v<Element, CgalMesh::Edge_index>) {
      p = {m.point(m.vertex(x, 0)), m.point(m.vertex(x, 1))};
    } else {
      for (const auto v : CGAL::vertices_around_face(m.halfedge(x), m)) p.push_back(m.point(v));
    }
    std::sort(p.begin(), p.end());
    return p;
  };
  std::vector<std::pair<std::vector<CgalKernel::Point_3>, Element>> keyed;
  keyed.reserve(elements.size());
  for (const Element x : elements) keyed.emplace_back(points_of(x), x);
  std::sort(keyed.begin(), keyed.end(), [](const auto& p, const auto& q) { return p.first < q.first; });
  for (std::size_t i = 0; i < keyed.size(); ++i) elements[i] = keyed[i].second;
}

double squared_length(const CgalMesh& m, CgalMesh::Edge_index e) {
  return CGAL::squared_distance(m.point(m.vertex(e, 0)), m.point(m.vertex(e, 1)));
}

// Collapses the edges shorter than `gap`. Such an edge is where a lattice edge passed within a few floats of a
// vertex of the wall's tessellation: the Boolean put a vertex there, and once rounded its slivers can fold through
// a neighbour (the main job at a tolerance of 0.005 and 0.007: 1 float apart). Returns how many collapsed.
std::int64_t collapse_short_edges(CgalMesh& m, double gap) {
  std::vector<CgalMesh::Edge_index> short_edges;
  for (const auto e : m.edges())
    if (squared_length(m, e) < gap * gap) short_edges.push_back(e);
  sort_by_points(m, short_edges);
  std::int64_t collapsed = 0;
  for (const auto e : short_edges)  // an earlier collapse may have removed e, or moved an end of it
    if (!m.is_removed(e) && squared_length(m, e) < gap * gap && collapse(m, e)) ++collapsed;
  if (collapsed > 0) m.collect_garbage();
  return collapsed;
}

// Where rounded triangles still intersect, collapses the shortest edge of each that is a needle (its shortest edge
// below 1/20 of its longest) shorter than `limit`, for up to kUnfoldRounds rounds. Such needles are the Boolean's
// slivers where the lattice runs within a few floats of the wall's tessellation (a wall vertex under a lattice
// triangle: the main job at tolerances 0.003 to 0.004). Returns whether the mesh is then free of self-intersections.
bool unfold_needles(CgalMesh& m, double limit) {
  for (int round = 0;; ++round) {
    std::vector<std::pair<CgalMesh::Face_index, CgalMesh::Face_index>> pairs;
    PMP::self_intersections(m, std::back_inserter(pairs));
    if (pairs.empty()) return true;
    if (round == kUnfoldRounds || limit <= 0.0) return false;
    std::set<CgalMesh::Face_index> folded;
    for (const auto& [f, g] : pairs) folded.insert(f), folded.insert(g);
    std::vector<CgalMesh::Face_index> faces(folded.begin(), folded.end());
    sort_by_points(m, faces);
    std::int64_t now = 0;
    for (const auto f : faces) {
      if (m.is_removed(f)) continue;
      CgalMesh::Edge_index shortest;
      double lo = std::numeric_limits<double>::infinity(), hi = 0.0;
      for (const auto h : CGAL::halfedges_around_face(m.halfedge(f), m)) {
        const double l2 = squared_length(m, m.edge(h));
        if (l2 < lo) lo = l2, shortest = m.edge(h);
        hi = std::max(hi, l2);
      }
      if (lo < limit * limit && lo * 400.0 < hi && collapse(m, shortest)) ++now;
    }
    if (now == 0) return false;
    m.collect_garbage();
  }
}

}  // namespace

Vec3 float_rounded(const Vec3& p) { return Vec3(to_float(p.x), to_float(p.y), to_float(p.z)); }

void round_to_floats(TriangleMesh& mesh) {
  for (Vec3& v : mesh.vertices) v = float_rounded(v);
}

std::int64_t make_float_safe(TriangleMesh& band, const std::string& what, double needle_limit) {
  if (band.triangles.empty()) return 0;
  // A float converts to a double exactly, so the inexact-constructions kernel's predicates are exact on these points.
  CgalMesh m = to_half_edge_mesh<CgalMesh>(band);
  double largest = 0.0;
  for (const auto v : m.vertices()) {
    const auto& p = m.point(v);
    const Vec3 r = float_rounded(Vec3(p.x(), p.y(), p.z()));
    m.point(v) = CgalKernel::Point_3(r.x, r.y, r.z);
    largest = std::max({largest, std::abs(r.x), std::abs(r.y), std::abs(r.z)});
  }
  const std::int64_t before = static_cast<std::int64_t>(m.number_of_faces());
  // 16 floats' resolution at the largest coordinate, the gap trimmed_mesh.cpp keeps between the lattice and the wall.
  collapse_short_edges(m, std::ldexp(largest, -19));
  bool degenerate = false;
  for (const auto f : m.faces()) degenerate = degenerate || PMP::is_degenerate_triangle_face(f, m);
  if (degenerate) {
    if (!PMP::remove_degenerate_faces(m))
      throw std::runtime_error("mesh: a triangle of " + what + " made flat by rounding to floats cannot be removed");
    m.collect_garbage();
  }
  if (!unfold_needles(m, needle_limit))
    throw std::runtime_error("mesh: " + what + " intersects itself once rounded to floats");
  // Back as an indexed mesh of the vertices still in a triangle (a removal can leave one isolated).
  band.vertices.clear(), band.triangles.clear();
  std::vector<std::uint32_t> number(m.number_of_vertices() + m.number_of_removed_vertices(), UINT32_MAX);
  for (const auto f : m.faces()) {
    Triangle t;
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(m.halfedge(f), m)) {
      if (number[v] == UINT32_MAX) {
        number[v] = static_cast<std::uint32_t>(band.vertices.size());
        band.vertices.emplace_back(m.point(v).x(), m.point(v).y(), m.point(v).z());
      }
      t[k++] = number[v];
    }
    band.triangles.push_back(t);
  }
  return before - static_cast<std::int64_t>(m.number_of_faces());
}

}  // namespace steady
