#include "brep/pcurve_pieces.hpp"

#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>

#include <algorithm>

namespace steady {

namespace {
// Parameters closer than this to a curve's ends are its ends (vertices snap to them).
constexpr double kSameParameter = 1e-12;
}  // namespace

Handle(Geom2d_BSplineCurve) edge_pcurve(const Handle(Geom2d_BSplineCurve)& curve, double t0, double t1) {
  const double first = curve->FirstParameter(), last = curve->LastParameter();
  const double a = std::max(first, std::min(t0, t1)), b = std::min(last, std::max(t0, t1));
  if (a <= first + kSameParameter && b >= last - kSameParameter) return curve;
  Handle(Geom2d_BSplineCurve) piece = Handle(Geom2d_BSplineCurve)::DownCast(curve->Copy());
  piece->Segment(a, b);
  return piece;
}

int give_edges_their_own_pcurves(const TopoDS_Shape& shape) {
  const BRep_Builder builder;
  int replaced = 0;
  for (TopExp_Explorer f(shape, TopAbs_FACE); f.More(); f.Next()) {
    const TopoDS_Face& face = TopoDS::Face(f.Current());
    for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
      const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
      // Seams (two pcurves on the face) are lines here: nothing to cut.
      if (BRep_Tool::Degenerated(edge) || BRep_Tool::IsClosed(edge, face)) continue;
      double t0 = 0.0, t1 = 0.0;
      const Handle(Geom2d_BSplineCurve) curve =
          Handle(Geom2d_BSplineCurve)::DownCast(BRep_Tool::CurveOnSurface(edge, face, t0, t1));
      if (curve.IsNull()) continue;
      const Handle(Geom2d_BSplineCurve) piece = edge_pcurve(curve, t0, t1);
      if (piece == curve) continue;
      builder.UpdateEdge(edge, piece, face, BRep_Tool::Tolerance(edge));
      builder.Range(edge, face, t0, t1);
      ++replaced;
    }
  }
  return replaced;
}

}  // namespace steady
