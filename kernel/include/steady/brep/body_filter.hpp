#pragma once
// Keep the nodes inside a B-rep body (the brep family: it reads the body with OpenCASCADE).
#include <string>

#include "steady/query/filters.hpp"

namespace steady {

// A body as B-rep text (OpenCASCADE's BRepTools format, what FreeCAD's exportBrepToString writes). It
// must hold at least one closed, valid solid; InvalidInput naming `field` otherwise.
FilterPtr inside_brep(const std::string& brep_text, const std::string& field = "body");

}  // namespace steady
