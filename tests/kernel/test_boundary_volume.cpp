// boundary_volume (each face's share by Green's theorem on its (u, v) domain) against closed forms, and against
// OpenCASCADE's adaptive rule where that one is right.
#include <gtest/gtest.h>

#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <GProp_GProps.hxx>
#include <TopoDS_Shape.hxx>

#include <cmath>

#include "steady/brep/boundary_volume.hpp"
#include "steady/core/errors.hpp"

namespace steady {
namespace {

double occ_adaptive(const TopoDS_Shape& shape) {
  GProp_GProps props;
  BRepGProp::VolumeProperties(shape, props, 1e-10, Standard_True);
  return props.Mass();
}

TEST(BoundaryVolume, PrimitivesHaveTheirClosedFormVolumes) {
  const gp_Ax2 tilted(gp_Pnt(1, -2, 3), gp_Dir(0.3, -0.2, 1.0));
  const double pi = M_PI;
  EXPECT_NEAR(boundary_volume(BRepPrimAPI_MakeSphere(tilted, 1.5).Shape()), 4.0 / 3.0 * pi * 1.5 * 1.5 * 1.5, 1e-12);
  EXPECT_NEAR(boundary_volume(BRepPrimAPI_MakeBox(tilted, 1.0, 2.0, 3.0).Shape()), 6.0, 1e-12);
  EXPECT_NEAR(boundary_volume(BRepPrimAPI_MakeCylinder(tilted, 0.7, 2.0).Shape()), pi * 0.49 * 2.0, 1e-12);
  EXPECT_NEAR(boundary_volume(BRepPrimAPI_MakeCone(tilted, 1.0, 0.4, 2.0).Shape()),
              pi * 2.0 / 3.0 * (1.0 + 0.4 + 0.16), 1e-12);
  EXPECT_NEAR(boundary_volume(BRepPrimAPI_MakeTorus(tilted, 2.0, 0.5).Shape()), 2.0 * pi * pi * 2.0 * 0.25, 1e-11);
  // A ball with a cap cut off at height h above its centre: 4/3 pi r^3 - pi (r - h)^2 (2 r + h) / 3.
  const double r = 1.0, h = 0.35;
  const TopoDS_Shape capped = BRepAlgoAPI_Cut(BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), r).Shape(),
                                              BRepPrimAPI_MakeBox(gp_Pnt(-2, -2, h), 4, 4, 4).Shape()).Shape();
  EXPECT_NEAR(boundary_volume(capped), 4.0 / 3.0 * pi - pi * (r - h) * (r - h) * (2 * r + h) / 3.0, 1e-12);
}

// Faces bounded by intersection curves (B-splines, approximated by OpenCASCADE to about 1e-7): the Steinmetz
// solids, 16/3 r^3 for two cylinders and 8 (2 - sqrt 2) r^3 for three.
TEST(BoundaryVolume, SteinmetzSolidsAgreeWithTheClosedFormToTheirCurvesAccuracy) {
  const TopoDS_Shape x = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(-3, 0, 0), gp::DX()), 1.0, 6.0).Shape();
  const TopoDS_Shape y = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, -3, 0), gp::DY()), 1.0, 6.0).Shape();
  const TopoDS_Shape z = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, -3), gp::DZ()), 1.0, 6.0).Shape();
  const TopoDS_Shape two = BRepAlgoAPI_Common(x, y).Shape(), three = BRepAlgoAPI_Common(two, z).Shape();
  EXPECT_NEAR(boundary_volume(two), 16.0 / 3.0, 1e-8);
  EXPECT_NEAR(boundary_volume(three), 8.0 * (2.0 - std::sqrt(2.0)), 1e-8);
  // On these faces OpenCASCADE's adaptive rule is right too: both integrate the same curves.
  EXPECT_NEAR(boundary_volume(two), occ_adaptive(two), 1e-11);
  EXPECT_NEAR(boundary_volume(three), occ_adaptive(three), 1e-11);
}

TEST(BoundaryVolume, AReversedSolidHasTheOppositeVolumeAndAnEmptyShapeNone) {
  const TopoDS_Shape ball = BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), 2.0).Shape();
  EXPECT_NEAR(boundary_volume(ball.Reversed()), -boundary_volume(ball), 1e-12);
  EXPECT_EQ(boundary_volume(TopoDS_Shape()), 0.0);
}

}  // namespace
}  // namespace steady
