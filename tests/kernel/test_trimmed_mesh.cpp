// Lattices trimmed into a body as meshes, with and without a skin: closed, oriented, no self-intersection (CGAL's
// own checks), and the volume of lattice ∩ body (∪ skin) by Monte Carlo over point membership (the slow twin)
// within the chord bound.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include <array>
#include <map>
#include <random>
#include <sstream>

#include <tbb/global_control.h>

#include "brick_definition.hpp"
#include "lattice_test_shapes.hpp"
#include "test_support.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "steady/lattice/presets.hpp"
#include "steady/mesh/lattice_mesh.hpp"
#include "steady/mesh/trimmed_mesh.hpp"
#include "steady/query/lattice_query.hpp"
#include "steady/query/queries.hpp"

namespace steady {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;

// A closed, outward prism over a regular n-gon (n = 4: a box turned by `turn`), between heights z0 and z1.
TriangleMesh prism(const Vec3& center, double radius, double z0, double z1, int n, double turn) {
  TriangleMesh m;
  for (double z : {z0, z1})
    for (int i = 0; i < n; ++i) {
      const double a = turn + 2.0 * M_PI * i / n;
      m.vertices.emplace_back(center.x + radius * std::cos(a), center.y + radius * std::sin(a), z);
    }
  const auto bottom = static_cast<std::uint32_t>(m.vertices.size());
  m.vertices.emplace_back(center.x, center.y, z0);
  m.vertices.emplace_back(center.x, center.y, z1);
  const auto N = static_cast<std::uint32_t>(n);
  for (std::uint32_t i = 0; i < N; ++i) {
    const std::uint32_t j = (i + 1) % N;
    m.triangles.push_back({i, j, N + j});
    m.triangles.push_back({i, N + j, N + i});
    m.triangles.push_back({bottom, j, i});
    m.triangles.push_back({bottom + 1, N + i, N + j});
  }
  return m;
}

bool inside_prism(const Vec3& p, const Vec3& center, double radius, double z0, double z1, int n, double turn) {
  if (p.z < z0 || p.z > z1) return false;
  for (int i = 0; i < n; ++i) {  // inside every edge's half-plane
    const double a = turn + 2.0 * M_PI * i / n, b = turn + 2.0 * M_PI * (i + 1) / n;
    const Vec3 u(radius * std::cos(a), radius * std::sin(a), 0.0), v(radius * std::cos(b), radius * std::sin(b), 0.0);
    const Vec3 q = p - center;
    if ((v.x - u.x) * (q.y - u.y) - (v.y - u.y) * (q.x - u.x) < 0.0) return false;
  }
  return true;
}

struct Prism {
  Vec3 center;
  double radius, z0, z1;
  int n;
  double turn;
  TriangleMesh mesh(double inset = 0.0) const {
    return prism(center, (radius - inset / std::cos(M_PI / n)), z0 + inset, z1 - inset, n, turn);
  }
  bool contains(const Vec3& p, double inset = 0.0) const {
    return inside_prism(p, center, radius - inset / std::cos(M_PI / n), z0 + inset, z1 - inset, n, turn);
  }
};

// The mesh as an STL or 3MF reader sees it: every vertex rounded to a 32-bit float, vertices welded by those
// coordinates. It must still be closed, 2-manifold, without flat triangles or self-intersections, in as many parts
// as before rounding.
void expect_float_safe(const TriangleMesh& mesh) {
  std::map<std::array<float, 3>, std::size_t> weld;
  std::vector<K::Point_3> points;
  std::vector<std::size_t> to(mesh.vertices.size());
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const Vec3& v = mesh.vertices[i];
    const std::array<float, 3> f{static_cast<float>(v.x), static_cast<float>(v.y), static_cast<float>(v.z)};
    const auto [it, fresh] = weld.emplace(f, points.size());
    if (fresh) points.emplace_back(f[0], f[1], f[2]);
    to[i] = it->second;
  }
  TriangleMesh welded;
  for (const K::Point_3& p : points) welded.vertices.emplace_back(p.x(), p.y(), p.z());
  std::vector<std::vector<std::size_t>> polygons;
  int flat = 0;
  for (const Triangle& t : mesh.triangles) {
    const std::size_t a = to[t[0]], b = to[t[1]], c = to[t[2]];
    flat += a == b || b == c || c == a || CGAL::collinear(points[a], points[b], points[c]);
    polygons.push_back({a, b, c});
    welded.triangles.push_back({static_cast<std::uint32_t>(a), static_cast<std::uint32_t>(b), static_cast<std::uint32_t>(c)});
  }
  EXPECT_EQ(flat, 0) << "flat triangles after rounding to floats";
  EXPECT_TRUE(mesh_edge_report(welded).closed_manifold()) << "after rounding to floats";
  const bool soup_is_mesh = CGAL::Polygon_mesh_processing::is_polygon_soup_a_polygon_mesh(polygons);
  EXPECT_TRUE(soup_is_mesh) << "after rounding to floats, a vertex or edge is not manifold";
  if (flat > 0 || !soup_is_mesh) return;
  CGAL::Surface_mesh<K::Point_3> sm;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, sm);
  EXPECT_FALSE(CGAL::Polygon_mesh_processing::does_self_intersect(sm)) << "after rounding to floats";
  auto component = sm.add_property_map<CGAL::Surface_mesh<K::Point_3>::Face_index, std::size_t>("f:c").first;
  CGAL::Surface_mesh<K::Point_3> unrounded;
  std::vector<K::Point_3> exact;
  for (const Vec3& v : mesh.vertices) exact.emplace_back(v.x, v.y, v.z);
  std::vector<std::vector<std::size_t>> triangles;
  for (const Triangle& t : mesh.triangles) triangles.push_back({t[0], t[1], t[2]});
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(exact, triangles, unrounded);
  auto unrounded_component = unrounded.add_property_map<CGAL::Surface_mesh<K::Point_3>::Face_index, std::size_t>("f:c").first;
  EXPECT_EQ(CGAL::Polygon_mesh_processing::connected_components(sm, component),
            CGAL::Polygon_mesh_processing::connected_components(unrounded, unrounded_component))
      << "rounding to floats split or joined parts";
}

