#include "mesh/sphere_hull.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <array>
#include <map>
#include <stdexcept>
#include <string>
#include <unordered_map>

#include "core/disjoint_sets.hpp"

namespace steady {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;

[[noreturn]] void internal_error(const std::string& what) { throw std::runtime_error("mesh: " + what); }

Point cgal_point(const Vec3& p) { return Point(p.x, p.y, p.z); }

// Directed edge (a, b) as one key.
std::uint64_t edge_key(std::uint32_t a, std::uint32_t b) { return static_cast<std::uint64_t>(a) << 32 | b; }

// Four or more points of a sphere in one plane (symmetric hubs have them; every ring is one) can be triangulated in
// several ways, and the hull picks one depending on how it was built (one thread or two, at once or point by
// point). Each such planar facet (adjacent triangles whose corners are coplanar) is triangulated again as the fan
// from its smallest index: a choice that depends on the points alone. across[f][k]: the triangle across edge
// (k, k + 1) of triangle f.
void canonical_facets(std::vector<Triangle>& triangles, const std::vector<std::array<std::uint32_t, 3>>& across,
                      const std::vector<Vec3>& points) {
  DisjointSets facet(triangles.size());
  for (std::size_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const std::size_t g = across[f][k];
      if (g < f) continue;  // each edge once
      const std::uint32_t a = triangles[f][k], b = triangles[f][(k + 1) % 3], c = triangles[f][(k + 2) % 3];
      std::uint32_t d = 0;
      for (std::uint32_t v : triangles[g])
        if (v != a && v != b) d = v;
      if (CGAL::orientation(cgal_point(points[a]), cgal_point(points[b]), cgal_point(points[c]),
                            cgal_point(points[d])) == CGAL::COPLANAR)
        facet.join(f, g);
    }
  // Lone triangles stay (most of them); the planar facets' triangles, by facet, are triangulated again.
  std::vector<std::size_t> size(triangles.size(), 0);
  for (std::size_t f = 0; f < triangles.size(); ++f) ++size[facet.root(f)];
  std::vector<Triangle> out;
  out.reserve(triangles.size());
  std::vector<std::pair<std::size_t, std::size_t>> in_facet;  // (facet, triangle)
  for (std::size_t f = 0; f < triangles.size(); ++f) {
    if (size[facet.root(f)] == 1) out.push_back(triangles[f]);
    else in_facet.emplace_back(facet.root(f), f);
  }
  std::sort(in_facet.begin(), in_facet.end());
  for (std::size_t i = 0; i < in_facet.size();) {
    const std::size_t id = in_facet[i].first;
    std::vector<std::size_t> faces;
    for (; i < in_facet.size() && in_facet[i].first == id; ++i) faces.push_back(in_facet[i].second);
    // The facet's boundary: its directed edges whose twin lies outside it, chained into the polygon.
    std::map<std::uint32_t, std::uint32_t> next;
    for (std::size_t f : faces)
      for (int k = 0; k < 3; ++k)
        if (facet.root(across[f][k]) != id) next[triangles[f][k]] = triangles[f][(k + 1) % 3];
    std::uint32_t start = next.begin()->first;  // the smallest index on the boundary
    std::vector<std::uint32_t> polygon{start};
    for (std::uint32_t v = next.at(start); v != start; v = next.at(v)) polygon.push_back(v);
    if (polygon.size() != faces.size() + 2) internal_error("a planar facet of a hub's sphere is not a convex polygon");
    for (std::size_t j = 1; j + 1 < polygon.size(); ++j) out.push_back({polygon[0], polygon[j], polygon[j + 1]});
  }
  triangles = std::move(out);
}


// The hull of all points at once by CGAL, as outward triangles of the points' indices.
std::vector<Triangle> cgal_hull(const std::vector<Point>& points) {
  using Key = std::array<double, 3>;
  // Only looked up, so hashed (on the bits, with -0 as 0 since they compare equal).
  struct KeyHash {
    std::size_t operator()(const Key& k) const {
      std::size_t h = 0;
      for (double d : k) h = h * 0x9E3779B97F4A7C15ULL + std::hash<double>()(d == 0.0 ? 0.0 : d);
      return h;
    }
  };
  std::unordered_map<Key, std::uint32_t, KeyHash> index;
  index.reserve(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    index.emplace(Key{points[i].x(), points[i].y(), points[i].z()}, static_cast<std::uint32_t>(i));
  if (index.size() != points.size()) internal_error("two points of a hub's sphere coincide");
  Mesh hull;
  CGAL::convex_hull_3(points.begin(), points.end(), hull);
  if (hull.number_of_vertices() != points.size()) internal_error("a point of a hub's sphere is not on its hull");
  std::vector<Triangle> triangles;
  triangles.reserve(hull.number_of_faces());
  for (const auto f : hull.faces()) {
    Triangle t;
    int i = 0;
    for (const auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) {
      const Point& p = hull.point(v);
      t[i++] = index.at(Key{p.x(), p.y(), p.z()});
    }
    triangles.push_back(t);
  }
  return triangles;
}

}  // namespace

SphereHull::SphereHull(const std::vector<Vec3>& points) : points_(points) {
  std::vector<Point> cgal;
  for (const Vec3& p : points) cgal.push_back(cgal_point(p));
  corners_ = cgal_hull(cgal);
  alive_.assign(corners_.size(), 1);
  triangle_at_.assign(points.size(), 0);
  std::unordered_map<std::uint64_t, std::uint32_t> face_of;
  face_of.reserve(3 * corners_.size());
  for (std::uint32_t t = 0; t < corners_.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      face_of[edge_key(corners_[t][k], corners_[t][(k + 1) % 3])] = t;
      triangle_at_[corners_[t][k]] = t;
    }
  across_.resize(corners_.size());
  for (std::uint32_t t = 0; t < corners_.size(); ++t)
    for (int k = 0; k < 3; ++k) across_[t][k] = face_of.at(edge_key(corners_[t][(k + 1) % 3], corners_[t][k]));
}

bool SphereHull::sees(std::uint32_t t, std::uint32_t point) const {
  const Triangle& c = corners_[t];
  return CGAL::orientation(cgal_point(points_[c[0]]), cgal_point(points_[c[1]]), cgal_point(points_[c[2]]),
                           cgal_point(points_[point])) == CGAL::POSITIVE;  // beyond the outward triangle's plane
}

std::uint32_t SphereHull::seeing_triangle(std::uint32_t point, const std::vector<std::uint32_t>& near) const {
  // The triangles around each near vertex (walked through the adjacency), then every triangle.
  for (std::uint32_t v : near) {
    const std::uint32_t first = triangle_at_[v];
    std::uint32_t t = first;
    for (std::size_t step = 0; step < corners_.size(); ++step) {
      if (sees(t, point)) return t;
      const int k = static_cast<int>(std::find(corners_[t].begin(), corners_[t].end(), v) - corners_[t].begin());
      t = across_[t][k];  // across the edge leaving v: the next triangle around v
      if (t == first) break;
    }
  }
  for (std::uint32_t t = 0; t < corners_.size(); ++t)
    if (alive_[t] && sees(t, point)) return t;
  internal_error("a point of a hub's sphere is not on its hull");
}

std::uint32_t SphereHull::new_triangle(const Triangle& corners) {
  std::uint32_t t;
  if (!free_.empty()) {
    t = free_.back();
    free_.pop_back();
    corners_[t] = corners;
    alive_[t] = 1;
  } else {
    t = static_cast<std::uint32_t>(corners_.size());
    corners_.push_back(corners);
    across_.emplace_back();
    alive_.push_back(1);
  }
  return t;
}

void SphereHull::add(const Vec3& point, const std::vector<std::uint32_t>& near) {
  const auto p = static_cast<std::uint32_t>(points_.size());
  points_.push_back(point);
  triangle_at_.push_back(0);
  // The triangles p sees form a disk (p lies outside the hull); its boundary edges keep their outer neighbours.
  std::vector<std::uint32_t> seen{seeing_triangle(p, near)}, stack = seen;
  std::map<std::uint32_t, bool> visited{{seen[0], true}};
  struct Rim {
    std::uint32_t a, b, outside;
  };
  std::vector<Rim> rim;
  while (!stack.empty()) {
    const std::uint32_t t = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t n = across_[t][k];
      auto [it, fresh] = visited.emplace(n, false);
      if (fresh) {
        it->second = sees(n, p);
        if (it->second) seen.push_back(n), stack.push_back(n);
      }
      if (!it->second) rim.push_back({corners_[t][k], corners_[t][(k + 1) % 3], n});
    }
  }
  // A corner of a seen triangle off the rim would no longer be a vertex of the hull.
  std::vector<std::uint32_t> on_rim;
  for (const Rim& r : rim) on_rim.push_back(r.a);
  std::sort(on_rim.begin(), on_rim.end());
  for (std::uint32_t t : seen)
    for (std::uint32_t v : corners_[t])
      if (!std::binary_search(on_rim.begin(), on_rim.end(), v))
        internal_error("a point of a hub's sphere is not on its hull");
  for (std::uint32_t t : seen) alive_[t] = 0, free_.push_back(t);
  // The fan: triangle (a, b, p) per rim edge, joined to the outside across (a, b) and to its two fan neighbours.
  std::map<std::uint32_t, std::uint32_t> from, to;  // rim vertex -> the fan triangle whose rim edge starts / ends there
  for (const Rim& r : rim) {
    const std::uint32_t t = new_triangle({r.a, r.b, p});
    from[r.a] = t, to[r.b] = t;
    across_[t][0] = r.outside;
    std::array<std::uint32_t, 3>& back = across_[r.outside];
    for (int k = 0; k < 3; ++k)
      if (corners_[r.outside][k] == r.b && corners_[r.outside][(k + 1) % 3] == r.a) back[k] = t;
    triangle_at_[r.a] = triangle_at_[r.b] = triangle_at_[p] = t;
  }
  if (from.size() != rim.size() || to.size() != rim.size())
    internal_error("the triangles a point of a hub's sphere sees do not form a disk");
  for (const Rim& r : rim) {
    const std::uint32_t t = from.at(r.a);
    across_[t][1] = from.at(r.b);  // edge (b, p): the fan triangle starting at b
    across_[t][2] = to.at(r.a);    // edge (p, a): the one ending at a
  }
}

std::vector<Triangle> SphereHull::triangles() const {
  // The live slots, numbered in order.
  std::vector<std::uint32_t> number(corners_.size(), 0);
  std::vector<Triangle> triangles;
  for (std::size_t t = 0; t < corners_.size(); ++t)
    if (alive_[t]) number[t] = static_cast<std::uint32_t>(triangles.size()), triangles.push_back(corners_[t]);
  std::vector<std::array<std::uint32_t, 3>> across;
  across.reserve(triangles.size());
  for (std::size_t t = 0; t < corners_.size(); ++t)
    if (alive_[t]) across.push_back({number[across_[t][0]], number[across_[t][1]], number[across_[t][2]]});
  canonical_facets(triangles, across, points_);
  // Each triangle from its smallest index, the list sorted: the same points give the same triangles in the same
  // order however the hull was built.
  for (Triangle& t : triangles) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

std::vector<Triangle> sphere_triangulation(const std::vector<Vec3>& directions) {
  return SphereHull(directions).triangles();
}

}  // namespace steady
