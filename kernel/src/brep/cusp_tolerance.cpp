#include "brep/cusp_tolerance.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>

#include <algorithm>
#include <cmath>
#include <tuple>
#include <vector>

namespace steady {

namespace {

// Where two pcurves leaving one vertex count as parted, in (u, v): 100 times BRepCheck_Wire's intersection
// tolerance (1e-10), so the stretch it may report as an overlap (up to 1.7e-5 of the arc parameter from the cusp
// on issue 17's octet, measured) lies well inside the vertex: the distance grows as the square root, ten times.
constexpr double kCuspSeparation = 1e-8;
// Pairs of edges whose directions at the vertex differ by more than this (radians) part within about 1e-7 of a
// unit ball's vertex (measured: 6.7e-8 at 0.198 rad), which its tolerance already covers.
constexpr double kCuspAngle = 0.2;
// (u, v) gap under which two pcurves' ends are the same point (not on two sides of a periodic seam).
constexpr double kSameUv = 1e-6;

// An edge of a face as it leaves one of its vertices: its pcurve, the parameter at the vertex and at its other end.
struct Leaving {
  TopoDS_Vertex vertex;
  Handle(Geom2d_Curve) pcurve;
  double at = 0.0, toward = 0.0;
  gp_Pnt2d uv;
  gp_Vec2d direction;
};

std::vector<Leaving> leavings(const TopoDS_Face& face) {
  std::vector<Leaving> out;
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next()) {
    const TopoDS_Edge edge = TopoDS::Edge(x.Current());
    if (BRep_Tool::Degenerated(edge) || BRep_Tool::IsClosed(edge, face)) continue;  // poles, seams
    Standard_Real first, last;
    const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, first, last);
    if (pcurve.IsNull()) continue;
    TopoDS_Vertex v0, v1;
    TopExp::Vertices(edge, v0, v1);  // v0 at `first`, v1 at `last`
    for (const auto& [v, at, toward] : {std::make_tuple(v0, first, last), std::make_tuple(v1, last, first)}) {
      if (v.IsNull()) continue;
      Leaving l{v, pcurve, at, toward, gp_Pnt2d(), gp_Vec2d()};
      pcurve->D1(at, l.uv, l.direction);
      if (toward < at) l.direction.Reverse();
      if (l.direction.Magnitude() < 1e-12) continue;
      out.push_back(l);
    }
  }
  return out;
}

// Distance from q to b's pcurve near `t` (a parameter of b close to the foot of q): Newton steps on the foot,
// kept in b's range. (A general projection may find no interior extremum this close to b's end.)
double distance_near(const Leaving& b, const gp_Pnt2d& q, double t) {
  const double lo = std::min(b.at, b.toward), hi = std::max(b.at, b.toward);
  for (int k = 0; k < 8; ++k) {
    gp_Pnt2d p;
    gp_Vec2d d1, d2;
    b.pcurve->D2(t, p, d1, d2);
    const gp_Vec2d r(q, p);
    const double slope = d1.SquareMagnitude() + r.Dot(d2);
    if (!(slope > 0.0)) break;
    t = std::clamp(t - r.Dot(d1) / slope, lo, hi);
  }
  return q.Distance(b.pcurve->Value(t));
}

// How far from the vertex (3D) a's pcurve stays within kCuspSeparation of b's: the first of doubling steps along
// a where they have parted. 0 when a never parts from b (the edges overlap: not a cusp; the checker's business).
double confused_reach(const BRepAdaptor_Surface& surface, const Leaving& a, const Leaving& b, const gp_Pnt& vertex) {
  const double span = std::abs(a.toward - a.at), sign = a.toward > a.at ? 1.0 : -1.0;
  const double b_sign = b.toward > b.at ? 1.0 : -1.0, speed = a.direction.Magnitude() / b.direction.Magnitude();
  for (double step = span * 1e-9; step <= span; step *= 2.0) {
    const gp_Pnt2d q = a.pcurve->Value(a.at + sign * step);
    if (distance_near(b, q, b.at + b_sign * step * speed) > kCuspSeparation)
      return surface.Value(q.X(), q.Y()).Distance(vertex);
  }
  return 0.0;
}

}  // namespace

int widen_cusp_vertices(const TopoDS_Shape& shape) {
  const BRep_Builder builder;
  int widened = 0;
  for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) {
    const TopoDS_Face face = TopoDS::Face(f.Current());
    const std::vector<Leaving> ls = leavings(face);
    const BRepAdaptor_Surface surface(face, Standard_False);
    for (std::size_t i = 0; i < ls.size(); ++i)
      for (std::size_t j = i + 1; j < ls.size(); ++j) {
        const Leaving &a = ls[i], &b = ls[j];
        if (!a.vertex.IsSame(b.vertex) || a.uv.Distance(b.uv) > kSameUv) continue;
        if (std::abs(a.direction.Angle(b.direction)) > kCuspAngle) continue;
        const gp_Pnt p = BRep_Tool::Pnt(a.vertex);
        const double reach = std::max(confused_reach(surface, a, b, p), confused_reach(surface, b, a, p));
        if (reach > BRep_Tool::Tolerance(a.vertex)) {
          builder.UpdateVertex(a.vertex, reach);
          ++widened;
        }
      }
  }
  return widened;
}

}  // namespace steady
