#include "steady/brep/boundary_volume.hpp"

#include <BRepBndLib.hxx>
#include <BRepTools.hxx>
#include <Bnd_Box.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <Geom_Surface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "steady/core/errors.hpp"

namespace steady {

namespace {

// 12-point Gauss-Legendre on [-1, 1] (nodes symmetric: the positive half).
constexpr std::array<double, 6> kNodes = {0.1252334085114689, 0.3678314989981802, 0.5873179542866175,
                                          0.7699026741943047, 0.9041172563704749, 0.9815606342467192};
constexpr std::array<double, 6> kWeights = {0.2491470458134028, 0.2334925365383548, 0.2031674267230659,
                                            0.1600783285433462, 0.1069393259953184, 0.0471753363865118};

// Sum of g over [a, b] by 12-point Gauss-Legendre on `panels` equal panels.
template <typename G>
double gauss(double a, double b, int panels, const G& g) {
  double sum = 0.0;
  const double h = (b - a) / panels;
  for (int p = 0; p < panels; ++p) {
    const double mid = a + (p + 0.5) * h, half = 0.5 * h;
    for (std::size_t k = 0; k < kNodes.size(); ++k)
      sum += kWeights[k] * half * (g(mid - half * kNodes[k]) + g(mid + half * kNodes[k]));
  }
  return sum;
}

// Panels no wider than this (radians on periodic parameters, where the integrands are trigonometric).
constexpr double kPanel = 0.25;

class FaceShare {
 public:
  FaceShare(const TopoDS_Face& face, const gp_Pnt& origin) : surface_(BRep_Tool::Surface(face)), origin_(origin) {
    double umax, vmin, vmax;
    BRepTools::UVBounds(face, u_ref_, umax, vmin, vmax);
    u_panel_ = std::max((umax - u_ref_) / 8.0, 1e-300);  // non-periodic u: 16 panels across the face
    u_ref_ = 0.5 * (u_ref_ + umax);
    periodic_u_ = surface_->IsUPeriodic() || surface_->IsUClosed();
  }
  // (S - O) . (S_u x S_v) / 3 at (u, v), O the shape's middle (a far origin would lose digits).
  double density(double u, double v) const {
    gp_Pnt p;
    gp_Vec su, sv;
    surface_->D1(u, v, p, su, sv);
    return gp_Vec(origin_, p).Dot(su.Crossed(sv)) / 3.0;
  }
  // Integral of the density across u, from the face's middle u to u, at v.
  double across(double u, double v) const {
    const double width = periodic_u_ ? kPanel : u_panel_;
    const int panels = std::max(1, static_cast<int>(std::ceil(std::abs(u - u_ref_) / width)));
    return gauss(u_ref_, u, panels, [&](double s) { return density(s, v); });
  }
  // Integral of across(u, v) dv along the edge's (u, v) curve, as the edge runs in the face.
  double along(const TopoDS_Edge& edge, const TopoDS_Face& face) const {
    Standard_Real t0, t1;
    const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(edge, face, t0, t1);
    if (c.IsNull()) return std::nan("");
    // Break points: the B-spline's knots inside the range (the curve is smooth between them).
    std::vector<double> breaks = {t0};
    Handle(Geom2d_Curve) basis = c;
    if (auto trimmed = Handle(Geom2d_TrimmedCurve)::DownCast(c)) basis = trimmed->BasisCurve();
    if (auto spline = Handle(Geom2d_BSplineCurve)::DownCast(basis))
      for (int k = 1; k <= spline->NbKnots(); ++k)
        if (spline->Knot(k) > t0 && spline->Knot(k) < t1) breaks.push_back(spline->Knot(k));
    breaks.push_back(t1);
    double sum = 0.0;
    for (std::size_t k = 0; k + 1 < breaks.size(); ++k) {
      const double a = breaks[k], b = breaks[k + 1];
      const gp_Pnt2d middle = c->Value(0.5 * (a + b));
      const double reach = c->Value(a).Distance(middle) + c->Value(b).Distance(middle);
      const int panels = std::clamp(static_cast<int>(std::ceil(reach / kPanel)), 1, 256);
      sum += gauss(a, b, panels, [&](double t) {
        gp_Pnt2d uv;
        gp_Vec2d d;
        c->D1(t, uv, d);
        return d.Y() == 0.0 ? 0.0 : across(uv.X(), uv.Y()) * d.Y();
      });
    }
    return edge.Orientation() == TopAbs_REVERSED ? -sum : sum;
  }

 private:
  Handle(Geom_Surface) surface_;
  gp_Pnt origin_;
  double u_ref_ = 0.0, u_panel_ = 1.0;
  bool periodic_u_ = false;
};

}  // namespace

double face_volume_share(const TopoDS_Face& face, const gp_Pnt& origin) {
  const TopoDS_Face forward = TopoDS::Face(face.Oriented(TopAbs_FORWARD));
  const FaceShare share(forward, origin);
  double volume = 0.0;
  for (TopExp_Explorer e(forward, TopAbs_EDGE); e.More(); e.Next()) {
    const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
    if (!BRep_Tool::Degenerated(edge)) volume += share.along(edge, forward);
  }
  return face.Orientation() == TopAbs_REVERSED ? -volume : volume;
}

double boundary_volume(const TopoDS_Shape& shape, const char* what) {
  Bnd_Box box;
  BRepBndLib::Add(shape, box);
  if (box.IsVoid()) return 0.0;
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  const gp_Pnt middle(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1));
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) faces.push_back(TopoDS::Face(f.Current()));
  std::vector<double> shares(faces.size(), 0.0);
  tbb::parallel_for(std::size_t(0), faces.size(),
                    [&](std::size_t i) { shares[i] = face_volume_share(faces[i], middle); });
  double volume = 0.0;  // summed in the faces' order, so that the result does not depend on the threads
  for (const double share : shares) {
    if (std::isnan(share)) fail_input(what, "an edge of a face has no (u, v) curve on it");
    volume += share;
  }
  return volume;
}

}  // namespace steady
