#pragma once
// Keep the nodes inside a B-rep body (the brep family: it reads the body with OpenCASCADE).
#include <string>

#include "steady/query/filters.hpp"

namespace steady {

// A body as B-rep text (OpenCASCADE's BRepTools format, what FreeCAD's exportBrepToString writes). It
// must hold at least one closed, valid solid, and no face outside its solids; InvalidInput naming `field`
// otherwise. Several solids (a compound, a compsolid) are their union: a node inside any of them is kept.
FilterPtr inside_brep(const std::string& brep_text, const std::string& field = "body");

}  // namespace steady
