#pragma once
// Connectors of a constant-radius lattice as exact B-reps (OpenCASCADE): one solid per family, built once in the
// family's template frame and placed at every member (lattice/connector_plan.hpp says what a connector is and
// why the members of a family are congruent), and the rods (cylinders of one radius) placed on the beams.
#include <TopoDS_Shape.hxx>
#include <gp_Trsf.hxx>

#include <vector>

#include "steady/core/progress.hpp"
#include "steady/lattice/connector_plan.hpp"

namespace steady {

struct ConnectorParts {
  ConnectorPlan plan;
  std::vector<TopoDS_Shape> templates;  // per family: one valid solid, its node at the origin
  std::vector<double> volumes;          // per family (adaptive integration, brep_io.hpp)
  std::vector<double> build_seconds;    // per family
};

// Ball(center, reach rho) ∩ ExtendedHub(sleeve rho) − ExtendedHub(hole rho) for the unit beam directions at a node,
// where ExtendedHub(s) is the ball of radius s rho at the center united with a cylinder of radius s rho along each
// direction (long enough to leave the ball: beams end beyond it, plan_connectors checks). Spheres and cylinders
// joined by OpenCASCADE's Booleans, built at a rod radius of 10 around the origin along the given directions and
// then scaled and moved. A result is kept when it is one valid solid whose volume agrees with 20,000 sampled
// points of the definition (6 sigma); otherwise the spheres' poles are turned, the cylinders fused one at a time,
// fuzzy values of 1e-7 and 1e-6 rod radii tried. InvalidInput naming "directions" (none given) or "connector"
// (every try failed).
TopoDS_Shape connector_solid(const Vec3& center, const std::vector<Vec3>& directions,
                             const ConnectorParameters& parameters);

// A rod: the cylinder of `radius` along +z from the origin, `length` long.
TopoDS_Shape rod_solid(double radius, double length);

// Where a family's template goes for one member, and where a rod (rod_solid of its length) goes on its beam.
gp_Trsf connector_transform(const ConnectorPlacement& placement);
gp_Trsf rod_transform(const Rod& rod);

// The plan (plan_connectors, with its errors) and one template solid per family. The families are built in
// parallel; progress counts them, and a cancel stops between families (Cancelled).
ConnectorParts build_connectors(const FlatLattice& lattice, const ConnectorParameters& parameters,
                                Progress& progress = no_progress());

}  // namespace steady
