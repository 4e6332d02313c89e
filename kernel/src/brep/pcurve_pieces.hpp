#pragma once
// Each edge carries its own piece of a B-spline (u, v) curve, not the curve of a longer arc it was cut from.
// A STEP file stores an edge's pcurve without its range; a reader finds the range by projecting the edge's
// vertices onto the curve. When the longer curve is a whole circle on a sphere, its two ends are one point, the
// projection can take the wrong end, and OpenCASCADE's reader then drops the pcurve and rebuilds it by projection
// (cubic, up to 1e-2 off; the main job's lattice volume came back 1.7e-6 off). Each edge's own piece is also all a
// file needs to store.
#include <Geom2d_BSplineCurve.hxx>
#include <TopoDS_Shape.hxx>

namespace steady {

// The part of `curve` on [t0, t1], with the same parameter: `curve` itself when the range spans it.
Handle(Geom2d_BSplineCurve) edge_pcurve(const Handle(Geom2d_BSplineCurve)& curve, double t0, double t1);

// Replaces, on every edge of the faces of `shape`, a B-spline pcurve longer than the edge's range by the edge's
// own piece (the same points: the geometry does not change). For faces made by OpenCASCADE's Booleans (the Fuse of
// a crowded hub's core, the trim's clipped hubs), which keep the parent's pcurve on each piece of a split edge.
// Returns how many pcurves were replaced.
int give_edges_their_own_pcurves(const TopoDS_Shape& shape);

}  // namespace steady
