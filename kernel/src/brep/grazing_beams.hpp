#pragma once
// The lattice and the skin as two parts (a STEP assembly): a beam whose axis runs outside the skin's inner wall
// but whose cone dips through it leaves a lens in the trimmed lattice, thin between the cone and the wall and
// sharp at its ends. A mesher cannot resolve it: in the main job four such lenses, 0.037 mm thick over 3 mm of a
// beam nearly tangent to the wall, made gmsh fail on the assembly (docs/fea.md). Such a beam belongs to the skin, as
// its axis does: the lattice is split along the beam's frustum between its two exit planes, and what lies inside
// is a piece holding no hub built whole, which give_loose_pieces_to_skin gives to the skin. The interface is then
// the exit disk, square to the wall, and in the skin the cone continues the wall, as in the united part.
#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <string>
#include <unordered_set>
#include <vector>

#include "steady/brep/solid_body.hpp"
#include "steady/core/progress.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/flat_lattice.hpp"

namespace steady::trim {

// Beams whose axis, between the two exit planes, lies outside `inner` (farther than its confusion from it) while
// the cone around it comes within reach of it, and whose stumps meet no other stump of their hubs outside the
// balls (so that the frustum holds that beam alone). Those that do not in fact dip into `inner` split nothing.
std::vector<std::int64_t> grazing_beams(const FlatLattice& f, const std::vector<BeamFrustum>& frustums,
                                        const SolidBody& inner, Progress& progress);

struct GrazingSplit {
  TopoDS_Shape lattice;     // the lattice with those beams' lenses as solids of their own, or as given
  std::int64_t pieces = 0;  // solids split off (each holding no hub built whole)
  std::string kept_reason;  // why the lattice was kept as given (the split failed its checks), or empty
};

// Splits `lattice` (solids, trimmed to the skin's inner wall) along the frustums of `beams`. Checked: valid; the
// same volume (the faces the split made enclose what those it replaced did, to 1e-7 of their size); as many solids
// holding a hub built whole (a face in `whole_hub_faces`) as before; every piece split off within a frustum's box.
// Otherwise the lattice is kept as given and `kept_reason` says why.
GrazingSplit split_off_grazing_beams(const TopoDS_Shape& lattice, const std::vector<BeamFrustum>& frustums,
                                     const std::vector<std::int64_t>& beams,
                                     const std::unordered_set<const void*>& whole_hub_faces, Progress& progress);

}  // namespace steady::trim
