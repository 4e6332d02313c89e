#pragma once
// Thin bands of cone merged into the stumps beside them. Between two crowded hubs' tight collars a beam keeps a
// band of cone a few thousandths of its radius wide (0.00284 and 0.00567 on the BCC at beam/node 1.0: 243 of its
// boundary cluster's 493 beam faces), split by a joint ring where the two collars have no common vertex direction.
// OpenCASCADE's section of such a band with a curved body misses it about one time in four, its split edges do
// not close, and the Common of the whole cluster with a cylinder came out empty in every layout, frame and fuzzy
// value (docs/brep.md, section 3). Merged into the stump beside it (the same cone), no face is thin any more.
//
// A band is a face on a beam's cone whose one wire holds only circles (or arcs of them) and its seam. It is merged
// into the face across one of its full circles (a collar) when that face lies on the same cone and is no band:
// the band's edges get pcurves on the stump's surface (its own carried over by the isometry of the two
// parametrizations, found from the collar's two pcurves and checked on the band's edges), and the stump's wire
// takes the band's edges in place of the collar. OpenCASCADE 7.6's `ShapeUpgrade_UnifySameDomain` throws on these
// faces ("TopoDS_Vertex hasn't gp_Pnt", on a whole cluster and on one beam's faces alike), hence this narrow merge
// of our own.
#include <TopoDS_Face.hxx>
#include <TopoDS_Shape.hxx>

#include <vector>

namespace steady {

struct MergedBands {
  std::vector<TopoDS_Face> faces;  // the faces with each merged band gone and its stump replaced
  int merged = 0;                  // bands merged
};

// Every band of `faces` merged into a stump where it can be; every other face comes back as the very same face.
// The merged stumps are checked (BRepCheck) and a merge that does not pass is not made.
MergedBands merge_bands_into_stumps(const std::vector<TopoDS_Face>& faces);

// The solids of `cluster` with their bands merged, or a null shape when it has none to merge.
TopoDS_Shape with_bands_merged(const TopoDS_Shape& cluster);

}  // namespace steady
