// Cuts placed again beyond a collar a build found (brep_pieces.hpp, CollarPastCut). The crowded sweep's FCC at
// beam/node 0.5 with a taper (3 x 3 x 3 cells, nodes 0.35 of the neighbour distance) trimmed into a cylinder
// through its middle was refused: "hub: ball 28: beam 7 is too short for the collar its crowded hub needs (collar
// at 0.265059, cut at 0.258961)". Its tangent exit caps send the cores to OpenCASCADE's Fuse, which needed collars
// 1.12 times as far out as the ones the cut was placed for. The trim now places the cuts again knowing that
// collar (crowded_sweep.py --trim-cylinder: one valid part of 7 solids, 4.31715 against 4.3172 +- 0.0045 by
// sampling, 60 s).
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "brep/brep_pieces.hpp"
#include "lattice_membership.hpp"
#include "lattice_test_shapes.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/trim.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {
namespace {

test::BrickDefinition tapered_fcc() {
  test::BrickDefinition d = test::preset_brick("FCC", 0.35, 0.5, {3, 3, 3});
  d.u = {Similarity::dilation(1.05, {-20, 0.5, 0.5})};
  return d;
}

TEST(CollarPastCut, CutsArePlacedBeyondACollarTheBuildFound) {
  const FlatLattice f = flatten(Lattice(tapered_fcc()));
  const std::vector<BeamFrustum> planned = [&] {
    std::vector<BeamFrustum> p = beam_frustums(f);
    place_cuts_between_collars(f, p);
    return p;
  }();
  // A collar found 1 % beyond a beam's planned cut, at either end: the cut moves beyond it, still on the beam.
  int checked = 0;
  for (std::int64_t e = 0; e < f.beam_count(); e += 7) {
    if (!planned[e].exists) continue;
    for (int end = 0; end < 2; ++end) {
      const double length = planned[e].cone.length;
      const double cut_from_end = end == 0 ? planned[e].cut_position() : length - planned[e].cut_position();
      const double collar = 1.01 * cut_from_end;
      std::vector<BeamFrustum> again = beam_frustums(f);
      const std::vector<char> no_room = place_cuts_between_collars(f, again, {{2 * e + end, collar}});
      ASSERT_FALSE(no_room[e]) << "beam " << e << ": a collar 1 % farther out leaves no room";
      const double now = end == 0 ? again[e].cut_position() : length - again[e].cut_position();
      EXPECT_GT(now, collar) << "beam " << e << ", end " << end;
      EXPECT_LT(now, length) << "beam " << e << ", end " << end;
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

TEST(CollarPastCut, TheTaperedFccWithTangentCapsTrimsIntoACylinder) {
  const FlatLattice f = flatten(Lattice(tapered_fcc()));
  const double radius = 1.05, height = 4.5;
  const Vec3 base(1.25, 1.25, -1.0);
  const TopoDS_Shape body =
      BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(base.x, base.y, base.z), gp_Dir(0, 0, 1)), radius, height).Shape();
  std::vector<std::string> log;
  TrimOptions options;
  options.report = [&](const std::string& m) { log.push_back(m); };
  const TrimResult r = trim_lattice(f, body, options);
  EXPECT_TRUE(is_valid(r.part));
  bool placed_again = false;
  for (const std::string& m : log) placed_again = placed_again || m.find("cuts placed again") != std::string::npos;
  EXPECT_TRUE(placed_again) << "the first build's collars fit: the case no longer shows the Fuse's farther collars";
  // The lattice lies within heights -0.5 and 3.5.
  const test::SampledVolume sampled =
      test::volume_in_upright_cylinder(f, base.x, base.y, radius, -0.5, 3.5, 200000, 3);
  EXPECT_NEAR(shape_volume(r.part), sampled.volume, 4 * sampled.sigma);
  std::printf("[ report ] tapered FCC at beam/node 0.5 in the cylinder: volume %.5f, Monte Carlo %.5f +- %.5f\n",
              shape_volume(r.part), sampled.volume, sampled.sigma);
}

}  // namespace
}  // namespace steady
