#pragma once
// STEP assemblies through OpenCASCADE's XCAF: named, coloured parts under one named assembly, as CAD systems
// (FreeCAD, and OpenCASCADE's own STEP reader) read them back.
#include <TopoDS_Shape.hxx>
#include <gp_Trsf.hxx>

#include <array>
#include <string>
#include <vector>

#include "steady/core/output_file.hpp"  // check_output_path
#include "steady/core/progress.hpp"

namespace steady {

struct StepPart {
  std::string name;
  TopoDS_Shape shape;
  std::array<double, 3> color{0.8, 0.8, 0.8};  // RGB in [0, 1]
  bool has_color = true;
  // Where copies of the part go: empty for one copy as it is; otherwise one component per placement, all of one
  // product (a family of connectors, a length of rod), which readers give back as placed copies of one shape.
  std::vector<gp_Trsf> instances;
};

constexpr std::size_t kMaxStepNameLength = 255;

// Throws InvalidInput naming `field` unless a STEP reader gives `name` back as written: not empty (readers put
// their translator's name there), no NUL, at most kMaxStepNameLength characters (OpenCASCADE's reader refuses a
// file holding a name of 100,000 characters).
void check_step_name(const std::string& name, const char* field);

// Writes the parts as components of one assembly. Throws InvalidInput naming "path" when the file cannot be
// written (a failed write leaves no partial file), "parts" when there is nothing to write. Cancelled while the
// shapes are translated leaves the file
// untouched (it is written only after; the writing itself runs to its end).
void write_step_assembly(const std::string& path, const std::vector<StepPart>& parts,
                         const std::string& assembly_name = "LatticePart", Progress& progress = no_progress());

// Reads a STEP file back: the leaf parts with their names, colours and shapes (placed). The file is read and
// checked in a reader process of its own (read_body_brep in brep_io.hpp says why): a file that crashes
// OpenCASCADE's reader is an InvalidInput naming "path", and a cancel of the current progress stops the read.
std::vector<StepPart> read_step_parts(const std::string& path);

}  // namespace steady
