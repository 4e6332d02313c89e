#include "mesh/sphere_hull.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <algorithm>
#include <array>
#include <map>
#include <stdexcept>
#include <string>

#include "core/disjoint_sets.hpp"

namespace steady {

namespace {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;

[[noreturn]] void internal_error(const std::string& what) { throw std::runtime_error("mesh: " + what); }

Point cgal_point(const Vec3& p) { return Point(p.x, p.y, p.z); }

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


// A key along a Z-order curve through the cube around the sphere: points inserted in its order follow each other
// closely, so the walk from the last one to the next is short.
std::uint64_t z_order(const Vec3& p) {
  auto spread = [](std::uint64_t v) {  // the 21 bits of v, two zeros after each
    v &= 0x1fffff;
    v = (v | v << 32) & 0x1f00000000ffffULL;
    v = (v | v << 16) & 0x1f0000ff0000ffULL;
    v = (v | v << 8) & 0x100f00f00f00f00fULL;
    v = (v | v << 4) & 0x10c30c30c30c30c3ULL;
    v = (v | v << 2) & 0x1249249249249249ULL;
    return v;
  };
  auto cell = [](double x) { return static_cast<std::uint64_t>(std::clamp(0.5 * (x + 1.0), 0.0, 1.0) * 2097151.0); };
  return spread(cell(p.x)) | spread(cell(p.y)) << 1 | spread(cell(p.z)) << 2;
}

}  // namespace

SphereHull::SphereHull(const std::vector<Vec3>& points) : points_(points), triangle_at_(points.size(), 0) {
  const std::uint32_t n = static_cast<std::uint32_t>(points.size());
  if (n < 4) internal_error("a hub's sphere needs four points at least");
  // First the points farthest along +-x, +-y, +-z: their hull holds the sphere's center, so from then on a point's
  // direction leads the walk to the triangles it sees. A tetrahedron of four of them not in one plane, outward.
  std::vector<std::uint32_t> first;
  for (int axis = 0; axis < 3; ++axis)
    for (double sign : {1.0, -1.0}) {
      std::uint32_t best = 0;
      for (std::uint32_t i = 1; i < n; ++i)
        if (sign * points[i][axis] > sign * points[best][axis]) best = i;
      if (std::find(first.begin(), first.end(), best) == first.end()) first.push_back(best);
    }
  std::array<std::uint32_t, 4> tetra{};
  std::size_t found = 0;
  for (std::uint32_t i : first) {
    const Point p = cgal_point(points[i]);
    const bool fits = found == 0 || (found == 1 && p != cgal_point(points[tetra[0]])) ||
                      (found == 2 && !CGAL::collinear(cgal_point(points[tetra[0]]), cgal_point(points[tetra[1]]), p)) ||
                      (found == 3 && CGAL::orientation(cgal_point(points[tetra[0]]), cgal_point(points[tetra[1]]),
                                                       cgal_point(points[tetra[2]]), p) != CGAL::COPLANAR);
    if (found < 4 && fits) tetra[found++] = i;
  }
  if (found < 4) internal_error("the points of a hub's sphere lie in one plane");
  if (CGAL::orientation(cgal_point(points[tetra[0]]), cgal_point(points[tetra[1]]), cgal_point(points[tetra[2]]),
                        cgal_point(points[tetra[3]])) == CGAL::NEGATIVE)
    std::swap(tetra[1], tetra[2]);
  const auto [a, b, c, d] = tetra;  // d on the positive side of (a, b, c): the outward faces turn the other way
  corners_ = {{a, c, b}, {a, b, d}, {b, c, d}, {a, d, c}};
  across_.resize(4);
  for (std::uint32_t t = 0; t < 4; ++t)
    for (int k = 0; k < 3; ++k)
      for (std::uint32_t u = 0; u < 4; ++u)
        for (int j = 0; j < 3; ++j)
          if (corners_[u][j] == corners_[t][(k + 1) % 3] && corners_[u][(j + 1) % 3] == corners_[t][k])
            across_[t][k] = u;
  alive_.assign(4, 1);
  for (std::uint32_t t = 0; t < 4; ++t)
    for (std::uint32_t v : corners_[t]) triangle_at_[v] = t;
  std::vector<char> in(n, 0);
  for (std::uint32_t v : tetra) in[v] = 1;
  // The rest of the first six, then every other point along the Z-order curve, each walked to from the last.
  std::vector<std::uint32_t> order;
  for (std::uint32_t i : first)
    if (!in[i]) order.push_back(i), in[i] = 1;
  std::vector<std::pair<std::uint64_t, std::uint32_t>> rest;
  for (std::uint32_t i = 0; i < n; ++i)
    if (!in[i]) rest.emplace_back(z_order(points[i]), i);
  std::sort(rest.begin(), rest.end());
  for (const auto& [key, i] : rest) order.push_back(i);
  std::uint32_t last = d;
  for (std::uint32_t i : order) insert(i, last), last = i;
}

bool SphereHull::sees(std::uint32_t t, std::uint32_t point) const {
  const Triangle& c = corners_[t];
  return CGAL::orientation(cgal_point(points_[c[0]]), cgal_point(points_[c[1]]), cgal_point(points_[c[2]]),
                           cgal_point(points_[point])) == CGAL::POSITIVE;  // beyond the outward triangle's plane
}

std::uint32_t SphereHull::seeing_triangle(std::uint32_t point, std::uint32_t near) const {
  // The walk toward the point's direction: from a triangle that does not see it, across an edge whose great circle
  // has the point on the far side (the center lies inside the hull, so the hull's triangles project onto the
  // sphere's triangulation, which such a walk crosses to the triangle holding the direction: that one sees it).
  const Point center(0.0, 0.0, 0.0), p = cgal_point(points_[point]);
  std::uint32_t t = triangle_at_[near];
  for (std::size_t step = 0; step < corners_.size(); ++step) {
    if (sees(t, point)) return t;
    const Triangle& c = corners_[t];
    int beyond = -1;
    for (int k = 0; k < 3 && beyond < 0; ++k)
      if (CGAL::orientation(center, cgal_point(points_[c[k]]), cgal_point(points_[c[(k + 1) % 3]]), p) ==
          CGAL::NEGATIVE)
        beyond = k;
    if (beyond < 0) break;
    t = across_[t][beyond];
  }
  for (std::uint32_t u = 0; u < corners_.size(); ++u)  // not reached while the center lies inside
    if (alive_[u] && sees(u, point)) return u;
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

void SphereHull::add(const Vec3& point, std::uint32_t near) {
  const auto p = static_cast<std::uint32_t>(points_.size());
  points_.push_back(point);
  triangle_at_.push_back(0);
  insert(p, near);
}

void SphereHull::insert(std::uint32_t p, std::uint32_t near) {
  // The triangles p sees form a disk (p lies outside the hull); its boundary edges keep their outer neighbours.
  mark_.resize(corners_.size(), 0);
  const std::uint32_t seen_mark = ++stamp_, unseen_mark = ++stamp_;  // this insertion's marks
  std::vector<std::uint32_t> seen{seeing_triangle(p, near)}, stack = seen;
  mark_[seen[0]] = seen_mark;
  struct Rim {
    std::uint32_t a, b, outside;
  };
  std::vector<Rim> rim;
  while (!stack.empty()) {
    const std::uint32_t t = stack.back();
    stack.pop_back();
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t n = across_[t][k];
      if (mark_[n] != seen_mark && mark_[n] != unseen_mark) {
        mark_[n] = sees(n, p) ? seen_mark : unseen_mark;
        if (mark_[n] == seen_mark) seen.push_back(n), stack.push_back(n);
      }
      if (mark_[n] == unseen_mark) rim.push_back({corners_[t][k], corners_[t][(k + 1) % 3], n});
    }
  }
  // A corner of a seen triangle off the rim would no longer be a vertex of the hull.
  std::vector<std::uint32_t> on_rim;
  for (const Rim& r : rim) on_rim.push_back(r.a);
  std::sort(on_rim.begin(), on_rim.end());
  if (std::adjacent_find(on_rim.begin(), on_rim.end()) != on_rim.end())
    internal_error("the triangles a point of a hub's sphere sees do not form a disk");
  for (std::uint32_t t : seen)
    for (std::uint32_t v : corners_[t])
      if (!std::binary_search(on_rim.begin(), on_rim.end(), v))
        internal_error("a point of a hub's sphere is not on its hull");
  for (std::uint32_t t : seen) alive_[t] = 0, free_.push_back(t);
  // The fan: triangle (a, b, p) per rim edge, joined to the outside across (a, b) and to its two fan neighbours.
  std::vector<std::uint32_t> fan(rim.size());
  for (std::size_t i = 0; i < rim.size(); ++i) {
    const Rim& r = rim[i];
    const std::uint32_t t = fan[i] = new_triangle({r.a, r.b, p});
    across_[t][0] = r.outside;
    std::array<std::uint32_t, 3>& back = across_[r.outside];
    for (int k = 0; k < 3; ++k)
      if (corners_[r.outside][k] == r.b && corners_[r.outside][(k + 1) % 3] == r.a) back[k] = t;
    triangle_at_[r.a] = triangle_at_[r.b] = triangle_at_[p] = t;
  }
  // Rim vertex -> the fan triangle whose rim edge starts there (each starts one edge: checked above).
  auto starting_at = [&](std::uint32_t v) {
    const auto it = std::lower_bound(on_rim.begin(), on_rim.end(), v);
    return it;
  };
  std::vector<std::uint32_t> from(rim.size()), to(rim.size());  // by the rank of the rim vertex in on_rim
  for (std::size_t i = 0; i < rim.size(); ++i) {
    from[starting_at(rim[i].a) - on_rim.begin()] = fan[i];
    const auto end = starting_at(rim[i].b);
    if (end == on_rim.end() || *end != rim[i].b)
      internal_error("the triangles a point of a hub's sphere sees do not form a disk");
    to[end - on_rim.begin()] = fan[i];
  }
  for (std::size_t i = 0; i < rim.size(); ++i) {
    const std::uint32_t t = fan[i];
    across_[t][1] = from[starting_at(rim[i].b) - on_rim.begin()];  // edge (b, p): the fan triangle starting at b
    across_[t][2] = to[starting_at(rim[i].a) - on_rim.begin()];    // edge (p, a): the one ending at a
  }
}

namespace {

// The canonical triangles (planar facets again as fans, each triangle from its smallest index, sorted): the same
// points give the same triangles in the same order however the hull was built.
using Adjacency = std::vector<std::array<std::uint32_t, 3>>;  // per triangle, the triangles across its edges

std::vector<Triangle> canonical(std::vector<Triangle> triangles, const Adjacency& across,
                                const std::vector<Vec3>& points) {
  canonical_facets(triangles, across, points);
  for (Triangle& t : triangles) std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
  std::sort(triangles.begin(), triangles.end());
  return triangles;
}

}  // namespace

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
  return canonical(std::move(triangles), across, points_);
}

std::vector<Triangle> canonical_hull_triangles(std::vector<Triangle> triangles, const std::vector<Vec3>& points) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> face_of;  // directed edge -> its triangle
  for (std::uint32_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) face_of[{triangles[f][k], triangles[f][(k + 1) % 3]}] = f;
  std::vector<std::array<std::uint32_t, 3>> across(triangles.size());
  for (std::uint32_t f = 0; f < triangles.size(); ++f)
    for (int k = 0; k < 3; ++k) across[f][k] = face_of.at({triangles[f][(k + 1) % 3], triangles[f][k]});
  return canonical(std::move(triangles), across, points);
}

std::vector<Triangle> sphere_triangulation(const std::vector<Vec3>& directions) {
  return SphereHull(directions).triangles();
}

}  // namespace steady
