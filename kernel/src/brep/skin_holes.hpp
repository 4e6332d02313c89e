#pragma once
// The union of the skin with the clipped boundary clusters, without a Boolean where none is needed. A cluster
// clipped by the skin's inner body touches the skin only along its cut faces: pieces of the inner boundary's
// faces, left by the cluster's Common on the very same surfaces. Where a cut face lies inside one face of the
// inner boundary, bounded only by the cluster's own section edges, the union there is that face with the cut
// face's outline as a hole, and the cluster without its cut face: the section edges are then shared by the
// skin and the lattice. A glued Fuse of the skin with thousands of clusters (one inner face taking thousands
// of holes) took most of 11 minutes at 10^5 beams and gave an invalid part (measured); cutting holes is local.
// Cut faces on the inner boundary's own edges or seams (a cluster straddling a rim) are not holes: such clusters
// are united with the skin through the pores (trim_skin_union.cpp).
#include <BRepAlgoAPI_BooleanOperation.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <string>
#include <vector>

namespace steady {

struct CutFace {
  TopoDS_Face face;    // as it lies in the cluster's result
  int inner_face = 0;  // which face of the inner boundary it comes from: its index in `tool_faces`
};

// The faces of `result` (a cluster's Common, possibly moved back from a turned frame) that are pieces of the
// tool's faces; `tool_faces`: the tool's faces as passed to `op` (TopExp::MapShapes order).
std::vector<CutFace> cut_faces(BRepAlgoAPI_BooleanOperation& op, const TopTools_IndexedMapOfShape& tool_faces,
                               const TopoDS_Shape& result);

// Whether each cut face can be a hole in its inner face: one wire, no degenerate edge, every edge used by the
// cut face once and by exactly one other face of `result`, which is not a cut face (so not the inner
// boundary's edges or seams), no vertex shared by two cut faces.
bool cut_faces_are_holes(const TopoDS_Shape& result, const std::vector<CutFace>& cuts);

// `pieces`: the faces that stand for one face of the inner boundary in the skin (the face itself, or its pieces
// after a Fuse), on the surface the holes' cut faces lie on, with the same parametrization. Returns the pieces
// with the holes cut, each piece with the orientation it had; the holes' edges gain a curve on the new faces.
// `verify`: check the new faces as BRepCheck would, locally (see skin_holes.cpp). Returns an empty vector and sets
// `error` when a hole lies in no piece, or the check fails.
std::vector<TopoDS_Face> pierce(const std::vector<TopoDS_Face>& pieces, const std::vector<TopoDS_Face>& holes,
                                bool verify, std::string& error);

}  // namespace steady
