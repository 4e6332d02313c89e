#pragma once
// B-rep utilities shared by the kernel, the module, tests and benchmarks: BREP text in and out, validity
// (BRepCheck_Analyzer) with a readable report, volume (BRepGProp) and element counts.
#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <functional>
#include <string>

#include "steady/core/progress.hpp"

namespace steady {

// OpenCASCADE's BREP text (what FreeCAD's Part.Shape.exportBrepToString gives and importBrep reads). Cancelled
// when the progress is cancelled.
std::string brep_to_text(const TopoDS_Shape& shape, Progress& progress = no_progress());
// Reads BREP text in this process; throws InvalidInput naming `field` when the text does not parse or holds no
// shape. For text OpenCASCADE wrote (the kernel's own copies); a body from outside goes through read_body_brep.
TopoDS_Shape brep_from_text(const std::string& text, const std::string& field);
// Reads the BREP text of a body from outside (a user's file, FreeCAD) in a reader process of its own
// (brep/child_reader.hpp): brep_from_text, OpenCASCADE's checker and `check` (more refusals, InvalidInput) run
// there, so a crash of the reader or checker on a corrupt text is an InvalidInput naming `field`, and a cancel of
// the current progress (Ctrl-C) stops it within 0.1 s.
TopoDS_Shape read_body_brep(const std::string& text, const std::string& field,
                            const std::function<void(const TopoDS_Shape&)>& check = {});
// Throws InvalidInput naming `field` when a face has no surface, an edge (not degenerated) no 3D curve, a curve or
// point representation misses the curve, surface or polygon it names, or a vertex has no finite point.
// OpenCASCADE's readers (BREP and STEP) leave such holes where a record does not parse, and say nothing; its
// checker (BRepCheck) and algorithms then dereference them and crash (found by tests/fuzz, docs/reliability.md).
void require_complete_geometry(const TopoDS_Shape& shape, const std::string& field);

bool is_valid(const TopoDS_Shape& shape);
// Empty when valid; otherwise the faulty sub-shapes (type and index) with their BRepCheck statuses, at most
// `max_lines` lines.
std::string validity_report(const TopoDS_Shape& shape, int max_lines = 20);

// Volume by boundary_volume (boundary_volume.hpp: each face's share by Green's theorem on its (u, v) domain, to
// about 1e-12). OpenCASCADE's default Gauss rule, which FreeCAD's Shape.Volume uses, is off by 1.3e-3 on the main
// job's part (sphere faces with 12 holes: 12,898.0 against 12,881.0 mm^3); its adaptive rule, which this used
// before, by up to 9e-6 on parts trimmed by a skin's inner wall (the main job: 5e-9).
double shape_volume(const TopoDS_Shape& shape);
std::int64_t count_subshapes(const TopoDS_Shape& shape, int type);  // type: a TopAbs_ShapeEnum value
std::int64_t face_count(const TopoDS_Shape& shape);
std::int64_t solid_count(const TopoDS_Shape& shape);
// The largest tolerance of the shape's edges: how far apart its curves may be (the builder's own edges: 1e-7;
// intersection curves of OpenCASCADE's Booleans up to 2e-3 on some trims, docs/brep.md), 0 without edges.
double max_edge_tolerance(const TopoDS_Shape& shape);

}  // namespace steady
