#pragma once
// The lattice and the skin as two parts (a STEP assembly): pieces of the trimmed lattice that hold no hub built
// whole go to the skin. Trimming the lattice to the skin's inner wall cuts a few beams and hubs whose nodes lie in
// the wall: their ends inside are pieces that touch only the skin (the main job: 16 of 0.004 to 0.08 mm^3 beside a
// lattice of 6,120 mm^3). In the skin part they are what they are in the united part, some of the wall.
#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <string>
#include <unordered_set>

#include "steady/core/progress.hpp"

namespace steady::trim {

struct PartsApart {
  TopoDS_Shape lattice;  // the solids holding at least one hub built whole
  TopoDS_Shape skin;     // the skin, glued to the pieces (one solid when the glued Fuse checks out)
  std::int64_t pieces = 0;
  double pieces_volume = 0.0;
  std::string unfused_reason;  // empty, or why the skin part is the skin and the pieces side by side
};

// Whether `solid` holds a hub the trim built whole (inside the inner wall): one of its faces is one of theirs (by
// TShape, `whole_hub_faces`).
bool holds_a_whole_hub(const TopoDS_Shape& solid, const std::unordered_set<const void*>& whole_hub_faces);

// Splits `lattice` (trimmed to the skin's inner wall) into the solids that hold a hub built whole (one of their
// faces is in `whole_hub_faces`, by TShape) and the pieces that hold none; the pieces are fused to `skin` with a
// glued Fuse (they share faces on the inner wall), checked: valid, as many solids as the skin had, volume the sum to 1e-6. Should the Fuse fail that check, the
// skin part is the skin and the pieces side by side (valid solids sharing faces; the assembly is as right, only
// not merged), and `unfused_reason` says why.
PartsApart give_loose_pieces_to_skin(const TopoDS_Shape& lattice, const TopoDS_Shape& skin,
                                     const std::unordered_set<const void*>& whole_hub_faces, Progress& progress);

}  // namespace steady::trim
