#pragma once
// The (u, v) curve of a circle arc on a spherical face, as a B-spline approximating the exact (transcendental)
// longitude/latitude of the circle to a given tolerance, with the circle's own parameter (so the edge is
// SameParameter with its 3D circle). Computed once per distinct hub shape; invariant under similarities.
#include <Geom2d_BSplineCurve.hxx>

#include "brep/sphere_layout.hpp"

namespace steady {

// (u, v) accuracy of the approximations, in radians. On a sphere of radius R the 3D deviation is at most
// R times this: 1e-7 model units (OpenCASCADE's confusion tolerance) for R = 100, and a volume error far below
// the 1e-7 relative the tests demand.
constexpr double kSpherePcurveTolerance = 1e-9;

struct ArcPcurve {
  Handle(Geom2d_BSplineCurve) curve;
  double max_error = 0.0;  // (u, v) distance to the exact curve, as measured by the approximation
};

ArcPcurve approximate_arc_pcurve(const SphereLayout& layout, int circle, const CircleArc& arc,
                                 double tolerance = kSpherePcurveTolerance);

}  // namespace steady
