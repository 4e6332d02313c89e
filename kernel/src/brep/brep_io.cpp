#include "steady/brep/brep_io.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <TopoDS.hxx>

#include <BRepCheck.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepCheck_ListOfStatus.hxx>
#include <BRepCheck_Result.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_CurveRepresentation.hxx>
#include <BRep_GCurve.hxx>
#include <BRep_ListIteratorOfListOfCurveRepresentation.hxx>
#include <BRep_ListIteratorOfListOfPointRepresentation.hxx>
#include <BRep_PointRepresentation.hxx>
#include <BRep_TEdge.hxx>
#include <BRep_TFace.hxx>
#include <BRep_TVertex.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom2d_Ellipse.hxx>
#include <Geom2d_Hyperbola.hxx>
#include <Geom2d_OffsetCurve.hxx>
#include <Geom2d_Parabola.hxx>
#include <Geom2d_TrimmedCurve.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Hyperbola.hxx>
#include <Geom_OffsetCurve.hxx>
#include <Geom_Parabola.hxx>
#include <Geom_TrimmedCurve.hxx>
#include <Precision.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>

#include <algorithm>
#include <cmath>
#include <ios>
#include <sstream>

#include "brep/child_reader.hpp"
#include "brep/occ_progress.hpp"
#include "steady/brep/boundary_volume.hpp"
#include "steady/core/errors.hpp"

