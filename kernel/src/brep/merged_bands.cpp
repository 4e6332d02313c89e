#include "brep/merged_bands.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <ElSLib.hxx>
#include <Geom2d_Curve.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Trsf2d.hxx>

#include <cmath>
#include <optional>
#include <unordered_map>

#include "steady/brep/brep_builder.hpp"

namespace steady {

namespace {

// How far a band's edges mapped onto the stump's surface may lie from where they are (model units).
constexpr double kMapTolerance = 1e-9;

bool on_beam_surface(const TopoDS_Face& face) {
  const GeomAbs_SurfaceType type = BRepAdaptor_Surface(face, Standard_False).GetType();
  return type == GeomAbs_Cone || type == GeomAbs_Cylinder;
}

bool is_closed_circle(const TopoDS_Edge& edge) {
  TopoDS_Vertex a, b;
  TopExp::Vertices(edge, a, b);
  Standard_Real f, l;
  const Handle(Geom_Curve) curve = BRep_Tool::Curve(edge, f, l);
  return !a.IsNull() && a.IsSame(b) && !curve.IsNull() && BRepAdaptor_Curve(edge).GetType() == GeomAbs_Circle;
}

// One wire of circles (or arcs) and a seam on a beam's cone.
bool is_band(const TopoDS_Face& face) {
  if (!on_beam_surface(face)) return false;
  int wires = 0;
  for (TopExp_Explorer w(face, TopAbs_WIRE); w.More(); w.Next()) ++wires;
  if (wires != 1) return false;
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next()) {
    const TopoDS_Edge& e = TopoDS::Edge(x.Current());
    if (!BRep_Tool::IsClosed(e, face) && BRepAdaptor_Curve(e).GetType() != GeomAbs_Circle) return false;
  }
  return true;
}

// The (u, v) of `p` on the face's cone or cylinder (its location applied).
gp_Pnt2d parameters_on(const BRepAdaptor_Surface& s, const gp_Pnt& p) {
  double u = 0.0, v = 0.0;
  if (s.GetType() == GeomAbs_Cylinder)
    ElSLib::Parameters(s.Cylinder(), p, u, v);
  else
    ElSLib::Parameters(s.Cone(), p, u, v);
  return gp_Pnt2d(u, v);
}

// The isometry of (u, v) taking the band's parametrization to the stump's: u' = su u + cu, v' = sv v + cv with
// su = sv (orientation kept), fixed by the collar's two pcurves (so that its own period branch matches).
std::optional<gp_Trsf2d> band_to_stump(const TopoDS_Face& band, const TopoDS_Face& stump, const TopoDS_Edge& collar) {
  Standard_Real f, l, fs, ls;
  const TopoDS_Edge c = TopoDS::Edge(collar.Oriented(TopAbs_FORWARD));
  const Handle(Geom2d_Curve) on_band = BRep_Tool::CurveOnSurface(c, band, f, l);
  const Handle(Geom2d_Curve) on_stump = BRep_Tool::CurveOnSurface(c, stump, fs, ls);
  if (on_band.IsNull() || on_stump.IsNull() || std::abs(f - fs) > 1e-12 || std::abs(l - ls) > 1e-12) return {};
  const double t0 = f + 0.25 * (l - f), t1 = f + 0.5 * (l - f);
  const gp_Pnt2d b0 = on_band->Value(t0), b1 = on_band->Value(t1), s0 = on_stump->Value(t0), s1 = on_stump->Value(t1);
  const double su = (s1.X() - s0.X()) / (b1.X() - b0.X());
  if (!(std::abs(std::abs(su) - 1.0) < 1e-9)) return {};
  // sv from a point of the band off the collar, placed on the stump's surface.
  const BRepAdaptor_Surface band_surface(band), stump_surface(stump);
  const double dv = 0.01;
  const gp_Pnt2d off = parameters_on(stump_surface, band_surface.Value(b0.X(), b0.Y() + dv));
  const double sv = (off.Y() - s0.Y()) / dv;
  if (!(std::abs(std::abs(sv) - 1.0) < 1e-6) || (su > 0) != (sv > 0)) return {};
  gp_Trsf2d map;
  if (su > 0)
    map.SetTranslation(gp_Vec2d(s0.X() - b0.X(), s0.Y() - b0.Y()));
  else
    map.SetMirror(gp_Pnt2d(0.5 * (s0.X() + b0.X()), 0.5 * (s0.Y() + b0.Y())));
  return map;
}

Handle(Geom2d_Curve) mapped(const Handle(Geom2d_Curve)& curve, const gp_Trsf2d& map) {
  return Handle(Geom2d_Curve)::DownCast(curve->Transformed(map));
}

// Whether the mapped pcurves of every band edge lie where the band's own do, in 3D.
bool map_holds(const TopoDS_Face& band, const TopoDS_Face& stump, const gp_Trsf2d& map) {
  const BRepAdaptor_Surface band_surface(band), stump_surface(stump);
  for (TopExp_Explorer x(band, TopAbs_EDGE); x.More(); x.Next()) {
    Standard_Real f, l;
    const Handle(Geom2d_Curve) pc = BRep_Tool::CurveOnSurface(TopoDS::Edge(x.Current()), band, f, l);
    if (pc.IsNull()) return false;
    const Handle(Geom2d_Curve) moved = mapped(pc, map);
    for (int k = 0; k <= 4; ++k) {
      const double t = f + (l - f) * k / 4.0;
      const gp_Pnt2d p = pc->Value(t), q = moved->Value(t);
      if (band_surface.Value(p.X(), p.Y()).Distance(stump_surface.Value(q.X(), q.Y())) > kMapTolerance) return false;
    }
  }
  return true;
}

// The edges of the face's wire holding `edge`, in order, with their orientations as the face (taken forward)
// uses them; `at` is where `edge` is.
std::vector<TopoDS_Edge> wire_edges(const TopoDS_Face& face, const TopoDS_Edge& edge, std::size_t& at, bool& found) {
  found = false;
  for (TopExp_Explorer w(face.Oriented(TopAbs_FORWARD), TopAbs_WIRE); w.More(); w.Next()) {
    std::vector<TopoDS_Edge> edges;
    for (TopoDS_Iterator it(w.Current()); it.More(); it.Next()) {
      if (it.Value().IsSame(edge)) at = edges.size(), found = true;
      edges.push_back(TopoDS::Edge(it.Value()));
    }
    if (found) return edges;
  }
  return {};
}

// The stump with the band merged across `collar`, or nothing when the two do not fit.
std::optional<TopoDS_Face> merged_face(const TopoDS_Face& stump, const TopoDS_Face& band, const TopoDS_Edge& collar) {
  if (stump.Orientation() != band.Orientation()) return {};
  const std::optional<gp_Trsf2d> map = band_to_stump(band, stump, collar);
  if (!map || !map_holds(band, stump, *map)) return {};
  std::size_t in_stump = 0, in_band = 0;
  bool stump_has = false, band_has = false;
  const std::vector<TopoDS_Edge> stump_wire = wire_edges(stump, collar, in_stump, stump_has);
  const std::vector<TopoDS_Edge> band_wire = wire_edges(band, collar, in_band, band_has);
  if (!stump_has || !band_has) return {};
  const BRep_Builder b;
  TopLoc_Location location;
  const Handle(Geom_Surface) surface = BRep_Tool::Surface(stump, location);
  TopoDS_Face out;
  b.MakeFace(out, surface, location, BRep_Tool::Tolerance(stump));
  // The band's edges on the stump's surface. This adds a representation to edges the unmerged cluster shares
  // (only the band's, on the stump's surface, exact): harmless to it, whose faces never ask for them.
  TopTools_IndexedMapOfShape band_edges;
  TopExp::MapShapes(band, TopAbs_EDGE, band_edges);
  for (int i = 1; i <= band_edges.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(band_edges(i));
    if (e.IsSame(collar)) continue;
    const TopoDS_Edge forward = TopoDS::Edge(e.Oriented(TopAbs_FORWARD));
    Standard_Real f, l;
    const double tolerance = BRep_Tool::Tolerance(e);
    if (BRep_Tool::IsClosed(e, band)) {
      const Handle(Geom2d_Curve) c1 = BRep_Tool::CurveOnSurface(forward, band, f, l);
      const Handle(Geom2d_Curve) c2 = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Oriented(TopAbs_REVERSED)), band, f, l);
      b.UpdateEdge(forward, mapped(c1, *map), mapped(c2, *map), out, tolerance);
    } else {
      b.UpdateEdge(forward, mapped(BRep_Tool::CurveOnSurface(forward, band, f, l), *map), out, tolerance);
    }
  }
  TopoDS_Wire wire;
  b.MakeWire(wire);
  for (std::size_t k = 0; k < in_stump; ++k) b.Add(wire, stump_wire[k]);
  for (std::size_t k = 1; k < band_wire.size(); ++k) b.Add(wire, band_wire[(in_band + k) % band_wire.size()]);
  for (std::size_t k = in_stump + 1; k < stump_wire.size(); ++k) b.Add(wire, stump_wire[k]);
  b.Add(out, wire);
  // The other wires of both as they were.
  for (const TopoDS_Face* face : {&stump, &band})
    for (TopExp_Explorer w(face->Oriented(TopAbs_FORWARD), TopAbs_WIRE); w.More(); w.Next()) {
      bool holds = false;
      for (TopoDS_Iterator it(w.Current()); it.More() && !holds; it.Next()) holds = it.Value().IsSame(collar);
      if (!holds) b.Add(out, w.Current());
    }
  out.Orientation(stump.Orientation());
  if (!BRepCheck_Analyzer(out).IsValid()) return {};
  return out;
}

}  // namespace

