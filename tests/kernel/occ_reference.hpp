#pragma once
// OpenCASCADE references for the property tests: hubs and small lattices built from BRepPrimAPI spheres and
// cones, fused with BRepAlgoAPI_Fuse, checked with BRepCheck_Analyzer, measured with BRepGProp.
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <GProp_GProps.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS_Shape.hxx>
#include <gp_Ax2.hxx>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "steady/lattice/flat_lattice.hpp"
#include "steady/properties/hub_properties.hpp"
#include "test_support.hpp"

namespace steady::test {

inline gp_Pnt occ_point(const Vec3& p) { return gp_Pnt(p.x, p.y, p.z); }


// The stump of a beam from the node at `center` (explicit radii: its start disk lies strictly inside the
// node ball, so the fuse meets only transversal intersections): the frustum from the near tangent circle
// to the cut disk.
inline TopoDS_Shape occ_stump(const Vec3& center, const HubStump& s) {
  const double sin_phi = (s.radius - s.other_radius) / s.length;
  const double cos_phi = std::sqrt(1.0 - sin_phi * sin_phi);
  const double x0 = s.radius * sin_phi, x1 = 0.5 * s.length;
  const double r0 = (s.radius - x0 * sin_phi) / cos_phi, r1 = (s.radius - x1 * sin_phi) / cos_phi;
  const gp_Ax2 axes(occ_point(center + x0 * s.axis), gp_Dir(s.axis.x, s.axis.y, s.axis.z));
  if (std::abs(r0 - r1) < 1e-12 * r0) return BRepPrimAPI_MakeCylinder(axes, r0, x1 - x0).Shape();
  return BRepPrimAPI_MakeCone(axes, r0, r1, x1 - x0).Shape();
}

// Fuses the pieces; nullopt when the fuse fails or its result is not a valid solid.
inline std::optional<TopoDS_Shape> occ_fuse(const std::vector<TopoDS_Shape>& pieces) {
  if (pieces.size() == 1) return pieces[0];
  TopTools_ListOfShape arguments, tools;
  arguments.Append(pieces[0]);
  for (std::size_t k = 1; k < pieces.size(); ++k) tools.Append(pieces[k]);
  BRepAlgoAPI_Fuse fuse;
  fuse.SetArguments(arguments);
  fuse.SetTools(tools);
  fuse.SetRunParallel(false);
  fuse.Build();
  if (!fuse.IsDone() || fuse.HasErrors()) return std::nullopt;
  const TopoDS_Shape shape = fuse.Shape();
  if (!BRepCheck_Analyzer(shape).IsValid()) return std::nullopt;
  return shape;
}

struct OccProperties {
  double volume = 0.0, area = 0.0;
  Vec3 centroid{0.0};
  Mat3 inertia{0.0};  // about the centroid, density 1
};

inline OccProperties occ_properties(const TopoDS_Shape& shape) {
  GProp_GProps volume, surface;
  BRepGProp::VolumeProperties(shape, volume, 1e-10);
  BRepGProp::SurfaceProperties(shape, surface, 1e-10);
  OccProperties p;
  p.volume = volume.Mass();
  p.area = surface.Mass();
  const gp_Pnt c = volume.CentreOfMass();
  p.centroid = Vec3(c.X(), c.Y(), c.Z());
  const gp_Mat m = volume.MatrixOfInertia();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) p.inertia[j][i] = m.Value(i + 1, j + 1);
  return p;
}

// A whole beam in the explicit-radii model: the frustum between its two tangent circles (the rest of the
// hull of its end balls lies inside the node balls).
inline TopoDS_Shape occ_beam(const Vec3& a, double ra, const Vec3& b, double rb) {
  const double L = glm::length(b - a);
  const Vec3 axis = (b - a) / L;
  const double sin_phi = (ra - rb) / L, cos_phi = std::sqrt(1.0 - sin_phi * sin_phi);
  const double x0 = ra * sin_phi, x1 = L + rb * sin_phi;
  const gp_Ax2 axes(occ_point(a + x0 * axis), gp_Dir(axis.x, axis.y, axis.z));
  if (std::abs(ra - rb) < 1e-12 * ra) return BRepPrimAPI_MakeCylinder(axes, ra, x1 - x0).Shape();
  return BRepPrimAPI_MakeCone(axes, ra * cos_phi, rb * cos_phi, x1 - x0).Shape();
}

// Every ball and beam of a listing fused by OpenCASCADE: the slow, obviously right twin of the builders' groups.
inline std::optional<TopoDS_Shape> occ_lattice_union(const FlatLattice& f) {
  std::vector<TopoDS_Shape> pieces;
  for (const Ball& ball : f.balls) pieces.push_back(BRepPrimAPI_MakeSphere(occ_point(ball.center), ball.radius).Shape());
  for (const FlatBeam& beam : f.beams)
    pieces.push_back(occ_beam(f.balls[beam.a].center, beam.ra, f.balls[beam.b].center, beam.rb));
  return occ_fuse(pieces);
}

inline std::optional<TopoDS_Shape> occ_hub(const HubShape& h) {
  std::vector<TopoDS_Shape> pieces{BRepPrimAPI_MakeSphere(occ_point(h.center), h.radius).Shape()};
  for (const HubStump& s : h.stumps) pieces.push_back(occ_stump(h.center, s));
  return occ_fuse(pieces);
}

}  // namespace steady::test
