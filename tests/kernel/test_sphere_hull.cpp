// The incremental hull of points on the unit sphere (mesh/sphere_hull.hpp) against CGAL's hull of all the points at
// once (convex_hull_3, put in the same canonical form): the same triangles, in the same order, whatever order the
// points come in, also where many points are cocircular (a hub's rings, the symmetric points of regular solids).
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/convex_hull_3.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <stdexcept>

#include "mesh/sphere_hull.hpp"

namespace steady {
namespace {

std::vector<Vec3> random_directions(std::mt19937_64& rng, int n) {
  std::normal_distribution<double> normal;
  std::vector<Vec3> points;
  for (int i = 0; i < n; ++i) points.push_back(glm::normalize(Vec3(normal(rng), normal(rng), normal(rng))));
  return points;
}

// Points on circles of the sphere (n on each, about random axes), as a hub template's rings are.
std::vector<Vec3> rings(std::mt19937_64& rng, int count, int n) {
  std::uniform_real_distribution<double> angle(0.2, 0.5);
  std::vector<Vec3> points;
  for (const Vec3& axis : random_directions(rng, count)) {
    const Vec3 e1 = glm::normalize(glm::cross(axis, std::abs(axis.x) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0)));
    const Vec3 e2 = glm::cross(axis, e1);
    const double a = angle(rng);
    for (int i = 0; i < n; ++i) {
      const double t = 2.0 * M_PI * i / n;
      points.push_back(glm::normalize(std::cos(a) * axis + std::sin(a) * (std::cos(t) * e1 + std::sin(t) * e2)));
    }
  }
  return points;
}

// CGAL's hull of the points, as triangles of their indices.
std::vector<Triangle> cgal_hull(const std::vector<Vec3>& points) {
  using Point = CGAL::Exact_predicates_inexact_constructions_kernel::Point_3;
  std::vector<Point> cgal;
  std::map<std::array<double, 3>, std::uint32_t> index;
  for (std::size_t i = 0; i < points.size(); ++i) {
    cgal.emplace_back(points[i].x, points[i].y, points[i].z);
    index[{points[i].x, points[i].y, points[i].z}] = static_cast<std::uint32_t>(i);
  }
  CGAL::Surface_mesh<Point> hull;
  CGAL::convex_hull_3(cgal.begin(), cgal.end(), hull);
  std::vector<Triangle> triangles;
  for (const auto f : hull.faces()) {
    Triangle t;
    int k = 0;
    for (const auto v : CGAL::vertices_around_face(hull.halfedge(f), hull)) {
      const Point& p = hull.point(v);
      t[k++] = index.at({p.x(), p.y(), p.z()});
    }
    triangles.push_back(t);
  }
  return canonical_hull_triangles(triangles, points);
}

// The first `start` points at once, the rest added one by one (each with a random "near" vertex that may be far
// away), against the hull of all of them at once.
void expect_same_as_at_once(const std::vector<Vec3>& points, std::size_t start, std::mt19937_64& rng) {
  SphereHull hull(std::vector<Vec3>(points.begin(), points.begin() + start));
  std::uniform_int_distribution<std::uint32_t> any(0, static_cast<std::uint32_t>(start - 1));
  for (std::size_t i = start; i < points.size(); ++i) hull.add(points[i], any(rng));
  const std::vector<Triangle> added = hull.triangles(), at_once = sphere_triangulation(points);
  const std::vector<Triangle> cgal = cgal_hull(points);
  EXPECT_EQ(added, cgal);
  EXPECT_EQ(at_once, cgal);
  EXPECT_EQ(cgal.size(), 2 * points.size() - 4);  // every point a vertex of a triangulated sphere (Euler)
}

TEST(SphereHull, PointsAddedOneByOneGiveTheHullOfAllAtOnce) {
  std::mt19937_64 rng(3);
  for (int trial = 0; trial < 20; ++trial) expect_same_as_at_once(random_directions(rng, 300), 20 + 10 * trial, rng);
}

TEST(SphereHull, CocircularPointsGiveTheSameCanonicalFacets) {
  std::mt19937_64 rng(8);
  for (int trial = 0; trial < 10; ++trial) {
    // Rings that are planar facets of the hull, between random points added in random order.
    std::vector<Vec3> points = rings(rng, 3, 8 + trial);
    std::vector<Vec3> others;
    for (const Vec3& p : random_directions(rng, 200)) {
      bool clear = true;
      for (std::size_t i = 0; i < points.size(); i += 8 + trial) {
        const Vec3 axis = glm::normalize(points[i] + points[i + (8 + trial) / 2]);
        clear = clear && glm::dot(p, axis) < glm::dot(points[i], axis) - 0.05;
      }
      if (clear) others.push_back(p);
    }
    std::shuffle(others.begin(), others.end(), rng);
    points.insert(points.end(), others.begin(), others.end());
    expect_same_as_at_once(points, points.size() - others.size() + 4, rng);
  }
  // The cube's and the octahedron's vertices: every face of the cube a planar facet of four points.
  std::vector<Vec3> solid;
  for (int i = 0; i < 8; ++i) solid.push_back(glm::normalize(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1)));
  for (int k = 0; k < 3; ++k)
    for (int s : {-1, 1}) {
      Vec3 p(0.0);
      p[k] = s;
      solid.push_back(p);
    }
  expect_same_as_at_once(solid, 8, rng);
}

TEST(SphereHull, APointThatIsNotAVertexIsAnError) {
  std::mt19937_64 rng(5);
  const std::vector<Vec3> points = random_directions(rng, 50);
  SphereHull inside(points);
  EXPECT_THROW(inside.add(0.5 * points[0] + 0.5 * points[1], 0), std::runtime_error);  // inside the hull
  SphereHull again(points);
  EXPECT_THROW(again.add(points[7], 7), std::runtime_error);  // already a vertex
}

}  // namespace
}  // namespace steady