void expect_trimmed(const Lattice& lattice, const Prism& body, double skin, double tolerance, const std::string& what) {
  SCOPED_TRACE(what);
  const FlatLattice f = flatten(lattice);
  const TriangleMesh outer = body.mesh(), inner = body.mesh(skin);
  TrimmedMeshRequest request;
  request.body = &outer;
  if (skin > 0.0) request.inner = &inner;
  TrimmedMeshStats stats;
  const TriangleMesh mesh = trimmed_lattice_mesh(f, {tolerance}, request, &stats);
  EXPECT_GT(stats.crossing_hubs, 0);
  EXPECT_TRUE(mesh_edge_report(mesh).closed_manifold());
  std::vector<K::Point_3> points;
  for (const Vec3& v : mesh.vertices) points.emplace_back(v.x, v.y, v.z);
  std::vector<std::vector<std::size_t>> polygons;
  for (const Triangle& t : mesh.triangles) polygons.push_back({t[0], t[1], t[2]});
  CGAL::Surface_mesh<K::Point_3> sm;
  CGAL::Polygon_mesh_processing::polygon_soup_to_polygon_mesh(points, polygons, sm);
  EXPECT_FALSE(CGAL::Polygon_mesh_processing::does_self_intersect(sm));
  expect_float_safe(mesh);
  // Monte Carlo over the body's bounding box with point membership.
  const LatticeQuery query(lattice);
  const LatticeSource source(query);
  const Vec3 lo(body.center.x - body.radius, body.center.y - body.radius, body.z0);
  const Vec3 hi(body.center.x + body.radius, body.center.y + body.radius, body.z1);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const int n = 300000;
  std::vector<double> p(3 * n);
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < 3; ++k) p[3 * i + k] = lo[k] + (hi[k] - lo[k]) * u01(rng);
  std::vector<std::uint8_t> in(n);
  contains(source, p.data(), n, in.data());
  int hits = 0;
  for (int i = 0; i < n; ++i) {
    const Vec3 x(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    if (!body.contains(x)) continue;
    hits += skin > 0.0 ? (!body.contains(x, skin) || in[i]) : in[i];
  }
  const double box = (hi.x - lo.x) * (hi.y - lo.y) * (hi.z - lo.z), fraction = double(hits) / n;
  const double expected = box * fraction, sigma = box * std::sqrt(fraction * (1.0 - fraction) / n);
  const double volume = mesh_volume(mesh);
  EXPECT_LE(volume, expected + 4.0 * sigma);
  EXPECT_GE(volume, expected - 4.0 * sigma - tolerance * mesh_area(mesh));
  std::cout << what << ": " << mesh.triangles.size() << " triangles, hubs inside / crossing / outside "
            << stats.inside_hubs << " / " << stats.crossing_hubs << " / " << stats.outside_hubs << ", band "
            << stats.band_triangles << " triangles, Booleans " << stats.boolean_seconds << " s, "
            << stats.moved_clear << " vertices moved off the wall, " << stats.float_removed_triangles << " triangles removed after rounding to floats; volume " << volume
            << ", Monte Carlo " << expected << " +- " << sigma << "\n";
}

