// The band's repair after rounding to 32-bit floats: an edge far below a float's resolution collapses, the
// triangles it made flat go, and the mesh stays closed and 2-manifold with every vertex a float.
#include <gtest/gtest.h>

#include "mesh/float_safe.hpp"

namespace steady {
namespace {

// An octahedron around (10, 10, 10) whose top vertex is split in two, 1e-9 apart along x, joined by an edge
// between two thin triangles: closed and 2-manifold in double, two triangles flat in floats.
TriangleMesh split_octahedron() {
  TriangleMesh m;
  const Vec3 c(10.0, 10.0, 10.0);
  m.vertices = {c + Vec3(1, 0, 0), c + Vec3(0, 1, 0), c + Vec3(-1, 0, 0), c + Vec3(0, -1, 0),
                c + Vec3(0, 0, -1), c + Vec3(0, 0, 1), c + Vec3(1e-9, 0, 1)};
  const std::uint32_t top = 5, top2 = 6, bottom = 4;
  for (std::uint32_t i = 0; i < 4; ++i) m.triangles.push_back({bottom, (i + 1) % 4, i});
  m.triangles.push_back({top2, 3, 0});
  m.triangles.push_back({top2, 0, 1});
  m.triangles.push_back({top, 1, 2});
  m.triangles.push_back({top, 2, 3});
  m.triangles.push_back({top2, 1, top});
  m.triangles.push_back({top, 3, top2});
  return m;
}

TEST(FloatSafe, AnEdgeBelowAFloatCollapses) {
  TriangleMesh m = split_octahedron();
  ASSERT_TRUE(mesh_edge_report(m).closed_manifold());
  const double volume = mesh_volume(m);
  EXPECT_EQ(make_float_safe(m, "the band"), 2);
  EXPECT_EQ(m.triangles.size(), 8u);
  EXPECT_EQ(m.vertices.size(), 6u);
  EXPECT_TRUE(mesh_edge_report(m).closed_manifold());
  for (const Vec3& v : m.vertices) EXPECT_EQ(float_rounded(v), v);
  EXPECT_NEAR(mesh_volume(m), volume, 1e-5);
}

TEST(FloatSafe, AMeshAlreadySafeIsOnlyRounded) {
  TriangleMesh m = split_octahedron();
  m.vertices[6].x += 0.25;  // the split is now far above a float's resolution
  const std::size_t triangles = m.triangles.size();
  EXPECT_EQ(make_float_safe(m, "the band"), 0);
  EXPECT_EQ(m.triangles.size(), triangles);
  EXPECT_TRUE(mesh_edge_report(m).closed_manifold());
}

}  // namespace
}  // namespace steady
