#pragma once
// Cusps: vertices where two edges of one face leave in the same direction. Exit caps exactly tangent (an octet's
// 60 degree neighbours at beam/node 0.5, under any steady step: similarities keep angles) meet so: the sphere
// face's loop touches itself at the tangency point, four arcs tangent there, and the conics between the two cones
// leave that point along the exit circles.
//
// Near a cusp the two edges' pcurves stay closer than BRepCheck_Wire's intersection tolerance (1e-10 in (u, v))
// over a stretch of about sqrt(2e-10 / curvature); the checker accepts such an overlap only when an end of it lies
// within the common vertex's tolerance. With a vertex of 1e-7 the verdict then depends on how the intersector cuts
// the stretch into segments, which a change of 1e-15 in the curves (the 15 digits of the BREP text) flips: a core
// valid in memory came back with a self-intersecting sphere wire (docs/brep.md, section 6). A vertex tolerance
// that covers the stretch where the edges are indistinguishable says what the geometry is, and holds either way.
#include <TopoDS_Shape.hxx>

namespace steady {

// Raises the tolerance of each cusp vertex of the faces of `shape` to the distance from the vertex at which its two
// edges' pcurves have parted by kCuspSeparation (see the .cpp). Returns how many vertices were raised.
int widen_cusp_vertices(const TopoDS_Shape& shape);

}  // namespace steady