namespace steady {

std::string brep_to_text(const TopoDS_Shape& shape, Progress& progress) {
  std::ostringstream os;
  OccProgress occ(progress);
  BRepTools::Write(shape, os, occ.range());
  occ.finish();
  return os.str();
}

TopoDS_Shape brep_from_text(const std::string& text, const std::string& field) {
  TopoDS_Shape shape;
  std::istringstream is(text);
  // OpenCASCADE's reader loops on `is >> value` until it reads a terminator (an edge's list of representations
  // ends with 0). Past the end of a truncated text the stream has failed, a failed extraction leaves the value as
  // it was, and such a loop never ends (issue 16, repro reliability/01: 100 % CPU forever). So every failed
  // extraction throws: a text that ends early or holds a malformed number is refused where the reader stops.
  is.exceptions(std::ios::failbit | std::ios::badbit);
  const BRep_Builder builder;
  try {
    BRepTools::Read(shape, is, builder);
  } catch (const Standard_Failure& e) {
    fail_input(field, std::string("is not BREP text (") + e.GetMessageString() + ")");
  } catch (const std::ios_base::failure&) {
    fail_input(field, "is not BREP text: it ends early or holds a malformed value (at character " +
                          std::to_string(static_cast<long long>(is.rdbuf()->pubseekoff(0, std::ios::cur, std::ios::in))) +
                          " of " + std::to_string(text.size()) + ")");
  }
  if (shape.IsNull()) fail_input(field, "is not BREP text, or holds no shape");
  require_complete_geometry(shape, field);
  return shape;
}

TopoDS_Shape read_body_brep(const std::string& text, const std::string& field,
                            const std::function<void(const TopoDS_Shape&)>& check) {
  const std::string binary = run_in_child(
      [&] {
        const TopoDS_Shape shape = brep_from_text(text, field);
        // Every caller checks the body next (validity, trimming), and the checker has crashed on shapes the reader
        // left incomplete (docs/reliability.md): it runs here first, where a crash is an error (sequential: the
        // child has no TBB workers).
        BRepCheck_Analyzer(shape, Standard_True, Standard_False).IsValid();
        if (check) check(shape);
        return shape_to_binary(shape);
      },
      field, "the BREP text", "BREP reader", text.size());
  return shape_from_binary(binary);
}

namespace {

bool finite(const gp_Pnt& p) { return std::isfinite(p.X()) && std::isfinite(p.Y()) && std::isfinite(p.Z()); }

// The size of a conic (a circle's radius, an ellipse's or hyperbola's minor radius, a parabola's focal length),
// through trimmed and offset curves; +inf for other curves. The readers take any numbers, and OpenCASCADE's
// intersections loop on a conic of no size: BRepCheck's wire self-intersection test ran for ever on an ellipse
// pcurve of radii 0 (found by fuzz_body_brep).
double conic_size(Handle(Geom2d_Curve) c) {
  for (int depth = 0; depth < 64 && !c.IsNull(); ++depth) {
    if (const Handle(Geom2d_TrimmedCurve) t = Handle(Geom2d_TrimmedCurve)::DownCast(c); !t.IsNull()) {
      c = t->BasisCurve();
    } else if (const Handle(Geom2d_OffsetCurve) o = Handle(Geom2d_OffsetCurve)::DownCast(c); !o.IsNull()) {
      c = o->BasisCurve();
    } else {
      break;
    }
  }
  if (const Handle(Geom2d_Circle) k = Handle(Geom2d_Circle)::DownCast(c); !k.IsNull()) return k->Radius();
  if (const Handle(Geom2d_Ellipse) k = Handle(Geom2d_Ellipse)::DownCast(c); !k.IsNull()) return k->MinorRadius();
  if (const Handle(Geom2d_Hyperbola) k = Handle(Geom2d_Hyperbola)::DownCast(c); !k.IsNull()) return k->MinorRadius();
  if (const Handle(Geom2d_Parabola) k = Handle(Geom2d_Parabola)::DownCast(c); !k.IsNull()) return k->Focal();
  return INFINITY;
}

double conic_size(Handle(Geom_Curve) c) {
  for (int depth = 0; depth < 64 && !c.IsNull(); ++depth) {
    if (const Handle(Geom_TrimmedCurve) t = Handle(Geom_TrimmedCurve)::DownCast(c); !t.IsNull()) {
      c = t->BasisCurve();
    } else if (const Handle(Geom_OffsetCurve) o = Handle(Geom_OffsetCurve)::DownCast(c); !o.IsNull()) {
      c = o->BasisCurve();
    } else {
      break;
    }
  }
  if (const Handle(Geom_Circle) k = Handle(Geom_Circle)::DownCast(c); !k.IsNull()) return k->Radius();
  if (const Handle(Geom_Ellipse) k = Handle(Geom_Ellipse)::DownCast(c); !k.IsNull()) return k->MinorRadius();
  if (const Handle(Geom_Hyperbola) k = Handle(Geom_Hyperbola)::DownCast(c); !k.IsNull()) return k->MinorRadius();
  if (const Handle(Geom_Parabola) k = Handle(Geom_Parabola)::DownCast(c); !k.IsNull()) return k->Focal();
  return INFINITY;
}

// A conic smaller than the resolution of its space (parameters for a pcurve, model units for a 3D curve) cannot
// carry an edge; NaN sizes count as none.
bool no_size(double size, double resolution) { return !(size > resolution); }

// What is wrong with one of an edge's representations (nullptr when nothing): each must hold the curves, surfaces
// and polygons it names (a record naming a curve or surface that did not read holds a null one).
const char* broken_representation(const Handle(BRep_CurveRepresentation)& r) {
  if (r.IsNull()) return "an empty representation";
  if (r->IsCurveOnSurface()) {
    if (r->Surface().IsNull()) return "a curve on a surface that did not read";
    if (r->PCurve().IsNull() || (r->IsCurveOnClosedSurface() && r->PCurve2().IsNull()))
      return "a curve on surface (pcurve) that did not read";
    if (no_size(conic_size(r->PCurve()), Precision::PConfusion()) ||
        (r->IsCurveOnClosedSurface() && no_size(conic_size(r->PCurve2()), Precision::PConfusion())))
      return "a curve on surface (pcurve) that is a circle or conic of no size";
  }
  if (r->IsCurve3D() && !r->Curve3D().IsNull() && no_size(conic_size(r->Curve3D()), Precision::Confusion()))
    return "a 3D curve that is a circle or conic of no size";
  if (r->IsRegularity() && (r->Surface().IsNull() || r->Surface2().IsNull())) return "a continuity between surfaces that did not read";
  if (r->IsPolygon3D() && r->Polygon3D().IsNull()) return "a 3D polygon that did not read";
  if (r->IsPolygonOnTriangulation() && (r->PolygonOnTriangulation().IsNull() || r->Triangulation().IsNull()))
    return "a polygon on a triangulation that did not read";
  if (r->IsPolygonOnSurface() && (r->Polygon().IsNull() || r->Surface().IsNull())) return "a polygon on a surface that did not read";
  if (r->IsCurve3D() || r->IsCurveOnSurface()) {
    const Handle(BRep_GCurve) g = Handle(BRep_GCurve)::DownCast(r);
    if (!g.IsNull() && !(std::isfinite(g->First()) && std::isfinite(g->Last()))) return "a curve of infinite range";
  }
  return nullptr;
}

const char* broken_point(const Handle(BRep_PointRepresentation)& p) {
  if (p.IsNull()) return "an empty point representation";
  if (p->IsPointOnCurve() && p->Curve().IsNull()) return "a point on a curve that did not read";
  if (p->IsPointOnCurveOnSurface() && (p->PCurve().IsNull() || p->Surface().IsNull()))
    return "a point on a curve on surface that did not read";
  if (p->IsPointOnSurface() && p->Surface().IsNull()) return "a point on a surface that did not read";
  return nullptr;
}

}  // namespace

void require_complete_geometry(const TopoDS_Shape& shape, const std::string& field) {
  auto refuse = [&](const char* kind, int number, const std::string& what) {  // numbered from 1, as in the maps
    fail_input(field, std::string(kind) + " #" + std::to_string(number) + " has " + what);
  };
  TopTools_IndexedMapOfShape faces, edges, vertices;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  TopExp::MapShapes(shape, TopAbs_EDGE, edges);
  TopExp::MapShapes(shape, TopAbs_VERTEX, vertices);
  for (int i = 1; i <= faces.Extent(); ++i) {
    const Handle(BRep_TFace) f = Handle(BRep_TFace)::DownCast(faces(i).TShape());
    if (f.IsNull() || f->Surface().IsNull()) refuse("face", i, "no surface (its record did not read)");
  }
  for (int i = 1; i <= edges.Extent(); ++i) {
    const Handle(BRep_TEdge) e = Handle(BRep_TEdge)::DownCast(edges(i).TShape());
    if (e.IsNull()) refuse("edge", i, "no geometry");
    bool has_curve = false;
    for (BRep_ListIteratorOfListOfCurveRepresentation it(e->Curves()); it.More(); it.Next()) {
      if (const char* what = broken_representation(it.Value())) refuse("edge", i, what);
      // A 3D curve representation may hold no curve (degenerated edges' do); what the checker needs is a curve.
      has_curve |= it.Value()->IsCurve3D() && !it.Value()->Curve3D().IsNull();
    }
    // The reader drops the 3D curve of an edge whose curve record did not read; BRepCheck_Edge then crashes.
    if (!has_curve && !e->Degenerated()) refuse("edge", i, "no 3D curve (its record did not read)");
  }
  for (int i = 1; i <= vertices.Extent(); ++i) {
    const Handle(BRep_TVertex) v = Handle(BRep_TVertex)::DownCast(vertices(i).TShape());
    if (v.IsNull() || !finite(v->Pnt())) refuse("vertex", i, "no finite point");
    for (BRep_ListIteratorOfListOfPointRepresentation it(v->Points()); it.More(); it.Next())
      if (const char* what = broken_point(it.Value())) refuse("vertex", i, what);
  }
}

// The kind of a face's surface, for error messages.
const char* surface_name(const TopoDS_Face& face) {
  switch (BRepAdaptor_Surface(face, Standard_False).GetType()) {
    case GeomAbs_Plane: return "plane";
    case GeomAbs_Cylinder: return "cylinder";
    case GeomAbs_Cone: return "cone";
    case GeomAbs_Sphere: return "sphere";
    case GeomAbs_Torus: return "torus";
    default: return "free-form surface";
  }
}

bool is_valid(const TopoDS_Shape& shape) {
  // The parallel analyzer checks faces on all cores; the verdict is the same.
  return !shape.IsNull() && BRepCheck_Analyzer(shape, Standard_True, Standard_True).IsValid();
}

std::string validity_report(const TopoDS_Shape& shape, int max_lines) {
  if (shape.IsNull()) return "null shape";
  BRepCheck_Analyzer analyzer(shape);
  if (analyzer.IsValid()) return "";
  static const char* kNames[] = {"compound", "compsolid", "solid", "shell", "face", "wire", "edge", "vertex"};
  std::ostringstream os;
  int lines = 0;
  for (TopAbs_ShapeEnum type : {TopAbs_SOLID, TopAbs_SHELL, TopAbs_FACE, TopAbs_WIRE, TopAbs_EDGE, TopAbs_VERTEX}) {
    TopTools_IndexedMapOfShape map;
    TopExp::MapShapes(shape, type, map);
    for (int i = 1; i <= map.Extent() && lines < max_lines; ++i) {
      const Handle(BRepCheck_Result) r = analyzer.Result(map(i));
      if (r.IsNull()) continue;
      auto report = [&](const BRepCheck_ListOfStatus& list) {
        for (auto it = list.cbegin(); it != list.cend() && lines < max_lines; ++it) {
          if (*it == BRepCheck_NoError) continue;
          std::ostringstream status;
          BRepCheck::Print(*it, status);
          std::string s = status.str();
          while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
          os << kNames[type] << " #" << i;
          if (type == TopAbs_FACE) os << " (" << surface_name(TopoDS::Face(map(i))) << ")";
          os << ": " << s << "\n";
          ++lines;
        }
      };
      report(r->Status());
      for (r->InitContextIterator(); r->MoreShapeInContext(); r->NextShapeInContext()) report(r->StatusOnShape());
    }
  }
  const std::string s = os.str();
  return s.empty() ? "invalid (no sub-shape status)" : s;
}

double shape_volume(const TopoDS_Shape& shape) { return boundary_volume(shape); }

std::int64_t count_subshapes(const TopoDS_Shape& shape, int type) {
  TopTools_IndexedMapOfShape map;
  TopExp::MapShapes(shape, static_cast<TopAbs_ShapeEnum>(type), map);
  return map.Extent();
}

std::int64_t face_count(const TopoDS_Shape& shape) { return count_subshapes(shape, TopAbs_FACE); }
std::int64_t solid_count(const TopoDS_Shape& shape) { return count_subshapes(shape, TopAbs_SOLID); }

double max_edge_tolerance(const TopoDS_Shape& shape) {
  double largest = 0.0;
  for (TopExp_Explorer e(shape, TopAbs_EDGE); e.More(); e.Next())
    largest = std::max(largest, BRep_Tool::Tolerance(TopoDS::Edge(e.Current())));
  return largest;
}

}  // namespace steady
