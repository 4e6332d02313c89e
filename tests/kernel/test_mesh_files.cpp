// Mesh files read back by readers we did not write: CGAL's STL and OBJ readers, lib3mf for 3MF, xmllint against
// the 3MF Beam Lattice specification's schemas; and by our own STL reader, which must agree.
#include <gtest/gtest.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/STL.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/repair_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Surface_mesh.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <tbb/global_control.h>

#include "steady/core/errors.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/presets.hpp"
#include "steady/mesh/lattice_mesh.hpp"
#include "steady/mesh/mesh_files.hpp"
#include "steady/mesh/threemf_reader.hpp"

namespace steady {
namespace {

using K = CGAL::Exact_predicates_inexact_constructions_kernel;
using SurfaceMesh = CGAL::Surface_mesh<K::Point_3>;
namespace PMP = CGAL::Polygon_mesh_processing;
namespace fs = std::filesystem;

std::string temp_path(const std::string& name) { return (fs::temp_directory_path() / ("steady_mesh_" + name)).string(); }

// A polygon soup as CGAL reads it, merged where points coincide, as a closed surface: its volume, or NaN.
double cgal_closed_volume(std::vector<K::Point_3> points, std::vector<std::vector<std::size_t>> polygons) {
  PMP::merge_duplicate_points_in_polygon_soup(points, polygons);
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) return NAN;
  SurfaceMesh sm;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, sm);
  if (!CGAL::is_closed(sm) || !PMP::is_outward_oriented(sm)) return NAN;
  return PMP::volume(sm);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

FlatLattice octet() { return flatten(preset_lattice("octet", {2, 2, 2}, 2.0, 0.3, 0.15)); }

TEST(MeshFiles, BinaryStlReadByCgalIsClosedWithTheMeshVolume) {
  const TriangleMesh mesh = lattice_mesh(octet(), {0.01});
  const std::string path = temp_path("octet.stl");
  write_stl(mesh, path, "octet");
  std::vector<K::Point_3> points;
  std::vector<std::array<std::size_t, 3>> triangles;
  ASSERT_TRUE(CGAL::IO::read_STL(path, points, triangles));
  EXPECT_EQ(triangles.size(), mesh.triangles.size());
  std::vector<std::vector<std::size_t>> polygons;
  for (const auto& t : triangles) polygons.push_back({t[0], t[1], t[2]});
  const double volume = mesh_volume(mesh);
  EXPECT_NEAR(cgal_closed_volume(points, polygons), volume, 1e-5 * volume);
  // Our reader agrees: welded by exact float coordinates, the same closed 2-manifold.
  const TriangleMesh back = read_stl(path);
  EXPECT_EQ(back.vertices.size(), mesh.vertices.size());
  EXPECT_TRUE(mesh_edge_report(back).closed_manifold());
  EXPECT_NEAR(mesh_volume(back), volume, 1e-5 * volume);
  std::remove(path.c_str());
}

TEST(MeshFiles, StreamedStlIsTheSameFileAsTheWholeMesh) {
  const FlatLattice f = octet();
  const std::string whole = temp_path("whole.stl"), streamed = temp_path("streamed.stl");
  write_stl(lattice_mesh(f, {0.01}), whole, "octet");
  const LatticeMeshStats stats = write_lattice_stl(f, {0.01}, streamed, "octet");
  EXPECT_EQ(slurp(whole), slurp(streamed));
  EXPECT_EQ(fs::file_size(streamed), 84 + 50 * static_cast<std::uint64_t>(stats.triangles));
  std::remove(whole.c_str());
  std::remove(streamed.c_str());
}

TEST(MeshFiles, FilesAreTheSameWhateverTheNumberOfThreads) {
  // Templates, placements and files do not depend on how the work was split: one thread or all of them write the
  // same bytes (STL streamed, beam lattice, a slice).
  const FlatLattice f = flatten(preset_lattice("octet", {2, 2, 2}, 2.0, 0.3, 0.24));  // crowded hubs too
  auto files = [&](const std::string& tag) {
    const std::string stl = temp_path("threads_" + tag + ".stl"), beams = temp_path("threads_" + tag + ".3mf");
    write_lattice_stl(f, {0.01}, stl);
    write_3mf_beam_lattice(f, beams);
    std::string out = slurp(stl) + slurp(beams);
    std::remove(stl.c_str());
    std::remove(beams.c_str());
    return out;
  };
  std::string one;
  {
    tbb::global_control single(tbb::global_control::max_allowed_parallelism, 1);
    one = files("one");
  }
  EXPECT_EQ(one, files("all"));
}

TEST(MeshFiles, ObjReadByCgal) {
  const TriangleMesh mesh = lattice_mesh(octet(), {0.01});
  const std::string path = temp_path("octet.obj");
  write_obj(mesh, path);
  std::vector<K::Point_3> points;
  std::vector<std::vector<std::size_t>> polygons;
  ASSERT_TRUE(CGAL::IO::read_OBJ(path, points, polygons));
  EXPECT_EQ(points.size(), mesh.vertices.size());
  EXPECT_EQ(polygons.size(), mesh.triangles.size());
  EXPECT_NEAR(cgal_closed_volume(points, polygons), mesh_volume(mesh), 1e-9 * mesh_volume(mesh));
  std::remove(path.c_str());
}

TEST(MeshFiles, Core3mfReadByLib3mf) {
  const TriangleMesh mesh = lattice_mesh(octet(), {0.01});
  const std::string path = temp_path("octet.3mf");
  ThreeMfOptions options;
  options.name = "octet part";
  options.unit = "micron";
  write_3mf(mesh, path, options);
  const ThreeMfContents back = read_3mf(path);
  EXPECT_TRUE(back.warnings.empty());
  EXPECT_EQ(back.unit, "micron");
  ASSERT_EQ(back.objects.size(), 1u);
  EXPECT_EQ(back.objects[0].name, "octet part");
  EXPECT_EQ(back.objects[0].mesh.triangles.size(), mesh.triangles.size());
  EXPECT_TRUE(mesh_edge_report(back.objects[0].mesh).closed_manifold());
  EXPECT_NEAR(mesh_volume(back.objects[0].mesh), mesh_volume(mesh), 1e-5 * mesh_volume(mesh));
  std::remove(path.c_str());
}

// The same mesh gives the same bytes whenever it is written: lib3mf drew the production UUIDs at random.
TEST(MeshFiles, Core3mfOfOneMeshIsTheSameFileEachTime) {
  const TriangleMesh mesh = lattice_mesh(octet(), {0.02});
  const std::string a = temp_path("first.3mf"), b = temp_path("second.3mf");
  write_3mf(mesh, a);
  write_3mf(mesh, b);
  EXPECT_FALSE(slurp(a).empty());
  EXPECT_EQ(slurp(a), slurp(b));
  EXPECT_TRUE(read_3mf(b).warnings.empty());
  std::remove(a.c_str());
  std::remove(b.c_str());
}

TEST(MeshFiles, BeamLattice3mfReadByLib3mfWithEveryBeamAndRadius) {
  const FlatLattice f = octet();
  const TriangleMesh representation = lattice_mesh(f, {0.02});
  const std::string path = temp_path("octet_beams.3mf");
  BeamLatticeOptions options;
  options.representation = &representation;
  const BeamLatticeStats stats = write_3mf_beam_lattice(f, path, options);
  EXPECT_EQ(stats.beams, f.beam_count());
  const ThreeMfContents back = read_3mf(path);
  // lib3mf 1.8.1 predates the balls namespace of v1.2 (2020): it says so, and reads the rest.
  ASSERT_EQ(back.warnings.size(), 1u);
  EXPECT_NE(back.warnings[0].find("required extension"), std::string::npos) << back.warnings[0];
  ASSERT_EQ(back.objects.size(), 2u);
  EXPECT_EQ(back.objects[0].mesh.triangles.size(), representation.triangles.size());
  const ThreeMfObject& lattice = back.objects[1];
  ASSERT_EQ(static_cast<std::int64_t>(lattice.beams.size()), f.beam_count());
  ASSERT_EQ(static_cast<std::int64_t>(lattice.mesh.vertices.size()), f.ball_count());
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    const ThreeMfBeam& b = lattice.beams[e];
    EXPECT_EQ(b.v1, f.beams[e].a);
    EXPECT_EQ(b.v2, f.beams[e].b);
    // Written as the shortest decimal that reads back to the same double; lib3mf 1.8.1 keeps radii as floats.
    EXPECT_NEAR(b.r1, f.beams[e].ra, 1e-7 * f.beams[e].ra);
    EXPECT_NEAR(b.r2, f.beams[e].rb, 1e-7 * f.beams[e].rb);
  }
  for (std::int64_t i = 0; i < f.ball_count(); ++i)
    EXPECT_LT(glm::length(lattice.mesh.vertices[i] - f.balls[i].center), 1e-6 * (1.0 + glm::length(f.balls[i].center)));
  std::remove(path.c_str());
}