MergedBands merge_bands_into_stumps(const std::vector<TopoDS_Face>& faces) {
  MergedBands out;
  out.faces = faces;
  std::vector<char> gone(faces.size(), 0);
  // The faces using each edge, kept current as faces are replaced.
  std::unordered_map<const void*, std::vector<std::size_t>> users;
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (TopExp_Explorer x(faces[i], TopAbs_EDGE); x.More(); x.Next()) {
      std::vector<std::size_t>& u = users[x.Current().TShape().get()];
      if (u.empty() || u.back() != i) u.push_back(i);
    }
  for (std::size_t t = 0; t < faces.size(); ++t) {
    if (gone[t] || !is_band(out.faces[t])) continue;
    for (TopExp_Explorer x(out.faces[t], TopAbs_EDGE); x.More(); x.Next()) {
      const TopoDS_Edge& collar = TopoDS::Edge(x.Current());
      if (!is_closed_circle(collar)) continue;
      const std::vector<std::size_t>& u = users[collar.TShape().get()];
      if (u.size() != 2) continue;
      const std::size_t s = u[0] == t ? u[1] : u[0];
      if (s == t || gone[s] || !on_beam_surface(out.faces[s]) || is_band(out.faces[s])) continue;
      std::optional<TopoDS_Face> merged;
      try {
        merged = merged_face(out.faces[s], out.faces[t], collar);
      } catch (const Standard_Failure&) {
      }
      if (!merged) continue;
      // The band's edges are now the stump's.
      for (TopExp_Explorer y(out.faces[t], TopAbs_EDGE); y.More(); y.Next())
        for (std::size_t& user : users[y.Current().TShape().get()])
          if (user == t) user = s;
      out.faces[s] = *merged;
      gone[t] = 1;
      ++out.merged;
      break;
    }
  }
  std::vector<TopoDS_Face> kept;
  for (std::size_t i = 0; i < faces.size(); ++i)
    if (!gone[i]) kept.push_back(out.faces[i]);
  out.faces = std::move(kept);
  return out;
}

TopoDS_Shape with_bands_merged(const TopoDS_Shape& cluster) {
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer x(cluster, TopAbs_FACE); x.More(); x.Next()) faces.push_back(TopoDS::Face(x.Current()));
  const MergedBands merged = merge_bands_into_stumps(faces);
  return merged.merged ? solids_from_faces(merged.faces) : TopoDS_Shape();
}

}  // namespace steady
