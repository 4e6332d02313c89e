#include "properties/checked_fuse.hpp"

#include <BRepAlgoAPI_Fuse.hxx>
#include <TopTools_ListOfShape.hxx>

#include <stdexcept>

namespace steady {

namespace {

// Fuzzy values of the retries, relative to the pieces' extent: the B-rep's group Fuse's (an exact Fuse first,
// since a fuzzy one leaves edges with tolerances of its size, and the smaller value before the larger).
constexpr double kFuzzyRetries[] = {0.0, 1e-7, 1e-6};

// One Fuse of `args` with `tools`; empty when OpenCASCADE reports a failure.
TopoDS_Shape fuse_once(const TopoDS_Shape& first, const std::vector<TopoDS_Shape>& rest, double fuzzy) {
  TopTools_ListOfShape args, tools;
  args.Append(first);
  for (const TopoDS_Shape& s : rest) tools.Append(s);
  BRepAlgoAPI_Fuse fuse;
  fuse.SetArguments(args);
  fuse.SetTools(tools);
  fuse.SetRunParallel(Standard_False);  // clusters already run in parallel
  if (fuzzy > 0.0) fuse.SetFuzzyValue(fuzzy);
  fuse.Build();
  if (!fuse.IsDone() || fuse.HasErrors()) return TopoDS_Shape();
  return fuse.Shape();
}

TopoDS_Shape fuse_pieces(const std::vector<TopoDS_Shape>& pieces, double fuzzy, bool one_by_one) {
  if (!one_by_one) return fuse_once(pieces.front(), {pieces.begin() + 1, pieces.end()}, fuzzy);
  TopoDS_Shape sum = pieces.front();
  for (std::size_t i = 1; i < pieces.size() && !sum.IsNull(); ++i) sum = fuse_once(sum, {pieces[i]}, fuzzy);
  return sum;
}

}  // namespace

TopoDS_Shape checked_fuse(const std::vector<TopoDS_Shape>& pieces, double size, const FuseCheck& check,
                          const std::string& what) {
  if (pieces.empty()) throw std::invalid_argument("checked_fuse: no pieces to fuse");
  if (pieces.size() == 1) {
    const std::string refusal = check(pieces.front());
    if (!refusal.empty()) throw std::runtime_error("hub union: " + refusal);
    return pieces.front();
  }
  std::string first_refusal;
  for (double fuzzy : kFuzzyRetries)
    for (bool one_by_one : {false, true}) {
      if (one_by_one && pieces.size() == 2) continue;  // the same Fuse as all at once
      const TopoDS_Shape result = fuse_pieces(pieces, fuzzy * size, one_by_one);
      const std::string refusal =
          result.IsNull() ? "OpenCASCADE's Fuse of " + what + " failed" : check(result);
      if (refusal.empty()) return result;
      if (first_refusal.empty()) first_refusal = refusal;
    }
  throw std::runtime_error("hub union: " + first_refusal + " (and every retry: one by one, fuzzy values 1e-7 and "
                           "1e-6, failed too)");
}

}  // namespace steady
