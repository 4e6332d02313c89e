#pragma once
// The skin of a body: the shell of wall thickness t between the body's boundary and its inward offset by t.
// Built as one solid with the body's boundary as outer shell and the offset boundary (reversed) as a void, so
// no Boolean is needed; the inner solid (the offset body) is where the lattice goes.
#include <TopoDS_Solid.hxx>

#include "steady/core/progress.hpp"
#include "steady/brep/solid_body.hpp"

namespace steady {

struct Skin {
  TopoDS_Solid skin;   // body minus inner: a solid with one void
  TopoDS_Solid inner;  // the inward offset of the body by the thickness
  double thickness = 0.0;
};

// Throws InvalidInput naming "skin" for a negative or non-finite thickness, and when the body cannot hold a
// wall that thick (the inward offset is empty, inverted, or comes closer than the thickness to the boundary);
// Cancelled when the progress is cancelled (OpenCASCADE's offset stops at its next check).
Skin make_skin(const SolidBody& body, double thickness, Progress& progress = no_progress());

}  // namespace steady
