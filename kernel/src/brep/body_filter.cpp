// The B-rep body filter: nodes whose centers lie inside a solid read from BREP text (OpenCASCADE).
#include "steady/brep/body_filter.hpp"

#include <BRepCheck_Analyzer.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRep_Tool.hxx>
#include <Precision.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Solid.hxx>
#include <tbb/enumerable_thread_specific.h>

#include <memory>

#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"

namespace steady {
namespace {

// A B-rep body: its solids, classified with one BRepClass3d_SolidClassifier per thread and solid (the
// classifier keeps per-query state and is not shared between threads).
class InsideBrep : public NodeFilter {
 public:
  explicit InsideBrep(std::vector<TopoDS_Solid> solids) : solids_(std::move(solids)) {}
  void evaluate(const Lattice&, const NodeId*, const Ball* balls, std::size_t n, std::uint8_t* keep) const override {
    auto& classifiers = local_.local();
    if (classifiers.empty())
      for (const TopoDS_Solid& s : solids_) classifiers.push_back(std::make_unique<BRepClass3d_SolidClassifier>(s));
    for (std::size_t q = 0; q < n; ++q) {
      const gp_Pnt p(balls[q].center.x, balls[q].center.y, balls[q].center.z);
      keep[q] = 0;
      for (auto& c : classifiers) {
        c->Perform(p, Precision::Confusion());
        const TopAbs_State st = c->State();
        if (st == TopAbs_IN || st == TopAbs_ON) {
          keep[q] = 1;
          break;
        }
      }
    }
  }
  std::string describe() const override { return "inside a B-rep body (" + std::to_string(solids_.size()) + " solids)"; }

 private:
  std::vector<TopoDS_Solid> solids_;
  mutable tbb::enumerable_thread_specific<std::vector<std::unique_ptr<BRepClass3d_SolidClassifier>>> local_;
};

}  // namespace

FilterPtr inside_brep(const std::string& brep_text, const std::string& field) {
  const TopoDS_Shape shape = read_body_brep(brep_text, field, [&](const TopoDS_Shape& read) {
    if (!TopExp_Explorer(read, TopAbs_SOLID).More()) fail_input(field, "is not a solid (the shape holds no solid)");
    // Several solids are their union (a node inside any is kept). A face outside every solid (a loose face or open
    // shell beside them) bounds no volume, and would be ignored without a word: refused.
    TopTools_IndexedMapOfShape faces, solid_faces;
    TopExp::MapShapes(read, TopAbs_FACE, faces);
    for (TopExp_Explorer x(read, TopAbs_SOLID); x.More(); x.Next()) TopExp::MapShapes(x.Current(), TopAbs_FACE, solid_faces);
    if (faces.Extent() > solid_faces.Extent())
      fail_input(field, "holds " + std::to_string(faces.Extent() - solid_faces.Extent()) +
                            " faces outside its solids (a loose face or open shell bounds no volume): give solids only");
    if (!BRepCheck_Analyzer(read, Standard_True, Standard_False).IsValid())
      fail_input(field, "is not a valid solid (BRepCheck_Analyzer)");
    for (TopExp_Explorer s(read, TopAbs_SOLID); s.More(); s.Next())
      for (TopExp_Explorer x(s.Current(), TopAbs_SHELL); x.More(); x.Next())
        if (!BRep_Tool::IsClosed(x.Current())) fail_input(field, "is not a closed solid (a shell is open)");
  });
  std::vector<TopoDS_Solid> solids;
  for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next()) solids.push_back(TopoDS::Solid(x.Current()));
  return std::make_shared<InsideBrep>(std::move(solids));
}

}  // namespace steady
