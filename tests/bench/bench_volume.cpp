// Volumes of lattice parts: the kernel's boundary_volume (each face by Green's theorem on its (u, v) domain, faces
// in parallel) against OpenCASCADE's adaptive rule (BRepGProp::VolumeProperties, epsilon 1e-9, what shape_volume
// used before): wall time (medians of 3, alternated) and the two values.
//
// Default: the cubic lattice with a bend and the BCC lattice with a screw of tests/kernel/data (each lattice part
// and skin apart, and united, in the tilted cylinder of the Python tests with a 0.3 skin) and the main job's
// lattice clipped by a box around its middle. --long: the main
// job's part (3,792 beams, 1.2 mm skin, one solid).
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <GProp_GProps.hxx>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_common.hpp"
#include "steady/brep/boundary_volume.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/trim.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "test_support.hpp"

namespace {

using namespace steady;

double adaptive_volume(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props, 1e-9, Standard_True);
  return props.Mass();
}

void compare(const char* name, const TopoDS_Shape& shape) {
  double ours = 0.0, theirs = 0.0;
  std::vector<double> t_ours, t_theirs;
  for (int r = 0; r < 3; ++r) {
    t_ours.push_back(bench::seconds_of([&] { ours = boundary_volume(shape); }));
    t_theirs.push_back(bench::seconds_of([&] { theirs = adaptive_volume(shape); }));
  }
  std::sort(t_ours.begin(), t_ours.end());
  std::sort(t_theirs.begin(), t_theirs.end());
  std::printf("%-40s faces %6lld  boundary_volume %.9f in %6.3f s  adaptive %.9f in %6.3f s  ratio %.2fx  "
              "relative difference %.1e\n",
              name, static_cast<long long>(face_count(shape)), ours, t_ours[1], theirs, t_theirs[1],
              t_theirs[1] / t_ours[1], theirs / ours - 1.0);
}

// A skinned assembly's lattice part and the united part compared, and how the lattice and skin parts add up to
// the united part by each integration.
void compare_assembly(const std::string& name, const FlatLattice& lattice, const TopoDS_Shape& body, double skin) {
  TrimOptions apart;
  apart.skin = skin;
  apart.unite_skin = false;
  const TrimResult parts = trim_lattice(lattice, body, apart);
  TrimOptions united = apart;
  united.unite_skin = true;
  const TopoDS_Shape whole = trim_lattice(lattice, body, united).part;
  compare((name + ": lattice part").c_str(), parts.lattice);
  compare((name + ": united").c_str(), whole);
  std::printf("  lattice + skin - united: boundary_volume %.1e, adaptive %.1e (relative)\n",
              (boundary_volume(parts.lattice) + boundary_volume(parts.skin)) / boundary_volume(whole) - 1.0,
              (adaptive_volume(parts.lattice) + adaptive_volume(parts.skin)) / adaptive_volume(whole) - 1.0);
}

}  // namespace

int main(int argc, char** argv) {
  const std::string data = STEADY_TEST_DATA;
  const TopoDS_Shape cylinder =
      brep_from_text(test::file_bytes(data + "/../../python/data/cylinder.brep"), "body");
  auto lattice = [&](const char* file) { return flatten(lattice_from_json(test::file_bytes(data + "/" + file))); };
  compare_assembly("cubic with a bend", lattice("cubic_bend_skinned_straddle.json"), cylinder, 0.3);
  // BCC with a screw: the case where the adaptive rule made the parts seem not to add up (7.9e-6).
  compare_assembly("BCC with a screw", lattice("bcc_screw_skinned.json"), cylinder, 0.3);

  const FlatLattice main_job = lattice("main_job_octet.json");
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(gp_Pnt(9.5, 9.5, 5.5), gp_Pnt(30.5, 30.5, 22.5)).Shape();
  compare("main job clipped by a box", trim_lattice(main_job, box, {}).part);
  if (bench::long_run(argc, argv)) {
    TrimOptions skin;
    skin.skin = 1.2;
    const TopoDS_Shape body = brep_from_text(test::file_bytes(data + "/main_job_cylinder.brep"), "body");
    compare("main job (1.2 mm skin, one solid)", trim_lattice(main_job, body, skin).part);
  }
  return 0;
}
