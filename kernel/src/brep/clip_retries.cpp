#include "brep/clip_retries.hpp"

#include <gp_Ax1.hxx>
#include <gp_Dir.hxx>
#include <gp_Trsf.hxx>

namespace steady {

const std::vector<ClipAttempt>& clip_retries() {
  static const std::vector<ClipAttempt> attempts = [] {
    std::vector<ClipAttempt> a;
    for (const double fuzzy : {0.0, 1e-4, 1e-3}) {
      for (int frame = 0; frame < 3; ++frame)
        for (int layout = 0; layout < 2; ++layout) a.push_back({layout, frame, fuzzy});
      if (fuzzy == 0.0)
        for (int layout = 0; layout < 2; ++layout) a.push_back({layout, 0, 0.0, true});
    }
    return a;
  }();
  return attempts;
}

TopLoc_Location turned_frame(int k, const gp_Pnt& center) {
  if (k == 0) return TopLoc_Location();
  // Turns of 0.37 k rad about a skew axis: any rotation that is not a symmetry of the lattice's grid would do.
  gp_Trsf turn;
  turn.SetRotation(gp_Ax1(center, gp_Dir(1.0, 0.5 * k, 2.0)), 0.37 * k);
  return TopLoc_Location(turn);
}

}  // namespace steady
