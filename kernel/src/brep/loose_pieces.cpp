#include "brep/loose_pieces.hpp"

#include <BRepAlgoAPI_Fuse.hxx>
#include <TopExp_Explorer.hxx>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>
#include <unordered_set>
#include <vector>

#include "brep/trim_phases.hpp"
#include "steady/brep/brep_io.hpp"

namespace steady::trim {

namespace {

std::vector<TopoDS_Shape> solids_of(const TopoDS_Shape& shape) {
  std::vector<TopoDS_Shape> out;
  for (TopExp_Explorer e(shape, TopAbs_SOLID); e.More(); e.Next()) out.push_back(e.Current());
  return out;
}

// The skin fused with the pieces (glued: they meet on faces of its inner wall), checked; where that check fails,
// the skin and the pieces side by side in one compound (valid solids sharing faces), and why in `reason`.
TopoDS_Shape glued_to_skin(const TopoDS_Shape& skin, const std::vector<TopoDS_Shape>& pieces, double pieces_volume,
                           Progress& progress, std::string& reason) {
  std::vector<TopoDS_Shape> side_by_side = {skin};
  side_by_side.insert(side_by_side.end(), pieces.begin(), pieces.end());
  TopoDS_Shape merged;
  try {
    BRepAlgoAPI_Fuse op;
    op.SetGlue(BOPAlgo_GlueShift);
    merged = run_boolean(op, text_copy(skin), text_copy(compound_of(pieces)),
                         "glued Fuse of the skin and the loose pieces", progress);
  } catch (const Cancelled&) {
    throw;
  } catch (const std::runtime_error& e) {
    reason = e.what();
    return compound_of(side_by_side);
  }
  const double expected = shape_volume(skin) + pieces_volume, got = shape_volume(merged);
  const std::size_t solids = solids_of(merged).size(), wanted = solids_of(skin).size();
  const bool valid = is_valid(merged);
  if (solids == wanted && valid && std::abs(got - expected) <= 1e-6 * expected) return merged;
  std::ostringstream os;
  os << "the glued Fuse of the skin and " << pieces.size() << " loose pieces gave " << solids
     << " solid(s) of volume " << got << " where " << wanted << " of " << expected << " were due"
     << (valid ? "" : ", invalid");
  reason = os.str();
  return compound_of(side_by_side);
}

}  // namespace

// Deciding it from the geometry instead (a ball's centre classified in the solid, its distance to the faces) took
// 40 s on the main job's lattice (3,759 faces); this takes milliseconds.
bool holds_a_whole_hub(const TopoDS_Shape& solid, const std::unordered_set<const void*>& whole_hub_faces) {
  for (TopExp_Explorer e(solid, TopAbs_FACE); e.More(); e.Next())
    if (whole_hub_faces.count(e.Current().TShape().get())) return true;
  return false;
}

PartsApart give_loose_pieces_to_skin(const TopoDS_Shape& lattice, const TopoDS_Shape& skin,
                                     const std::unordered_set<const void*>& whole_hub_faces, Progress& progress) {
  PartsApart out;
  out.lattice = lattice;
  out.skin = skin;
  const std::vector<TopoDS_Shape> solids = solids_of(lattice);
  if (solids.size() < 2) return out;
  std::vector<TopoDS_Shape> kept, pieces;
  std::vector<double> piece_volumes;
  for (const TopoDS_Shape& solid : solids) {
    progress.check();
    if (holds_a_whole_hub(solid, whole_hub_faces)) {
      kept.push_back(solid);
    } else {
      pieces.push_back(solid);
      piece_volumes.push_back(shape_volume(solid));
    }
  }
  if (kept.empty()) {  // no hub lies whole inside the inner wall (a lattice as thin as the skin): the largest stays
    const std::size_t largest = std::max_element(piece_volumes.begin(), piece_volumes.end()) - piece_volumes.begin();
    kept.push_back(pieces[largest]);
    pieces.erase(pieces.begin() + largest);
    piece_volumes.erase(piece_volumes.begin() + largest);
  }
  for (const double v : piece_volumes) out.pieces_volume += v;
  if (pieces.empty()) return out;
  out.skin = glued_to_skin(skin, pieces, out.pieces_volume, progress, out.unfused_reason);
  out.lattice = kept.size() == 1 ? kept[0] : compound_of(kept);
  out.pieces = static_cast<std::int64_t>(pieces.size());
  return out;
}

}  // namespace steady::trim
