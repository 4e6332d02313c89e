#include "steady/skin_holes.hpp"

#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Surface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Wire.hxx>

#include <memory>
#include <unordered_map>
#include <unordered_set>

namespace steady {

std::vector<CutFace> cut_faces(BRepAlgoAPI_BooleanOperation& op, const TopTools_IndexedMapOfShape& tool_faces,
                               const TopoDS_Shape& result) {
  // By TShape: `result` may be the Boolean's output moved back from a turned frame.
  std::unordered_map<const void*, int> inner_of;
  for (int i = 1; i <= tool_faces.Extent(); ++i) {
    const TopTools_ListOfShape& images = op.Modified(tool_faces(i));
    inner_of.emplace(tool_faces(i).TShape().get(), i);  // a tool face that came out untouched
    for (TopTools_ListOfShape::Iterator it(images); it.More(); it.Next()) inner_of.emplace(it.Value().TShape().get(), i);
  }
  std::vector<CutFace> out;
  for (TopExp_Explorer x(result, TopAbs_FACE); x.More(); x.Next()) {
    const auto it = inner_of.find(x.Current().TShape().get());
    if (it != inner_of.end()) out.push_back({TopoDS::Face(x.Current()), it->second});
  }
  return out;
}

bool cut_faces_are_holes(const TopoDS_Shape& result, const std::vector<CutFace>& cuts) {
  std::unordered_map<const void*, int> uses;  // edge occurrences in all faces (a seam counts twice)
  for (TopExp_Explorer x(result, TopAbs_FACE); x.More(); x.Next())
    for (TopExp_Explorer e(x.Current(), TopAbs_EDGE); e.More(); e.Next()) ++uses[e.Current().TShape().get()];
  std::unordered_map<const void*, int> cut_uses;   // edge occurrences in cut faces
  std::unordered_map<const void*, int> vertex_of;  // vertex -> the cut face using it
  for (std::size_t k = 0; k < cuts.size(); ++k) {
    int wires = 0;
    for (TopoDS_Iterator w(cuts[k].face); w.More(); w.Next()) ++wires;
    if (wires != 1) return false;
    for (TopExp_Explorer e(cuts[k].face, TopAbs_EDGE); e.More(); e.Next()) {
      if (BRep_Tool::Degenerated(TopoDS::Edge(e.Current()))) return false;
      ++cut_uses[e.Current().TShape().get()];
    }
    for (TopExp_Explorer v(cuts[k].face, TopAbs_VERTEX); v.More(); v.Next()) {
      const auto [it, inserted] = vertex_of.emplace(v.Current().TShape().get(), static_cast<int>(k));
      if (!inserted && it->second != static_cast<int>(k)) return false;
    }
  }
  for (const auto& [edge, count] : cut_uses)
    if (count != 1 || uses.at(edge) != 2) return false;
  return true;
}

namespace {

// A point of the hole's outline in the parameters of its surface, and the surface there.
bool outline_point(const TopoDS_Face& hole, gp_Pnt2d& uv) {
  TopExp_Explorer e(hole, TopAbs_EDGE);
  if (!e.More()) return false;
  double first = 0.0, last = 0.0;
  const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(TopoDS::Edge(e.Current()), hole, first, last);
  if (c.IsNull()) return false;
  uv = c->Value(0.5 * (first + last));
  return true;
}

// The two faces' surfaces give the same point at `uv` (within both faces' tolerances): the hole's curves on its
// surface are then curves on the piece's.
bool same_parametrization(const TopoDS_Face& piece, const TopoDS_Face& hole, const gp_Pnt2d& uv) {
  const Handle(Geom_Surface) a = BRep_Tool::Surface(piece), b = BRep_Tool::Surface(hole);
  if (a.IsNull() || b.IsNull() || a->DynamicType() != b->DynamicType()) return false;
  const double tolerance = BRep_Tool::Tolerance(piece) + BRep_Tool::Tolerance(hole);
  for (const double du : {0.0, 0.1}) {
    const gp_Pnt2d p(uv.X() + du, uv.Y() + du);
    if (a->Value(p.X(), p.Y()).Distance(b->Value(p.X(), p.Y())) > tolerance) return false;
  }
  return true;
}

}  // namespace

std::vector<TopoDS_Face> pierce(const std::vector<TopoDS_Face>& pieces, const std::vector<TopoDS_Face>& holes,
                                std::string& error) {
  std::vector<std::vector<const TopoDS_Face*>> holes_of(pieces.size());
  // One classifier per piece (a polygon of its boundary in its parameters), for all the holes.
  std::vector<std::unique_ptr<BRepTopAdaptor_FClass2d>> classifiers;
  for (const TopoDS_Face& piece : pieces)
    classifiers.push_back(std::make_unique<BRepTopAdaptor_FClass2d>(TopoDS::Face(piece.Oriented(TopAbs_FORWARD)),
                                                                    BRep_Tool::Tolerance(piece)));
  for (const TopoDS_Face& hole : holes) {
    const TopoDS_Face forward = TopoDS::Face(hole.Oriented(TopAbs_FORWARD));
    gp_Pnt2d uv;
    if (!outline_point(forward, uv)) {
      error = "a cut face has no curve on its surface";
      return {};
    }
    std::size_t home = pieces.size();
    for (std::size_t k = 0; k < pieces.size() && home == pieces.size(); ++k)
      if (classifiers[k]->Perform(uv) == TopAbs_IN) home = k;
    if (home == pieces.size()) {
      error = "a cut face lies in no piece of its inner face";
      return {};
    }
    if (!same_parametrization(pieces[home], forward, uv)) {
      error = "a cut face does not lie on its inner face's surface as parametrized";
      return {};
    }
    holes_of[home].push_back(&hole);
  }
  const BRep_Builder b;
  std::vector<TopoDS_Face> out;
  for (std::size_t k = 0; k < pieces.size(); ++k) {
    if (holes_of[k].empty()) {
      out.push_back(pieces[k]);
      continue;
    }
    const TopoDS_Face piece = TopoDS::Face(pieces[k].Oriented(TopAbs_FORWARD));
    TopLoc_Location location;
    const Handle(Geom_Surface)& surface = BRep_Tool::Surface(piece, location);
    TopoDS_Face face;
    b.MakeFace(face, surface, location, BRep_Tool::Tolerance(piece));
    for (TopoDS_Iterator w(piece); w.More(); w.Next()) b.Add(face, w.Value());
    for (const TopoDS_Face* hole : holes_of[k]) {
      const TopoDS_Face forward = TopoDS::Face(hole->Oriented(TopAbs_FORWARD));
      for (TopExp_Explorer e(forward, TopAbs_EDGE); e.More(); e.Next()) {
        const TopoDS_Edge& edge = TopoDS::Edge(e.Current());
        double first = 0.0, last = 0.0;
        const Handle(Geom2d_Curve) c = BRep_Tool::CurveOnSurface(edge, forward, first, last);
        b.UpdateEdge(edge, c, face, BRep_Tool::Tolerance(edge));
      }
      // The cut face's outline runs with the cut face on its left (in the common parameters); the hole's
      // runs the other way.
      for (TopoDS_Iterator w(forward); w.More(); w.Next()) b.Add(face, w.Value().Reversed());
    }
    out.push_back(TopoDS::Face(face.Oriented(pieces[k].Orientation())));
  }
  return out;
}

}  // namespace steady
