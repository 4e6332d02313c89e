#pragma once
// Shells written with their faces in connected order. OpenCASCADE's STEP reader orients every shell it reads
// (ShapeFix_Shell::FixFaceOrientation): it grows the shell one face at a time, and after each face it scans the
// remaining faces again from the first until one shares an open edge with the shell so far. Faces in an arbitrary
// order make that quadratic in the faces (a 100,000-beam part did not read back in half an hour of CPU); in an
// order where every face shares an edge with one before it, the first face of each scan fits and reading is
// linear. FreeCAD, gmsh and other tools built on OpenCASCADE read STEP that way.
#include <TopoDS_Shape.hxx>

namespace steady {

// The same shape (faces, edges and vertices shared as before, same orientations and locations) whose shells list
// their faces breadth first through shared edges from the shell's first face; faces not reached that way (a
// shell in several pieces) follow in the same order, piece after piece.
TopoDS_Shape with_faces_in_connected_order(const TopoDS_Shape& shape);

}  // namespace steady
