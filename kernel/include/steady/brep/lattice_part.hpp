#pragma once
// A lattice made into a CAD part: the untrimmed lattice, or the lattice trimmed into a body (given as BREP text)
// with a policy and an optional skin, as BREP text or as a STEP assembly. This is what the Python module and the
// FreeCAD feature LatticePart call.
#include <array>
#include <optional>
#include <string>

#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/core/progress.hpp"
#include "steady/brep/trim.hpp"

namespace steady {

struct LatticePartRequest {
  std::optional<std::string> body_brep;  // BREP text of the body; absent: the whole (clean) lattice
  TrimOptions trim;                      // policy, dangling beams, skin
};

// The part's solid as BREP text. InvalidInput for a skin without a body, and for everything trim_lattice and
// build_lattice_brep refuse; Cancelled soon after the progress is cancelled. `stats`: where given, how the trim
// went (all zero without a body).
std::string lattice_part_brep(const FlatLattice& lattice, const LatticePartRequest& request,
                              Progress& progress = no_progress(), TrimStats* stats = nullptr);

// What a lattice part's STEP file holds: the lattice and its skin as two parts that share the faces of the skin's
// inner wall (an assembly), or the part as one solid, the lattice united with its skin (named `lattice`): the
// part as it is printed, one material, and what a mesher for analysis takes in one piece (docs/fea.md).
enum class StepLayout { Assembly, OneSolid };

struct StepNames {
  StepLayout layout = StepLayout::Assembly;
  std::string assembly = "LatticePart";
  std::string lattice = "Lattice";
  std::string skin = "Skin";
  std::array<double, 3> lattice_color{0.85, 0.55, 0.20};
  std::array<double, 3> skin_color{0.55, 0.65, 0.80};
};

// Writes a STEP assembly: the lattice (trimmed to the inner offset when there is a skin) and the skin as two
// named, coloured parts (the lattice alone when there is no skin). Pieces of the trimmed lattice that hold no hub
// built whole go to the skin part (TrimStats::skin_pieces). With StepLayout::OneSolid, one part: the lattice
// united with its skin, the shape lattice_part_brep gives. Cancelled leaves the file untouched. `stats`: where
// given, how the trim went.
void write_lattice_step(const std::string& path, const FlatLattice& lattice, const LatticePartRequest& request,
                        const StepNames& names = {}, Progress& progress = no_progress(), TrimStats* stats = nullptr);

}  // namespace steady
