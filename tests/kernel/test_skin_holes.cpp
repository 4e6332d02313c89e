// Gluing a clipped cluster to the skin by a hole in its inner face (steady/skin_holes.hpp), on shapes whose union
// is known in closed form: a skin between the boxes [-1, 11]^3 and [0, 10]^3, and a cylinder of radius 1 clipped
// by the inner box. The glued part must be one valid solid of the exact volume; a cut face that runs along the
// inner box's edges must be refused as a hole.
#include <BRepAlgoAPI_Common.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp_Face.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRep_Builder.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <unordered_set>

#include "steady/brep/brep_io.hpp"
#include "brep/skin_holes.hpp"

using namespace steady;

namespace {

struct Clipped {
  BRepAlgoAPI_Common op;
  TopTools_IndexedMapOfShape tool_faces;
  TopoDS_Shape result;
};

// The cylinder of radius 1 on the axis (x, y, z0) + t (0, 0, 1), t in [0, 4], clipped by `inner` as trim.cpp
// clips a cluster (non-destructive).
void clip(Clipped& c, const TopoDS_Shape& inner, double x, double y, double z0) {
  const TopoDS_Shape cylinder = BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(x, y, z0), gp_Dir(0, 0, 1)), 1.0, 4.0).Shape();
  TopTools_ListOfShape args, tools;
  args.Append(cylinder);
  tools.Append(inner);
  c.op.SetArguments(args);
  c.op.SetTools(tools);
  c.op.SetNonDestructive(Standard_True);
  c.op.Build();
  ASSERT_TRUE(c.op.IsDone());
  c.result = c.op.Shape();
  TopExp::MapShapes(inner, TopAbs_FACE, c.tool_faces);
}

// The point at the middle of a face's parameter range, and the face's normal there.
std::pair<gp_Pnt, gp_Vec> middle(const TopoDS_Face& face) {
  BRepGProp_Face surface(face);
  double u0, u1, v0, v1;
  surface.Bounds(u0, u1, v0, v1);
  gp_Pnt p;
  gp_Vec n;
  surface.Normal(0.5 * (u0 + u1), 0.5 * (v0 + v1), p, n);
  return {p, n};
}

struct Skin {
  TopoDS_Shape inner = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(10, 10, 10)).Shape();
  TopoDS_Shape outer = BRepPrimAPI_MakeBox(gp_Pnt(-1, -1, -1), gp_Pnt(11, 11, 11)).Shape();
  TopoDS_Solid solid;  // outer shell, and the inner box's shell reversed as a void
  Skin() {
    const BRep_Builder b;
    b.MakeSolid(solid);
    for (TopExp_Explorer x(outer, TopAbs_SHELL); x.More(); x.Next()) b.Add(solid, x.Current());
    for (TopExp_Explorer x(inner, TopAbs_SHELL); x.More(); x.Next()) b.Add(solid, x.Current().Reversed());
  }
};

}  // namespace

