#include "steady/brep/skin.hpp"

#include <BRepOffsetAPI_MakeOffsetShape.hxx>
#include <BRepLib.hxx>
#include <BRep_Builder.hxx>
#include <ShapeFix_ShapeTolerance.hxx>
#include <BRep_Tool.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Vertex.hxx>

#include <cmath>
#include <sstream>

#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"
#include "brep/canonical_order.hpp"
#include "brep/occ_progress.hpp"

namespace steady {

namespace {

// Offset tolerance: OpenCASCADE's confusion tolerance.
constexpr double kOffsetTolerance = 1e-7;
// The offset boundary may come closer to the body's boundary than the thickness by this fraction only (rounding
// of the offset surfaces); anything closer means the offset folded over itself.
constexpr double kThicknessSlack = 1e-6;

[[noreturn]] void too_thick(double t, const std::string& why) {
  std::ostringstream os;
  os << "a wall of thickness " << t << " does not fit in the body (" << why << ")";
  fail_input("skin", os.str());
}

}  // namespace

Skin make_skin(const SolidBody& body, double thickness, Progress& progress) {
  if (!std::isfinite(thickness) || thickness < 0.0) {
    std::ostringstream os;
    os << "must be a thickness >= 0 (got " << thickness << ")";
    fail_input("skin", os.str());
  }
  if (thickness == 0.0) fail_input("skin", "must be > 0 to make a skin");
  Skin out;
  out.thickness = thickness;
  TopoDS_Shape offset;
  // The offset is nearly all the work; the checks after it are the last tenth.
  progress.set_total(10);
  Progress offset_progress(progress, 9);
  OccProgress occ(offset_progress);
  try {
    BRepOffsetAPI_MakeOffsetShape maker;
    maker.PerformByJoin(body.solid(), -thickness, kOffsetTolerance, BRepOffset_Skin, Standard_False, Standard_False,
                        GeomAbs_Arc, Standard_False, occ.range());
    occ.finish();  // a cancelled offset is not a failed one
    if (!maker.IsDone()) too_thick(thickness, "the inward offset failed");
    offset = maker.Shape();
  } catch (const Standard_Failure& e) {
    if (occ.cancelled()) throw Cancelled();
    too_thick(thickness, std::string("the inward offset failed: ") + e.GetMessageString());
  }
  TopoDS_Shell inner_shell;
  int shells = 0;
  for (TopExp_Explorer x(offset, TopAbs_SHELL); x.More(); x.Next(), ++shells) inner_shell = TopoDS::Shell(x.Current());
  if (shells != 1) too_thick(thickness, "the inward offset has " + std::to_string(shells) + " shells");
  // BRepOffset orders its faces and edges by memory address: put them in an order of their geometry, so that the
  // Booleans against the inner wall, and the files, come out the same each time.
  inner_shell = in_canonical_order(inner_shell);
  const BRep_Builder b;
  b.MakeSolid(out.inner);
  b.Add(out.inner, inner_shell);
  // BRepOffset leaves its working tolerance (1e-3) on every edge and vertex, though the offset of analytic faces
  // is exact: such tolerances make the Booleans on the boundary hubs see contacts that are not there. Bring them
  // down to the curves' actual deviation (at least the confusion tolerance).
  ShapeFix_ShapeTolerance().LimitTolerance(out.inner, kOffsetTolerance, kOffsetTolerance);
  BRepLib::SameParameter(out.inner, kOffsetTolerance, Standard_True);
  BRepLib::UpdateTolerances(out.inner, Standard_False);
  if (!is_valid(out.inner)) too_thick(thickness, "the inward offset is not a valid solid");
  const double inner_volume = shape_volume(out.inner);
  if (!(inner_volume > 0.0) || !(inner_volume < body.volume())) too_thick(thickness, "the inward offset is empty or inverted");
  // Every vertex of the offset must lie inside the body, at least the thickness away from its boundary.
  TopTools_IndexedMapOfShape vertices;
  TopExp::MapShapes(out.inner, TopAbs_VERTEX, vertices);
  for (int i = 1; i <= vertices.Extent(); ++i) {
    const gp_Pnt p = BRep_Tool::Pnt(TopoDS::Vertex(vertices(i)));
    const Vec3 q(p.X(), p.Y(), p.Z());
    if (!body.contains(q) || body.exact_distance(q) < thickness * (1.0 - kThicknessSlack) - kOffsetTolerance)
      too_thick(thickness, "the inward offset folds over itself");
  }
  TopoDS_Shell outer_shell;
  for (TopExp_Explorer x(body.solid(), TopAbs_SHELL); x.More(); x.Next()) outer_shell = TopoDS::Shell(x.Current());
  b.MakeSolid(out.skin);
  b.Add(out.skin, outer_shell);
  b.Add(out.skin, inner_shell.Reversed());
  progress.finish();
  return out;
}

}  // namespace steady
