#pragma once
// OpenCASCADE's Fuse of the pieces the exact union measures (a hub's ball and frustums, a cluster's hubs), tried
// in several ways until one result passes the caller's checks. The B-rep's group Fuse's strategy (brep/hub_group.cpp,
// fuse_members and its kFuzzyRetries) plus a reversed order, written again here because the properties family
// cannot use the brep family (which links it); the two should become one helper of the properties family.
#include <TopoDS_Shape.hxx>

#include <functional>
#include <string>
#include <vector>

namespace steady {

// Why a Fuse's result is refused ("" when it is accepted).
using FuseCheck = std::function<std::string(const TopoDS_Shape&)>;

// The pieces fused for each fuzzy value (exact first, then 1e-7 and 1e-6 of `size`, the pieces' extent): all at
// once, then one by one (each added to the union of those before it), then one by one from the last piece (a hub's
// ball last: the only order that fused a bent FCC hull-model hub whole). Returns the first result `check` accepts;
// throws std::runtime_error naming `what`, the attempts and the first refusal when none is accepted.
// Without `fuzzy_retries` only the exact Fuses are tried (with the fuzzy ones, the hubs of a tapered FCC whose beams
// are as thick as its balls kept properties() busy for over 100 s; without, it refuses in 17 s).
TopoDS_Shape checked_fuse(const std::vector<TopoDS_Shape>& pieces, double size, const FuseCheck& check,
                          const std::string& what, bool fuzzy_retries = true);

}  // namespace steady