TEST(TrimmedMesh, OctetInATurnedBoxAndAPrismWithAndWithoutSkin) {
  const Lattice octet = preset_lattice("octet", {3, 3, 3}, 2.0, 0.3, 0.15);
  const Prism box{{2.9, 2.8, 0.0}, 3.3, 0.6, 4.9, 4, 0.3};
  const Prism hexagon{{3.0, 3.0, 0.0}, 2.9, 0.45, 5.2, 6, 0.1};
  for (double skin : {0.0, 0.35}) {
    expect_trimmed(octet, box, skin, 0.01, "box, skin " + std::to_string(skin));
    expect_trimmed(octet, hexagon, skin, 0.01, "hexagon, skin " + std::to_string(skin));
  }
}

TEST(TrimmedMesh, CrowdedAndHullModelHubs) {
  const Prism hexagon{{3.0, 3.0, 0.0}, 2.9, 0.45, 5.2, 6, 0.1};
  expect_trimmed(preset_lattice("octet", {3, 3, 3}, 2.0, 0.3, 0.24), hexagon, 0.0, 0.01, "thick octet");
  expect_trimmed(preset_lattice("BCC", {3, 3, 3}, 2.0, 0.25, 0.0), hexagon, 0.3, 0.01, "hull BCC, skin");
}

// A diamond lattice tapered along U (cells of 1, nodes 0.45 of the neighbour distance, beams half their nodes): its
// nodes meet nodes they share no beam with, so its hubs are meshed as united groups (mesh_groups.hpp), and a group
// the surface crosses goes through the band's Boolean whole.
TEST(TrimmedMesh, HubsUnitedInGroupsAreTrimmedAsOnePiece) {
  test::BrickDefinition d = test::preset_brick("diamond", 0.45, 0.5, {3, 3, 3});
  d.u = {Similarity::dilation(1.05, {-20.0, 0.5, 0.5})};
  const Lattice diamond(d);
  LatticeMeshStats whole;
  lattice_mesh(diamond, {0.01}, &whole);
  EXPECT_GT(whole.foreign_groups, 0);
  const Prism hexagon{{1.5, 1.5, 0.0}, 1.2, 0.3, 2.2, 6, 0.1};
  for (double skin : {0.0, 0.15}) expect_trimmed(diamond, hexagon, skin, 0.01, "tapered diamond, skin " + std::to_string(skin));
}

// The lattice vertex nearest height 3.3 within 1.5 of `center` across (a box's middle, not its edges).
Vec3 vertex_to_graze(const TriangleMesh& lattice, const Vec3& center) {
  Vec3 graze(0.0, 0.0, HUGE_VAL);
  for (const Vec3& v : lattice.vertices)
    if (std::hypot(v.x - center.x, v.y - center.y) < 1.5 && std::abs(v.z - 3.3) < std::abs(graze.z - 3.3)) graze = v;
  return graze;
}

// A lattice vertex 1e-8 inside the wall the band is cut at: the Boolean leaves edges far shorter than a float's
// resolution there, which must not reach the output as merged vertices or flat triangles.
TEST(TrimmedMesh, AVertexGrazingTheWallStaysSafeInFloats) {
  const Lattice octet = preset_lattice("octet", {3, 3, 3}, 2.0, 0.3, 0.15);
  const TriangleMesh whole = lattice_mesh(octet, {0.01});
  const Vec3 center(2.9, 2.8, 0.0);
  const Vec3 graze = vertex_to_graze(whole, center);
  for (double skin : {0.0, 0.35}) {
    const Prism box{center, 3.3, 0.6, graze.z - 1e-8 + skin, 4, 0.3};
    expect_trimmed(octet, box, skin, 0.01, "grazing vertex, skin " + std::to_string(skin));
  }
}

