#pragma once
// Loose intersection edges of a Boolean, retraced onto the exact curve where their two faces meet.
//
// OpenCASCADE's Booleans approximate the curve where two quadrics meet (a ball on the skin's inner wall: a sphere
// and a cylinder) by a walking line, and keep the result with the error as the edge's tolerance: 1.5e-4 to 2e-3 on
// balls of radius 0.1, where the builder's own edges hold 1e-7. The 3D curve lies on one surface and its (u, v)
// curve on the other surface is as far off. A part holding such an edge is defined only to that tolerance (its
// volume differs from the same part made by another Boolean by about 1e-6), and a STEP reader, which gives every
// edge the file's tolerance, reads it with its curves apart. Both surfaces are known exactly, so the curve is too:
// points of the old curve are pulled onto both surfaces by Newton steps, and new 3D and (u, v) curves interpolate
// them, checked against both surfaces before they replace the old ones.
//
// The same walking lines make most of a part's file (issue 14: 48 % of the main job's STEP): 20 to 160 poles per
// curve, on every face along it. An edge that winds around a beam (a cylinder or cone) or a ball is a function of
// the angle around that axis, exactly: the point where the ruling (or meridian) at that angle meets the other
// surface. Every such B-spline edge, loose or not, is refitted with that angle as its parameter, its 3D and (u, v)
// curves one B-spline of degree up to 14 on one knot sequence, to 1e-8, where that takes fewer poles.
#include <TopoDS_Shape.hxx>

#include <cstdint>
#include <vector>

namespace steady {

struct RetracedEdges {
  std::int64_t loose = 0;      // edges above the threshold between faces of kinds the retrace knows; of those,
  std::int64_t retraced = 0;   //   given exact curves and the tolerance those hold
  std::int64_t refitted = 0;   // edges (loose or not) refitted around a beam's or ball's axis: 1e-8, fewer poles
  double loosest_before = 0.0, loosest_after = 0.0;  // the largest tolerance of those edges before and after
};

// Edges whose tolerance exceeds kLooseEdgeTolerance, or whose 3D curve is a B-spline, between a plane, sphere,
// cylinder or cone and another of these, are refitted around an axis where they wind around one (above); other
// loose ones get curves through points on both surfaces (to 1e-14; a line or conic keeps its 3D curve, which is
// exact, and gets new (u, v) curves) and the tolerance they hold (at least 1e-7), in place: the shapes may share such
// edges, and every shape holding one sees it retraced. An edge is left as it was when the surfaces meet nearly
// tangentially along it, a point of it lies within 1e-3 (cosine) of a sphere's pole, or the new curves do not hold
// half the old tolerance; and put back, with every retraced edge of the face, when a face along it that BRepCheck
// found valid before is invalid after. Vertices keep their tolerance, raised where the new curves need more: a
// vertex's tolerance also covers the other edges meeting there, on faces that no retraced edge bounds.
RetracedEdges retrace_intersection_edges(const std::vector<TopoDS_Shape>& shapes);

constexpr double kLooseEdgeTolerance = 2e-7;

}  // namespace steady
