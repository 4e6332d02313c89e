#pragma once
// The triangulation of points on the unit sphere as their convex hull (the sphere's Delaunay triangulation), kept
// while points are added. A hub template refines its triangulation in rounds, each adding a few points inside
// triangles that are still too coarse; rebuilding the hull of every point in each round was most of a crowded
// template's time, and adding a point only replaces the triangles it sees (incremental convex hull).
//
// triangles() answers the same list whichever way the hull was reached: the convex hull of a set of points is
// unique but for how its planar facets (four or more cocircular points) are cut into triangles, and those facets
// are triangulated again from their smallest index, so the same points give the same triangles in the same
// order, built at once or one point at a time.
#include <array>
#include <cstdint>
#include <vector>

#include "steady/core/vec.hpp"
#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

class SphereHull {
 public:
  // The hull of `points` (unit vectors spread around the sphere's center, as a hub's are; each must be a vertex of
  // the hull: an error otherwise), built point by point as well.
  explicit SphereHull(const std::vector<Vec3>& points);

  // Adds a point (unit vector; its index is the number of points before it): the triangles it sees are replaced
  // by the fan from it to their boundary. The search for them walks from `near`, a vertex close to the point.
  // Throws when the point sees no triangle or hides a vertex (points closer than rounding); the hull is not to be
  // used after that.
  void add(const Vec3& point, std::uint32_t near);

  // The outward triangles, canonical (see above) and sorted, each starting from its smallest index.
  std::vector<Triangle> triangles() const;

 private:
  bool sees(std::uint32_t triangle, std::uint32_t point) const;
  std::uint32_t seeing_triangle(std::uint32_t point, std::uint32_t near) const;
  std::uint32_t new_triangle(const Triangle& corners);
  void insert(std::uint32_t point, std::uint32_t near);

  std::vector<Vec3> points_;
  std::vector<Triangle> corners_;                    // per triangle slot, outward
  std::vector<std::array<std::uint32_t, 3>> across_;  // across_[t][k]: the triangle across edge (k, k + 1)
  std::vector<char> alive_;
  std::vector<std::uint32_t> free_;
  std::vector<std::uint32_t> triangle_at_;  // per vertex: a live triangle it is a corner of
  std::vector<std::uint32_t> mark_;         // per triangle slot: seen or not by the point being inserted
  std::uint32_t stamp_ = 0;                 // the marks of the last insertion
};

// The canonical form of another triangulation of the hull of `points` (outward triangles of their indices): what
// SphereHull::triangles() answers for the same points. The tests compare CGAL's hull with this one so.
std::vector<Triangle> canonical_hull_triangles(std::vector<Triangle> triangles, const std::vector<Vec3>& points);

// The triangles of the convex hull of unit vectors (SphereHull(points).triangles()).
std::vector<Triangle> sphere_triangulation(const std::vector<Vec3>& directions);

}  // namespace steady
