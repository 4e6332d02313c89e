// The caps of a node ball beyond its hub's cut disks (properties/caps_past_cuts.hpp): their moments against
// OpenCASCADE's of the same cap cut from a ball by a box; the hub fused whole against hub_properties plus the caps,
// also where another stump leaves the ball through a cap's directions; the refusal where two caps meet.
#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Common.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "occ_reference.hpp"
#include "properties/caps_past_cuts.hpp"
#include "properties/hub_solid.hpp"
#include "steady/properties/hub_properties.hpp"
#include "steady/lattice/hub.hpp"

namespace steady {
namespace {

// A stump of a beam from the ball at `center` (end radius r) along unit `axis`, `length` long, cut at `cut`.
Stump stump(const Vec3& center, const Vec3& axis, double r, double length, double cut) {
  Stump s;
  s.cone = beam_cone(Ball{center, r}, Ball{center + length * axis, r});
  move_cut(s, cut);
  return s;
}

TEST(CapsPastCuts, ItsMomentsMatchTheCapOpenCascadeCutsFromTheBall) {
  // A ball of radius 0.3 at (0.1, -0.2, 0.3) whose beam along a tilted axis is cut at 0.22, inside the ball: the cap
  // beyond, in closed form, against the ball's Common with a box beyond the cut plane (turned to the axis).
  const Vec3 c(0.1, -0.2, 0.3), axis = glm::normalize(Vec3(0.3, 0.5, 0.8));
  const double R = 0.3, cut = 0.22;
  Hub h;
  h.ball = Ball{c, R};
  h.stumps.push_back(stump(c, axis, 0.25, 0.44, cut));
  std::string refusal;
  const MassMoments m = caps_past_cuts(h, refusal);
  EXPECT_EQ(refusal, "");
  gp_Ax2 frame(test::occ_point(c + cut * axis), gp_Dir(axis.x, axis.y, axis.z));
  frame.Translate(gp_Vec(frame.XDirection()) * -1.0 + gp_Vec(frame.YDirection()) * -1.0);
  const TopoDS_Shape box = BRepPrimAPI_MakeBox(frame, 2.0, 2.0, 1.0).Shape();
  const TopoDS_Shape cap = BRepAlgoAPI_Common(BRepPrimAPI_MakeSphere(test::occ_point(c), R).Shape(), box).Shape();
  const test::OccProperties occ = test::occ_properties(cap);
  const double base_area = M_PI * (R * R - cut * cut);  // the cap's flat face, on the cut plane: not its surface
  std::printf("[ report ] cap volume %.12f (OpenCASCADE %.12f), area %.12f (%.12f)\n", m.volume, occ.volume, m.area,
              occ.area - base_area);
  EXPECT_NEAR(m.volume, occ.volume, 1e-9 * occ.volume);
  EXPECT_NEAR(m.area, occ.area - base_area, 1e-9 * occ.area);
  const Vec3 centroid = c + m.first / m.volume;  // caps_past_cuts gives moments about the ball's center
  EXPECT_LT(glm::length(centroid - occ.centroid), 1e-9 * R);
  const Vec3 g = m.first / m.volume;
  const Mat3 central = m.second - m.volume * glm::outerProduct(g, g);
  const double trace = central[0][0] + central[1][1] + central[2][2];
  const Mat3 inertia = trace * Mat3(1.0) - central;
  EXPECT_LT(test::max_abs(inertia - occ.inertia), 1e-8 * test::max_abs(occ.inertia));
}

TEST(CapsPastCuts, ACutOutsideTheBallHasNoCap) {
  Hub h;
  h.ball = Ball{Vec3(0.0), 0.3};
  h.stumps.push_back(stump(Vec3(0.0), Vec3(1, 0, 0), 0.2, 1.0, 0.5));
  std::string refusal;
  const MassMoments m = caps_past_cuts(h, refusal);
  EXPECT_EQ(m.volume, 0.0);
  EXPECT_EQ(m.area, 0.0);
  EXPECT_EQ(refusal, "");
}

TEST(CapsPastCuts, WhereAnotherStumpLeavesTheBallThroughACapItsPartThereIsTheHubsAlready) {
  // The short beam along x is cut at 0.25 of the ball of radius 0.3 (a cap 0.05 high, 33.6 degrees wide seen from the
  // center). A second beam of radius 0.1 leaves the ball over 19.5 degrees around its axis: at 60 degrees from x
  // apart from the cap, at 25 degrees through part of its directions, where hub_properties keeps the cap (the second
  // stump holds it: its cut disk is hidden there). Either way the hub as fused whole (ball and frustums, OpenCASCADE)
  // is hub_properties plus what caps_past_cuts gives: volume, centroid, inertia and area (leaving out the planar
  // faces, on the cut planes).
  for (double degrees : {60.0, 25.0}) {
    Hub h;
    h.ball = Ball{Vec3(0.0), 0.3};
    h.stumps.push_back(stump(Vec3(0.0), Vec3(1, 0, 0), 0.2, 0.5, 0.25));
    const double a = degrees * M_PI / 180.0;
    h.stumps.push_back(stump(Vec3(0.0), Vec3(std::cos(a), std::sin(a), 0.0), 0.1, 2.0, 1.0));
    std::string refusal;
    const MassMoments caps = caps_past_cuts(h, refusal);
    EXPECT_EQ(refusal, "") << degrees;
    const MassMoments m = hub_properties(hub_shape(h)).moments + caps;
    const TopoDS_Shape solid = hub_solid(h, Vec3(0.0));
    const test::OccProperties occ = test::occ_properties(solid);
    double curved_area = 0.0;
    for (TopExp_Explorer x(solid, TopAbs_FACE); x.More(); x.Next()) {
      const TopoDS_Face face = TopoDS::Face(x.Current());
      if (BRepAdaptor_Surface(face).GetType() == GeomAbs_Plane) continue;
      GProp_GProps g;
      BRepGProp::SurfaceProperties(face, g, 1e-10);
      curved_area += g.Mass();
    }
    const Vec3 g = m.first / m.volume;
    const Mat3 central = m.second - m.volume * glm::outerProduct(g, g);
    const Mat3 inertia = (central[0][0] + central[1][1] + central[2][2]) * Mat3(1.0) - central;
    std::printf("[ report ] %.0f degrees: caps %.9f, hub %.9f (OpenCASCADE %.9f), area %.9f (%.9f)\n", degrees,
                caps.volume, m.volume, occ.volume, m.area, curved_area);
    EXPECT_NEAR(m.volume, occ.volume, 1e-8 * occ.volume) << degrees;
    // The fused faces' areas are OpenCASCADE's to a few 1e-8 (1.4e-8 measured at 25 degrees, 4.6e-9 at 60).
    EXPECT_NEAR(m.area, curved_area, 5e-8 * curved_area) << degrees;
    EXPECT_LT(glm::length(g - occ.centroid), 1e-8 * 0.3) << degrees;
    EXPECT_LT(test::max_abs(inertia - occ.inertia), 1e-8 * test::max_abs(occ.inertia)) << degrees;
  }
}

TEST(CapsPastCuts, TwoCapsThatMeetAreRefused) {
  // Two short beams, both cut at 0.2 of a ball of radius 0.3. A point of both caps has x.(n1 + n2) >= 0.4, so it
  // lies at least 0.4 / |n1 + n2| from the center: 0.213 with the axes 40 degrees apart (the caps meet), 0.4 with
  // them 120 degrees apart (outside the ball: they do not), though the caps' base disks (radius 0.224, 0.346 apart)
  // come as close as in the first case.
  for (const auto& [degrees, meets] : {std::pair<double, bool>{120.0, false}, {40.0, true}}) {
    Hub h;
    h.ball = Ball{Vec3(0.0), 0.3};
    const double a = degrees * M_PI / 180.0;
    h.stumps.push_back(stump(Vec3(0.0), Vec3(1, 0, 0), 0.05, 0.4, 0.2));
    h.stumps.push_back(stump(Vec3(0.0), Vec3(std::cos(a), std::sin(a), 0.0), 0.05, 0.4, 0.2));
    std::string refusal;
    caps_past_cuts(h, refusal);
    EXPECT_EQ(!refusal.empty(), meets) << degrees << " degrees: " << refusal;
  }
}

}  // namespace
}  // namespace steady
