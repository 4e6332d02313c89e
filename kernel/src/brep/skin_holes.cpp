#include "brep/skin_holes.hpp"

#include <BRepTopAdaptor_FClass2d.hxx>
#include <BRep_Builder.hxx>
#include <BRepTools.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom_Surface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Wire.hxx>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <memory>
#include <numeric>
#include <unordered_map>
#include <unordered_set>

#include "steady/brep/brep_io.hpp"

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

// A point of the hole's outline, in the parameters of its surface.
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

// A face on the surface (and location) of `like` bounded by `wires`, each hole wire reversed.
TopoDS_Face face_on(const TopoDS_Face& like, const std::vector<TopoDS_Shape>& wires,
                    const std::vector<TopoDS_Shape>& holes) {
  const BRep_Builder b;
  TopLoc_Location location;
  const Handle(Geom_Surface)& surface = BRep_Tool::Surface(like, location);
  TopoDS_Face face;
  b.MakeFace(face, surface, location, BRep_Tool::Tolerance(like));
  for (const TopoDS_Shape& w : wires) b.Add(face, w);
  for (const TopoDS_Shape& w : holes) b.Add(face, w.Reversed());
  return face;
}

struct UVBox {
  double u0, u1, v0, v1;
  bool meets(const UVBox& o) const { return u0 <= o.u1 && o.u0 <= u1 && v0 <= o.v1 && o.v0 <= v1; }
};

// What BRepCheck checks on the pierced face, done locally: BRepCheck compares every pair of wires of a face
// (16 s for a face with 1,019 holes, measured; quadratic). Each hole is checked on a face of its own (its curves
// on the new surface), the holes whose parameter boxes meet in pairs, and the piece with the holes whose boxes
// meet its own edges'; holes apart from everything else cannot cross anything.
std::string check_holes(const TopoDS_Face& pierced, const TopoDS_Face& piece, const std::vector<TopoDS_Shape>& holes) {
  std::vector<TopoDS_Shape> piece_wires;
  for (TopoDS_Iterator w(piece); w.More(); w.Next()) piece_wires.push_back(w.Value());
  std::vector<UVBox> boxes(holes.size());
  std::atomic<bool> hole_invalid{false};
  tbb::parallel_for(std::size_t(0), holes.size(), [&](std::size_t k) {
    const TopoDS_Face alone = face_on(pierced, {holes[k]}, {});
    UVBox& box = boxes[k];
    BRepTools::UVBounds(alone, box.u0, box.u1, box.v0, box.v1);
    if (!is_valid(alone)) hole_invalid = true;
  });
  if (hole_invalid) return "a hole's outline is not valid on the skin's face";
  // A margin in the parameters, so that holes closer than it count as meeting.
  for (UVBox& box : boxes) {
    const double m = 1e-6 * std::max(box.u1 - box.u0, box.v1 - box.v0);
    box = {box.u0 - m, box.u1 + m, box.v0 - m, box.v1 + m};
  }
  std::vector<std::size_t> order(holes.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return boxes[a].u0 < boxes[b].u0; });
  for (std::size_t i = 0; i < order.size(); ++i)
    for (std::size_t j = i + 1; j < order.size() && boxes[order[j]].u0 <= boxes[order[i]].u1; ++j)
      if (boxes[order[i]].meets(boxes[order[j]]) &&
          !is_valid(face_on(pierced, piece_wires, {holes[order[i]], holes[order[j]]})))
        return "two holes in the skin's face cross";
  std::vector<UVBox> edge_boxes;
  for (TopExp_Explorer e(piece, TopAbs_EDGE); e.More(); e.Next()) {
    UVBox box{};
    BRepTools::UVBounds(piece, TopoDS::Edge(e.Current()), box.u0, box.u1, box.v0, box.v1);
    edge_boxes.push_back(box);
  }
  std::vector<TopoDS_Shape> near;
  for (std::size_t k = 0; k < holes.size(); ++k)
    if (std::any_of(edge_boxes.begin(), edge_boxes.end(), [&](const UVBox& e) { return e.meets(boxes[k]); }))
      near.push_back(holes[k]);
  if (!is_valid(face_on(pierced, piece_wires, near))) return "a hole crosses the boundary of the skin's face";
  return "";
}

}  // namespace

std::vector<TopoDS_Face> pierce(const std::vector<TopoDS_Face>& pieces, const std::vector<TopoDS_Face>& holes,
                                bool verify, std::string& error) {
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
    std::vector<TopoDS_Shape> piece_wires;
    for (TopoDS_Iterator w(piece); w.More(); w.Next()) piece_wires.push_back(w.Value());
    TopoDS_Face face = face_on(piece, piece_wires, {});
    std::vector<TopoDS_Shape> outlines;
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
      for (TopoDS_Iterator w(forward); w.More(); w.Next()) {
        b.Add(face, w.Value().Reversed());
        outlines.push_back(w.Value());
      }
    }
    if (verify) {
      error = check_holes(face, piece, outlines);
      if (!error.empty()) return {};
    }
    out.push_back(TopoDS::Face(face.Oriented(pieces[k].Orientation())));
  }
  return out;
}

}  // namespace steady