// One thread or all of them give the same mesh, bit for bit, here with vertices moved off the wall and a skin.
TEST(TrimmedMesh, SameMeshWhateverTheNumberOfThreads) {
  const Lattice octet = preset_lattice("octet", {3, 3, 3}, 2.0, 0.3, 0.15);
  const FlatLattice f = flatten(octet);
  const TriangleMesh whole = lattice_mesh(f, {0.01});
  const Vec3 center(2.9, 2.8, 0.0);
  const Prism box{center, 3.3, 0.6, vertex_to_graze(whole, center).z - 1e-8 + 0.35, 4, 0.3};
  const TriangleMesh outer = box.mesh(), inner = box.mesh(0.35);
  TrimmedMeshRequest request;
  request.body = &outer;
  request.inner = &inner;
  TriangleMesh one;
  TrimmedMeshStats stats;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = trimmed_lattice_mesh(f, {0.01}, request, &stats);
  }
  EXPECT_GT(stats.moved_clear, 0);
  const TriangleMesh all = trimmed_lattice_mesh(f, {0.01}, request);
  EXPECT_TRUE(one.vertices == all.vertices);
  EXPECT_TRUE(one.triangles == all.triangles);
}

// A mesh stored as text: "vertices triangles", then x y z per vertex (17 digits), then the triangles' indices.
TriangleMesh read_mesh_text(const std::string& name) {
  std::istringstream in(test::file_bytes(std::string(STEADY_TEST_DATA) + "/" + name));
  std::size_t vertices = 0, triangles = 0;
  in >> vertices >> triangles;
  TriangleMesh m;
  m.vertices.resize(vertices);
  m.triangles.resize(triangles);
  for (Vec3& v : m.vertices) in >> v.x >> v.y >> v.z;
  for (Triangle& t : m.triangles) in >> t[0] >> t[1] >> t[2];
  EXPECT_TRUE(in) << name;
  return m;
}

// The main job's part (its lattice, 3,792 beams, in its cylinder with a 1.2 mm skin), its body and inner offset
// tessellated by FreeCAD as the workbench's STL export does (tests/kernel/data/README.md). At tolerances 0.005 and
// 0.003 the band's Boolean left vertices within a float or a few of the wall's tessellation (a lattice edge passing
// by a wall vertex, a wall vertex under a lattice triangle), and once rounded to floats the band intersected
// itself: the export failed. The repair collapses those short edges and needles.
TEST(TrimmedMesh, TheMainJobAtFineTolerancesStaysSafeInFloats) {
  const FlatLattice f =
      flatten(lattice_from_json(test::file_bytes(std::string(STEADY_TEST_DATA) + "/main_job_octet.json")));
  for (const char* tolerance : {"0.005", "0.003"}) {
    SCOPED_TRACE(tolerance);
    const TriangleMesh body = read_mesh_text(std::string("main_job_body_mesh_") + tolerance + ".txt"),
                       inner = read_mesh_text(std::string("main_job_inner_mesh_") + tolerance + ".txt");
    TrimmedMeshRequest request;
    request.body = &body;
    request.inner = &inner;
    TrimmedMeshStats stats;
    const double t = std::stod(tolerance);
    const TriangleMesh mesh = trimmed_lattice_mesh(f, {t}, request, &stats);
    EXPECT_GT(stats.float_removed_triangles, 0);
    EXPECT_TRUE(mesh_edge_report(mesh).closed_manifold());
    expect_float_safe(mesh);
    // The exact part's volume (its B-rep, 12,880.969 mm^3) within the chords of the lattice and of the body.
    EXPECT_NEAR(mesh_volume(mesh), 12880.969, t * mesh_area(mesh));
  }
}

TEST(TrimmedMesh, BadBodiesNameTheParameter) {
  const FlatLattice f = flatten(preset_lattice("cubic", {2, 2, 2}, 2.0, 0.3, 0.1));
  TriangleMesh open = prism({2, 2, 0}, 2.0, 0.5, 3.0, 4, 0.0);
  open.triangles.pop_back();
  TriangleMesh inward = prism({2, 2, 0}, 2.0, 0.5, 3.0, 4, 0.0);
  for (Triangle& t : inward.triangles) std::swap(t[1], t[2]);
  for (const TriangleMesh* bad : {&open, &inward}) {
    TrimmedMeshRequest r;
    r.body = bad;
    try {
      trimmed_lattice_mesh(f, {0.01}, r);
      FAIL() << "accepted a bad body";
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("body"), std::string::npos) << e.what();
    }
  }
  EXPECT_THROW(trimmed_lattice_mesh(f, {0.01}, TrimmedMeshRequest{}), InvalidInput);
}

}  // namespace
}  // namespace steady