TEST(SkinHoles, CutFaceInsideAFaceBecomesAHoleAndTheUnionIsExact) {
  Skin skin;
  Clipped c;
  clip(c, skin.inner, 5.0, 4.0, 8.0);  // crosses the top face z = 10 far from its edges: z in [8, 10] is kept
  const std::vector<CutFace> cuts = cut_faces(c.op, c.tool_faces, c.result);
  ASSERT_EQ(cuts.size(), 1u);
  TopTools_IndexedMapOfShape inner_faces;
  TopExp::MapShapes(skin.inner, TopAbs_FACE, inner_faces);
  const TopoDS_Face top = TopoDS::Face(inner_faces(cuts[0].inner_face));
  EXPECT_NEAR(middle(top).first.Z(), 10.0, 1e-12) << "the cut face is said to come from another face than the top";
  EXPECT_TRUE(cut_faces_are_holes(c.result, cuts));

  // The skin's inner shell with the hole in its top face, and the cylinder's faces but the cut face.
  std::string error;
  std::vector<TopoDS_Face> faces;
  for (TopExp_Explorer x(skin.solid, TopAbs_FACE); x.More(); x.Next()) {
    if (!x.Current().IsSame(top)) {
      faces.push_back(TopoDS::Face(x.Current()));
      continue;
    }
    const std::vector<TopoDS_Face> pierced = pierce({TopoDS::Face(x.Current())}, {cuts[0].face}, true, error);
    ASSERT_EQ(pierced.size(), 1u) << error;
    EXPECT_EQ(pierced[0].Orientation(), x.Current().Orientation());
    faces.push_back(pierced[0]);
  }
  for (TopExp_Explorer x(c.result, TopAbs_FACE); x.More(); x.Next())
    if (!x.Current().IsSame(cuts[0].face)) faces.push_back(TopoDS::Face(x.Current()));
  // Outer box (6 faces) in one shell, the rest (void with the cylinder in it) in the other.
  const BRep_Builder b;
  TopoDS_Shell outer, inner;
  b.MakeShell(outer);
  b.MakeShell(inner);
  std::unordered_set<const void*> outer_faces;
  for (TopExp_Explorer x(skin.outer, TopAbs_FACE); x.More(); x.Next()) outer_faces.insert(x.Current().TShape().get());
  for (const TopoDS_Face& f : faces) b.Add(outer_faces.count(f.TShape().get()) ? outer : inner, f);
  outer.Closed(Standard_True);
  inner.Closed(Standard_True);
  TopoDS_Solid part;
  b.MakeSolid(part);
  b.Add(part, outer);
  b.Add(part, inner);
  EXPECT_TRUE(BRepCheck_Analyzer(part).IsValid());
  const double exact = std::pow(12.0, 3) - std::pow(10.0, 3) + M_PI * 2.0;
  EXPECT_NEAR(shape_volume(part) / exact, 1.0, 1e-9);
}

TEST(SkinHoles, CutFacesAlongTheInnerBoundarysEdgesAreNoHoles) {
  Skin skin;
  Clipped c;
  clip(c, skin.inner, 10.0, 4.0, 8.0);  // its axis on the face x = 10: the kept half-cylinder meets two faces
  const std::vector<CutFace> cuts = cut_faces(c.op, c.tool_faces, c.result);
  ASSERT_EQ(cuts.size(), 2u);
  EXPECT_NE(cuts[0].inner_face, cuts[1].inner_face);
  EXPECT_FALSE(cut_faces_are_holes(c.result, cuts));
}

TEST(SkinHoles, HoleOutsideItsFaceIsAnError) {
  Skin skin;
  Clipped c;
  clip(c, skin.inner, 5.0, 4.0, 8.0);
  const std::vector<CutFace> cuts = cut_faces(c.op, c.tool_faces, c.result);
  ASSERT_EQ(cuts.size(), 1u);
  // The bottom face z = 0 (same kind of surface, another plane): the hole's outline is not in it.
  TopoDS_Face bottom;
  for (TopExp_Explorer x(skin.inner, TopAbs_FACE); x.More(); x.Next()) {
    const auto [p, n] = middle(TopoDS::Face(x.Current()));
    if (std::abs(p.Z()) < 1e-12 && std::abs(n.Z()) > 0.5) bottom = TopoDS::Face(x.Current());
  }
  ASSERT_FALSE(bottom.IsNull());
  std::string error;
  EXPECT_TRUE(pierce({bottom}, {cuts[0].face}, true, error).empty());
  EXPECT_FALSE(error.empty());
}

TEST(SkinHoles, CrossingHolesAreRefusedByTheLocalCheck) {
  Skin skin;
  Clipped a, b;
  clip(a, skin.inner, 5.0, 4.0, 8.0);
  clip(b, skin.inner, 5.5, 4.5, 8.0);  // overlaps the first on the top face
  const std::vector<CutFace> ca = cut_faces(a.op, a.tool_faces, a.result), cb = cut_faces(b.op, b.tool_faces, b.result);
  ASSERT_EQ(ca.size(), 1u);
  ASSERT_EQ(cb.size(), 1u);
  TopTools_IndexedMapOfShape inner_faces;
  TopExp::MapShapes(skin.inner, TopAbs_FACE, inner_faces);
  const TopoDS_Face top = TopoDS::Face(inner_faces(ca[0].inner_face));
  std::string error;
  EXPECT_EQ(pierce({top}, {ca[0].face}, true, error).size(), 1u) << error;
  EXPECT_TRUE(pierce({top}, {ca[0].face, cb[0].face}, true, error).empty());
  EXPECT_EQ(error, "two holes in the skin's face cross");
}
