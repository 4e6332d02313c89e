// A lattice part's STEP file as OpenCASCADE's writer gives it against the kernel's writer: its size and write time,
// and how long OpenCASCADE's STEP reader (the one FreeCAD and gmsh use) takes to read it back. The kernel's writer
// puts each shell's faces in connected order (each sharing an edge with one before it,
// brep/connected_face_order.hpp; the reader orients every shell by scanning its remaining faces from the first after
// each face it adds: quadratic in the faces unless they come connected) and writes equal geometry once
// (brep/step_shared_geometry.hpp).
//
// Default: issue 14's swirled lattice (bench_brep's part 2 and bench_step_with_skin.py: one node of radius 0.25,
// three beams, U a slight swirl) at 18 x 18 x 12 nodes (10,908 beams) in a cylinder 3 degrees off its beams with a
// 0.4 skin. --long: also the main job (3,792 beams, 1.2 mm skin) and the swirled lattice at 24 x 24 x 16 (26,112
// beams).
// Both files of a case hold the same lattice and skin solids; the baseline is written by OpenCASCADE's STEP
// writer as the shapes are (pcurves on, as the kernel writes them), ours by write_step_assembly. Each is read by
// STEPControl_Reader as FreeCAD's Part.read does (file, then transfer with its shape fixing), in this process;
// medians of 3 reads, alternated. The shapes read from our file are checked (BRepCheck) once, after the timing.
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <IFSelect_ReturnStatus.hxx>
#include <Interface_Static.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <STEPControl_Reader.hxx>
#include <STEPControl_Writer.hxx>
#include <TopoDS_Compound.hxx>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include <unistd.h>

#include "bench_common.hpp"
#include "brep/step_shared_geometry.hpp"
#include "sample_lattices.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/brep/trim.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "test_support.hpp"

using namespace steady;

namespace {

// What FreeCAD's Part.read does with a STEP file: OpenCASCADE's reader, every root transferred into one shape.
TopoDS_Shape read_as_freecad_does(const std::string& path) {
  STEPControl_Reader reader;
  if (reader.ReadFile(path.c_str()) != IFSelect_RetDone || reader.TransferRoots() == 0)
    throw std::runtime_error("cannot read " + path);
  return reader.OneShape();
}

// The shapes as built, in one file by OpenCASCADE's own writer (no reordering).
void write_as_built(const std::string& path, const TopoDS_Shape& lattice, const TopoDS_Shape& skin) {
  TopoDS_Compound both;
  const BRep_Builder b;
  b.MakeCompound(both);
  b.Add(both, lattice);
  b.Add(both, skin);
  STEPControl_Writer writer;
  Interface_Static::SetIVal("write.surfacecurve.mode", 1);
  if (writer.Transfer(both, STEPControl_AsIs) != IFSelect_RetDone || writer.Write(path.c_str()) != IFSelect_RetDone)
    throw std::runtime_error("cannot write " + path);
}

void measure(const std::string& what, const FlatLattice& lattice, const TopoDS_Shape& body, double skin) {
  TrimOptions options;
  options.skin = skin;
  options.unite_skin = false;
  TrimResult trimmed;
  const double trim_seconds = bench::seconds_of([&] { trimmed = trim_lattice(lattice, body, options); });
  const std::string dir = std::filesystem::temp_directory_path().string() + "/steady_bench_step_read_" +
                          std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  const std::string built = dir + "/as_built.step", ours = dir + "/ours.step";
  const double write_built =
      bench::seconds_of([&] { write_as_built(built, trimmed.lattice, trimmed.skin); });
  const double write_ours = bench::seconds_of(
      [&] { write_step_assembly(ours, {{"Lattice", trimmed.lattice}, {"Skin", trimmed.skin}}); });
  std::vector<double> a, c;
  TopoDS_Shape read_built, read_ours;
  for (int run = 0; run < 3; ++run) {
    a.push_back(bench::seconds_of([&] { read_built = read_as_freecad_does(built); }));
    c.push_back(bench::seconds_of([&] { read_ours = read_as_freecad_does(ours); }));
  }
  const long solids_a = solid_count(read_built), solids_c = solid_count(read_ours);
  const long lattice_faces = face_count(trimmed.lattice), faces = lattice_faces + face_count(trimmed.skin);
  const bool valid = BRepCheck_Analyzer(read_ours).IsValid();
  std::sort(a.begin(), a.end());
  std::sort(c.begin(), c.end());
  // The sharing pass alone, on OpenCASCADE's file (ours runs it on its XCAF writer's file, with names and colours).
  const std::string built_text = test::file_bytes(built);
  const double share_seconds = bench::seconds_of([&] { (void)share_equal_geometry(built_text); });
  const double beams = static_cast<double>(lattice.beams.size());
  const double size_built = static_cast<double>(std::filesystem::file_size(built));
  const double size_ours = static_cast<double>(std::filesystem::file_size(ours));
  std::printf("%s: %zu beams, %ld faces (lattice %ld), trimmed in %.1f s\n", what.c_str(), lattice.beams.size(), faces,
              lattice_faces, trim_seconds);
  std::printf("  file: OpenCASCADE's writer %.1f MB (%.1f KB per beam) in %.1f s, ours %.1f MB (%.1f KB per beam) in "
              "%.1f s: %.2fx smaller (the sharing pass alone %.2f s)\n",
              size_built / 1e6, size_built / 1e3 / beams, write_built, size_ours / 1e6, size_ours / 1e3 / beams,
              write_ours, size_built / size_ours, share_seconds);
  std::printf("  read back (median of 3): OpenCASCADE's file %.1f s, ours %.1f s: %.2fx faster; "
              "solids %ld / %ld, our file's shape %s\n",
              a[1], c[1], a[1] / c[1], solids_a, solids_c, valid ? "valid" : "INVALID");
  std::filesystem::remove_all(dir);
}

// The swirled lattice of bench_brep's part 2 and its cylinder (radius half the smaller width, 0.9 of the height,
// axis 3 degrees off W).
void measure_swirled(Counts c) {
  const FlatLattice f = flatten(test::swirled_scale_lattice(c));
  Vec3 lo(1e300), hi(-1e300);
  for (const Ball& b : f.balls) {
    lo = glm::min(lo, b.center);
    hi = glm::max(hi, b.center);
  }
  const Vec3 mid = 0.5 * (lo + hi);
  const double radius = 0.5 * std::min(hi.x - lo.x, hi.y - lo.y), height = 0.9 * (hi.z - lo.z), tilt = 0.05;
  const TopoDS_Shape body =
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(mid.x, mid.y, mid.z - height / 2), gp_Dir(tilt, 0.6 * tilt, 1)), radius,
                               height)
          .Shape();
  measure("swirled lattice " + std::to_string(c.u) + " x " + std::to_string(c.v) + " x " + std::to_string(c.w), f,
          body, 0.4);
}

}  // namespace

int main(int argc, char** argv) {
  measure_swirled(Counts{18, 18, 12});
  if (!bench::long_run(argc, argv)) return 0;
  const std::string data = STEADY_TEST_DATA;
  const Lattice lattice = lattice_from_json(test::file_bytes(data + "/main_job_octet.json"));
  const TopoDS_Shape cylinder = brep_from_text(test::file_bytes(data + "/main_job_cylinder.brep"), "body");
  measure("main job", flatten(lattice), cylinder, 1.2);
  measure_swirled(Counts{24, 24, 16});
  return 0;
}
