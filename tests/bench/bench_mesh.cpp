// Lattice meshes against the baselines a user has today, measured in one run:
//  1. Lattices of 10^4, 10^5 (and with --long 10^6) beams streamed to binary STL: seconds, peak memory (each
//     size in its own process, forked before anything large is held), triangles, file size; and the same
//     lattices as 3MF beam lattices.
//  2. OpenCASCADE's mesher (BRepMesh, what FreeCAD's MeshPart runs) on the exact B-rep of the same lattice, at the
//     same measured deviation from the exact surface; the B-rep's build time is reported apart.
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Poly_Triangulation.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>

#include "bench_common.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/hub.hpp"
#include "steady/lattice/presets.hpp"
#include "steady/mesh/lattice_mesh.hpp"
#include "steady/mesh/mesh_files.hpp"

using namespace steady;

namespace {

// How deep below the exact surface a point of an inscribed mesh lies: the largest depth into any element (near
// the surface, the distance to the union's boundary).
double depth(const FlatLattice& f, const std::vector<BeamCone>& cones, const Vec3& p) {
  double d = -1e300;
  for (const Ball& b : f.balls) d = std::max(d, b.radius - glm::length(p - b.center));
  for (const BeamCone& c : cones) {
    const Vec3 w = p - c.a;
    const double x = glm::dot(w, c.axis);
    if (x < c.ra * c.sin_phi || x > c.length + c.rb * c.sin_phi) continue;
    d = std::max(d, (c.radius_at(x) - glm::length(w - x * c.axis)) * c.cos_phi);
  }
  return d;
}

// The largest deviation over sample points (centroids and edge midpoints) of every `stride`-th triangle.
double deviation(const FlatLattice& f, const std::vector<std::array<Vec3, 3>>& triangles, std::size_t stride) {
  std::vector<BeamCone> cones;
  for (const FlatBeam& b : f.beams) {
    const BeamCone c = beam_cone({f.balls[b.a].center, b.ra}, {f.balls[b.b].center, b.rb});
    if (c.has_lateral_surface()) cones.push_back(c);
  }
  double worst = 0.0;
  for (std::size_t i = 0; i < triangles.size(); i += stride) {
    const auto& t = triangles[i];
    for (const Vec3& p : {(t[0] + t[1] + t[2]) / 3.0, 0.5 * (t[0] + t[1]), 0.5 * (t[1] + t[2]), 0.5 * (t[2] + t[0])})
      worst = std::max(worst, std::abs(depth(f, cones, p)));
  }
  return worst;
}

std::vector<std::array<Vec3, 3>> corners(const TriangleMesh& m) {
  std::vector<std::array<Vec3, 3>> out;
  for (const Triangle& t : m.triangles) out.push_back({m.vertices[t[0]], m.vertices[t[1]], m.vertices[t[2]]});
  return out;
}

std::vector<std::array<Vec3, 3>> occ_triangles(const TopoDS_Shape& shape) {
  std::vector<std::array<Vec3, 3>> out;
  for (TopExp_Explorer x(shape, TopAbs_FACE); x.More(); x.Next()) {
    const TopoDS_Face face = TopoDS::Face(x.Current());
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
    if (tri.IsNull()) continue;
    for (int i = 1; i <= tri->NbTriangles(); ++i) {
      int a, b, c;
      tri->Triangle(i).Get(a, b, c);
      std::array<Vec3, 3> t;
      int k = 0;
      for (int n : {a, b, c}) {
        const gp_Pnt p = tri->Node(n).Transformed(loc.Transformation());
        t[k++] = Vec3(p.X(), p.Y(), p.Z());
      }
      out.push_back(t);
    }
  }
  return out;
}

// Undirected edges used once after welding equal coordinates: 0 for a closed mesh.
std::size_t open_edges(const std::vector<std::array<Vec3, 3>>& triangles) {
  std::map<std::array<double, 3>, std::size_t> id;
  auto index = [&](const Vec3& v) { return id.emplace(std::array<double, 3>{v.x, v.y, v.z}, id.size()).first->second; };
  std::map<std::pair<std::size_t, std::size_t>, int> uses;
  for (const auto& t : triangles)
    for (int k = 0; k < 3; ++k) {
      const std::size_t a = index(t[k]), b = index(t[(k + 1) % 3]);
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  std::size_t open = 0;
  for (const auto& [e, n] : uses) open += n == 1;
  return open;
}

void versus_opencascade() {
  const FlatLattice f = flatten(preset_lattice("BCC", {6, 6, 6}, 2.0, 0.3, 0.15));
  const double tolerance = 0.006;  // 2 % of the node radius, 4 % of the beams'
  std::printf("2. mesh from the lattice vs OpenCASCADE's mesher (BRepMesh, as FreeCAD's MeshPart) on its exact B-rep\n");
  std::printf("   BCC 6x6x6, %lld balls, %lld beams\n", static_cast<long long>(f.ball_count()),
              static_cast<long long>(f.beam_count()));
  TriangleMesh mesh;
  const double ours = bench::median_seconds(3, [&] { mesh = lattice_mesh(f, {tolerance}); });
  const double ours_dev = deviation(f, corners(mesh), 3);
  LatticeBrep brep;
  const double brep_seconds = bench::seconds_of([&] { brep = build_lattice_brep(f); });
  // OpenCASCADE's deflection is not the measured deviation: lower it until its mesh is as close as ours.
  double deflection = tolerance, occ_seconds = 0.0, occ_dev = 0.0;
  std::vector<std::array<Vec3, 3>> occ;
  for (int attempt = 0; attempt < 8; ++attempt, deflection *= 0.7) {
    BRepTools::Clean(brep.shape);
    occ_seconds = bench::seconds_of([&] { BRepMesh_IncrementalMesh(brep.shape, deflection, false, 0.5, true); });
    occ = occ_triangles(brep.shape);
    occ_dev = deviation(f, occ, 3);
    if (occ_dev <= ours_dev) break;
  }
  std::printf("   ours:        %.3f s, %zu triangles, measured deviation %.2e, open edges %zu\n", ours,
              mesh.triangles.size(), ours_dev, open_edges(corners(mesh)));
  std::printf("   OpenCASCADE: %.3f s (deflection %.2e), %zu triangles, measured deviation %.2e, open edges %zu "
              "(faces meshed apart); its B-rep took %.2f s more\n",
              occ_seconds, deflection, occ.size(), occ_dev, open_edges(occ), brep_seconds);
  std::printf("   ratio: %.1fx faster than meshing the B-rep, %.1fx counting the B-rep's build\n", occ_seconds / ours,
              (occ_seconds + brep_seconds) / ours);
}

// One size in a child process, so that its peak memory is its own.
void stl_size(int n, bool with_3mf) {
  std::fflush(stdout);
  const pid_t child = fork();
  if (child == 0) {
    const FlatLattice f = flatten(preset_lattice("BCC", {n, n, n}, 2.0, 0.3, 0.15));
    const std::string path = (std::filesystem::temp_directory_path() / "bench_mesh.stl").string();
    LatticeMeshStats stats;
    const double seconds = bench::seconds_of([&] { stats = write_lattice_stl(f, {0.006}, path); });
    const double mb = std::filesystem::file_size(path) / 1e6;
    std::remove(path.c_str());
    std::printf("   %9lld beams: STL %7.2f s, %10lld triangles, %8.1f MB, %lld templates for %lld hubs",
                static_cast<long long>(f.beam_count()), seconds, static_cast<long long>(stats.triangles), mb,
                static_cast<long long>(stats.templates), static_cast<long long>(stats.hubs));
    if (with_3mf) {
      const std::string p3 = (std::filesystem::temp_directory_path() / "bench_mesh.3mf").string();
      BeamLatticeStats b;
      const double s3 = bench::seconds_of([&] { b = write_3mf_beam_lattice(f, p3); });
      std::remove(p3.c_str());
      std::printf("; 3MF beam lattice %.2f s, %.2f MB", s3, b.bytes / 1e6);
    }
    std::fflush(stdout);
    _exit(0);
  }
  int status = 0;
  rusage usage{};
  wait4(child, &status, 0, &usage);
  std::printf(", peak memory %.0f MiB\n", usage.ru_maxrss / 1024.0);
}

}  // namespace

int main(int argc, char** argv) {
  const bool long_run = bench::long_run(argc, argv);
  std::printf("1. BCC lattices (node 0.3, beams 0.15, cells of 2) to binary STL at tolerance 0.006, streamed\n");
  stl_size(11, true);   // ~10^4 beams
  stl_size(23, true);   // ~10^5 beams
  if (long_run) stl_size(50, true);  // ~10^6 beams
  else std::printf("   (10^6 beams with --long)\n");
  versus_opencascade();
  return 0;
}
