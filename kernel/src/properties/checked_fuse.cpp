#include "properties/checked_fuse.hpp"

#include <BRepAlgoAPI_Fuse.hxx>
#include <TopTools_ListOfShape.hxx>

#include <algorithm>
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

// How the pieces are fused: all in one Fuse, or one by one (each added to the union of those before it) in their
// order or the reverse one.
enum class FuseOrder { AllAtOnce, OneByOne, OneByOneReversed };

TopoDS_Shape fuse_pieces(std::vector<TopoDS_Shape> pieces, double fuzzy, FuseOrder order) {
  if (order == FuseOrder::AllAtOnce) return fuse_once(pieces.front(), {pieces.begin() + 1, pieces.end()}, fuzzy);
  if (order == FuseOrder::OneByOneReversed) std::reverse(pieces.begin(), pieces.end());
  TopoDS_Shape sum = pieces.front();
  for (std::size_t i = 1; i < pieces.size() && !sum.IsNull(); ++i) sum = fuse_once(sum, {pieces[i]}, fuzzy);
  return sum;
}

}  // namespace

TopoDS_Shape checked_fuse(const std::vector<TopoDS_Shape>& pieces, double size, const FuseCheck& check,
                          const std::string& what, bool fuzzy_retries) {
  if (pieces.empty()) throw std::invalid_argument("checked_fuse: no pieces to fuse");
  if (pieces.size() == 1) {
    const std::string refusal = check(pieces.front());
    if (!refusal.empty()) throw std::runtime_error("hub union: " + refusal);
    return pieces.front();
  }
  std::string first_refusal;
  for (double fuzzy : kFuzzyRetries)
    for (FuseOrder order : {FuseOrder::AllAtOnce, FuseOrder::OneByOne, FuseOrder::OneByOneReversed}) {
      if (fuzzy > 0.0 && !fuzzy_retries) break;
      if (order != FuseOrder::AllAtOnce && pieces.size() == 2) continue;  // the same Fuse as all at once
      const TopoDS_Shape result = fuse_pieces(pieces, fuzzy * size, order);
      const std::string refusal =
          result.IsNull() ? "OpenCASCADE's Fuse of " + what + " failed" : check(result);
      if (refusal.empty()) return result;
      if (first_refusal.empty()) first_refusal = refusal;
    }
  throw std::runtime_error("hub union: " + first_refusal + " (and every retry: one by one in either order" +
                           std::string(fuzzy_retries ? ", fuzzy values 1e-7 and 1e-6," : ",") + " failed too)");
}

}  // namespace steady
