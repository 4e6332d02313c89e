#pragma once
// The (u, v) curve of a circle arc on a spherical face, as a B-spline approximating the exact (transcendental)
// longitude/latitude of the circle to a given tolerance, with the circle's own parameter (so the edge is
// SameParameter with its 3D circle). Computed once per distinct hub shape; invariant under similarities.
#include <Geom2d_BSplineCurve.hxx>

#include "brep/sphere_layout.hpp"

namespace steady {

// Accuracy of the approximations in model units: a tenth of the edges' tolerance (1e-7). On a sphere of radius R
// a (u, v) error e is at most R e away in 3D, so the (u, v) tolerance is this over the largest radius the curves
// are placed on, within the bounds below. A finer one only made the files larger (issue 14: at 1e-9 radians on
// the main job's balls of radius 0.55, 5.5e-10 in 3D, its STEP was 1.5 % larger than at 1e-8).
constexpr double kSpherePcurve3dTolerance = 1e-8;
constexpr double kFinestSpherePcurveTolerance = 1e-11, kCoarsestSpherePcurveTolerance = 1e-6;  // radians
constexpr double kSpherePcurveTolerance = 1e-9;  // radians, where no radius is known (right for radii up to 10)
double sphere_pcurve_tolerance(double largest_radius);

struct ArcPcurve {
  Handle(Geom2d_BSplineCurve) curve;
  double max_error = 0.0;  // (u, v) distance to the exact curve, as measured by the approximation
};

// `tolerance` in radians: sphere_pcurve_tolerance of the largest radius the arc is placed on.
ArcPcurve approximate_arc_pcurve(const SphereLayout& layout, int circle, const CircleArc& arc, double tolerance);

}  // namespace steady
