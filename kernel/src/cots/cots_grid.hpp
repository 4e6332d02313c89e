#pragma once
// The grid of tiles both curved-lattice maps (COTS in the plane, BeCOTS on a cone) share: its check and the tiles
// holding pre-images.
#include <array>
#include <vector>

#include "steady/cots/cots_map.hpp"

namespace steady {

// InvalidInput naming nu or nv when the grid is empty.
void require_grid(int nu, int nv);

// The tiles (i, j) of an nu x nv grid that hold each pre-image in [0,1]^2 (one per pre-image, in their order).
std::vector<std::array<int, 2>> tiles_of_preimages(const std::vector<CotsPreimage>& preimages, int nu, int nv);

}  // namespace steady
