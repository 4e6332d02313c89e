#pragma once
// The lattice file format: versioned JSON holding a whole lattice definition (docs/lattice-format.md).
// Saving then loading reproduces the definition bit for bit (similarities are saved by their generator,
// doubles in shortest round-trip form). Loading refuses a malformed or inconsistent file with an
// InvalidInput whose message names the field ("beams[2].to: node 5 does not exist ...").
#include <string>

#include "steady/lattice/lattice.hpp"

namespace steady {

// Version 2 holds the layout in its own section; version 1 files (a steady brick's U, V, W and placement at
// the top level) still load.
constexpr int kLatticeFormatVersion = 2;
constexpr const char* kLatticeFormatName = "steady-lattice";

// Spaces per level of indentation (-1: one line). Beyond kMaxJsonIndent the file only grows.
constexpr int kMaxJsonIndent = 64;
std::string lattice_to_json(const Lattice& lattice, int indent = 2);
Lattice lattice_from_json(const std::string& text);

// A similarity alone, in the same JSON form as inside a lattice file.
std::string similarity_to_json(const Similarity& s);
Similarity similarity_from_json(const std::string& text);

}  // namespace steady
