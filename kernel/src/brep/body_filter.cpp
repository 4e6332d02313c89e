// The B-rep body filter: nodes whose centers lie inside a solid read from BREP text (OpenCASCADE).
#include "steady/brep/body_filter.hpp"

#include <BRepCheck_Analyzer.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Solid.hxx>
#include <tbb/enumerable_thread_specific.h>

#include <memory>
#include <sstream>

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
  TopoDS_Shape shape;
  try {
    std::istringstream in(brep_text);
    BRep_Builder builder;
    BRepTools::Read(shape, in, builder);
  } catch (const Standard_Failure& e) {
    fail_input(field, std::string("is not readable B-rep text: ") + e.GetMessageString());
  }
  if (shape.IsNull()) fail_input(field, "is not readable B-rep text (OpenCASCADE read nothing)");
  std::vector<TopoDS_Solid> solids;
  for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next()) solids.push_back(TopoDS::Solid(x.Current()));
  if (solids.empty()) fail_input(field, "is not a solid (the shape holds no solid)");
  if (!BRepCheck_Analyzer(shape).IsValid()) fail_input(field, "is not a valid solid (BRepCheck_Analyzer)");
  for (const TopoDS_Solid& s : solids)
    for (TopExp_Explorer x(s, TopAbs_SHELL); x.More(); x.Next())
      if (!BRep_Tool::IsClosed(x.Current())) fail_input(field, "is not a closed solid (a shell is open)");
  return std::make_shared<InsideBrep>(std::move(solids));
}

}  // namespace steady