TEST(MeshFiles, BeamLatticeValidatesAgainstTheSpecificationSchemas) {
  // xmllint (libxml2) checks the <b:beamlattice> element, with its balls, against the schemas of the v1.2
  // specification (tests/kernel/data/3mf); a broken copy must fail, so the check can fail.
  const FlatLattice f = octet();
  const std::string path = temp_path("schema.3mf"), dir = temp_path("schema_dir");
  write_3mf_beam_lattice(f, path);
  fs::remove_all(dir);
  fs::create_directories(dir);
  ASSERT_EQ(std::system(("cd " + dir + " && unzip -q " + path).c_str()), 0);
  const std::string model = slurp(dir + "/3D/3dmodel.model");
  const std::size_t begin = model.find("<b:beamlattice"), end = model.find("</b:beamlattice>");
  ASSERT_NE(begin, std::string::npos);
  const std::string ns =
      " xmlns:b=\"http://schemas.microsoft.com/3dmanufacturing/beamlattice/2017/02\""
      " xmlns:b2=\"http://schemas.microsoft.com/3dmanufacturing/beamlattice/balls/2020/07\"";
  std::string fragment = model.substr(begin, end + 16 - begin);
  fragment.insert(14, ns);
  auto validates = [&](const std::string& xml) {
    std::ofstream(dir + "/fragment.xml") << "<?xml version=\"1.0\"?>\n" << xml;
    return std::system(("xmllint --noout --schema " STEADY_TEST_DATA "/3mf/wrapper.xsd " + dir +
                        "/fragment.xml 2>/dev/null").c_str()) == 0;
  };
  EXPECT_TRUE(validates(fragment));
  std::string broken = fragment;
  broken.replace(broken.find(" r=\"") + 4, 0, "-");  // a negative ball radius
  EXPECT_FALSE(validates(broken));
  fs::remove_all(dir);
  std::remove(path.c_str());
}

