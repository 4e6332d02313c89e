#pragma once
// Shapes in an order that depends on their geometry only. Some OpenCASCADE algorithms (BRepOffset's inward offset
// of the skin) return their faces and edges in an order that follows memory addresses (maps keyed by the
// sub-shapes' pointers), so the same input gave a different face order from run to run, then different splits in
// the Booleans that follow and different bytes in the written BREP and STEP (issue 16, item 5). Putting such a
// result in canonical order makes everything after it repeatable.
#include <TopoDS_Shell.hxx>

namespace steady {

// The same shell (its faces, edges and vertices shared as before) with its faces sorted by surface type, centre
// of mass and area, each face's wires by the same keys of their edges, and each wire's edges rotated to start at
// the edge whose midpoint comes first. Faces whose keys tie (to 1e-9 of the shell's size) keep their order.
TopoDS_Shell in_canonical_order(const TopoDS_Shell& shell);

}  // namespace steady