TEST(MeshFiles, BadPathsLeaveNoFileBehind) {
  const TriangleMesh mesh = lattice_mesh(octet(), {0.02});
  const std::string missing_dir = temp_path("no/such/dir/part.stl");
  EXPECT_THROW(write_stl(mesh, missing_dir), InvalidInput);
  EXPECT_THROW(write_stl(mesh, ""), InvalidInput);
  EXPECT_THROW(write_obj(mesh, missing_dir), InvalidInput);
  EXPECT_THROW(write_3mf(mesh, temp_path("no/such/dir/part.3mf")), std::exception);
  EXPECT_THROW(write_3mf_beam_lattice(octet(), temp_path("no/such/dir/part.3mf")), std::exception);
  ThreeMfOptions bad_unit;
  bad_unit.unit = "furlong";
  EXPECT_THROW(write_3mf(mesh, temp_path("unit.3mf"), bad_unit), InvalidInput);
  EXPECT_FALSE(fs::exists(temp_path("unit.3mf")));
  // A failed streamed write (bad tolerance) leaves neither the file nor its temporary.
  const std::string path = temp_path("bad_tolerance.stl");
  EXPECT_THROW(write_lattice_stl(octet(), {-1.0}, path), InvalidInput);
  EXPECT_FALSE(fs::exists(path));
  EXPECT_FALSE(fs::exists(path + ".partial"));
}

}  // namespace
}  // namespace steady
