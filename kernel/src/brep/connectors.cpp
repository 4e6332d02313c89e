#include "steady/brep/connectors.hpp"

#include <BRepAlgoAPI_Common.hxx>
#include <BRepAlgoAPI_Cut.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>
#include <gp_Ax3.hxx>

#include <tbb/parallel_for.h>

#include <chrono>
#include <cmath>

#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

// Fuzzy values (in rod radii) tried in turn when the exact Booleans fail, smallest first (as hub_group.cpp does):
// the edges a fuzzy Boolean makes keep a tolerance of that size.
constexpr double kFuzzyRetries[] = {0.0, 1e-7, 1e-6};
// The cylinders run this many reach radii from the node: past the ball's sphere, so that their end disks never
// meet it.
constexpr double kCylinderLength = 1.5;
// Connectors are built at this rod radius, then scaled: OpenCASCADE approximates the curves where cylinders meet
// to a tolerance that is nearly absolute (1.5e-4 rod radii at a rod radius of 0.012, 1.3e-8 at 10), and volumes
// follow the tolerance.
constexpr double kBuildRodRadius = 10.0;

gp_Pnt to_pnt(const Vec3& v) { return gp_Pnt(v.x, v.y, v.z); }

// ExtendedHub(radius) within the connector's ball: the node's ball, core_bulge larger, and a cylinder along each
// direction from inside that ball (where the cylinders of nearly opposite beams do not meet yet) past the reach.
TopTools_ListOfShape capsule_pieces(const std::vector<Vec3>& directions, double radius, double core_bulge,
                                    double reach) {
  TopTools_ListOfShape pieces;
  const double core = radius * (1.0 + core_bulge);
  pieces.Append(BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), core).Shape());
  // The cylinder leaves the core's sphere at sqrt(core^2 - radius^2) along its axis; it starts halfway there.
  const double start = 0.5 * std::sqrt(core * core - radius * radius);
  for (const Vec3& d : directions)
    pieces.Append(BRepPrimAPI_MakeCylinder(gp_Ax2(to_pnt(start * d), gp_Dir(d.x, d.y, d.z)), radius,
                                           kCylinderLength * reach).Shape());
  return pieces;
}

template <class Op>
TopoDS_Shape boolean(const TopTools_ListOfShape& args, const TopTools_ListOfShape& tools, double fuzzy) {
  Op op;
  op.SetArguments(args);
  op.SetTools(tools);
  op.SetRunParallel(Standard_False);  // families are built in parallel
  if (fuzzy > 0.0) op.SetFuzzyValue(fuzzy);
  op.Build();
  if (!op.IsDone() || op.HasErrors()) return TopoDS_Shape();
  return op.Shape();
}

TopoDS_Shape fuse(TopTools_ListOfShape pieces, double fuzzy) {
  TopTools_ListOfShape first;
  first.Append(pieces.First());
  pieces.RemoveFirst();
  return boolean<BRepAlgoAPI_Fuse>(first, pieces, fuzzy);
}

// One attempt at the build scale (rod radius kBuildRodRadius, node at the origin): the connector's only solid, or a
// null shape.
TopoDS_Shape attempt(const std::vector<Vec3>& directions, const ConnectorParameters& p, double fuzzy) {
  const double rho = kBuildRodRadius, reach = p.reach * rho;
  const TopoDS_Shape sleeves = fuse(capsule_pieces(directions, p.sleeve * rho, p.core_bulge, reach), fuzzy);
  const TopoDS_Shape holes = fuse(capsule_pieces(directions, p.hole * rho, p.core_bulge, reach), fuzzy);
  if (sleeves.IsNull() || holes.IsNull()) return TopoDS_Shape();
  TopTools_ListOfShape ball, outer, inner;
  ball.Append(BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), reach).Shape());
  outer.Append(sleeves);
  inner.Append(holes);
  const TopoDS_Shape bounded = boolean<BRepAlgoAPI_Common>(ball, outer, fuzzy);
  if (bounded.IsNull()) return TopoDS_Shape();
  TopTools_ListOfShape kept;
  kept.Append(bounded);
  const TopoDS_Shape result = boolean<BRepAlgoAPI_Cut>(kept, inner, fuzzy);
  if (result.IsNull() || solid_count(result) != 1) return TopoDS_Shape();
  const TopoDS_Shape solid = TopExp_Explorer(result, TopAbs_SOLID).Current();
  return is_valid(solid) ? solid : TopoDS_Shape();
}

}  // namespace

TopoDS_Shape connector_solid(const Vec3& center, const std::vector<Vec3>& directions, const ConnectorParameters& p) {
  check_connector_parameters(p);
  if (directions.empty()) fail_input("directions", "a connector needs at least one beam direction");
  std::vector<Vec3> unit;
  for (const Vec3& d : directions) {
    const double n = glm::length(d);
    if (!std::isfinite(n) || !(n > 0.0)) fail_input("directions", "must be finite, non-zero vectors");
    unit.push_back(d / n);
  }
  for (double fuzzy : kFuzzyRetries) {
    const TopoDS_Shape solid = attempt(unit, p, fuzzy * kBuildRodRadius);
    if (solid.IsNull()) continue;
    gp_Trsf scale, move;
    scale.SetScale(gp_Pnt(0, 0, 0), p.rod_radius / kBuildRodRadius);
    move.SetTranslation(gp_Vec(center.x, center.y, center.z));
    const TopoDS_Shape placed = BRepBuilderAPI_Transform(solid, move * scale, Standard_True).Shape();
    if (is_valid(placed)) return placed;
  }
  fail_input("connector", "OpenCASCADE's Booleans gave no single valid solid for the connector at (" +
                              std::to_string(center.x) + ", " + std::to_string(center.y) + ", " +
                              std::to_string(center.z) + ") with " + std::to_string(unit.size()) +
                              " beams, exactly or with fuzzy values up to 1e-6 rod radii");
}

TopoDS_Shape rod_solid(double radius, double length) {
  require_positive(radius, "radius");
  require_positive(length, "length");
  return BRepPrimAPI_MakeCylinder(gp_Ax2(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), radius, length).Shape();
}

gp_Trsf connector_transform(const ConnectorPlacement& m) {
  gp_Trsf t;
  const Mat3& r = m.rotation;  // column-major: r[c][row]
  t.SetValues(r[0][0], r[1][0], r[2][0], m.center.x, r[0][1], r[1][1], r[2][1], m.center.y, r[0][2], r[1][2], r[2][2],
              m.center.z);
  return t;
}

gp_Trsf rod_transform(const Rod& rod) {
  const Vec3 axis = glm::normalize(rod.end - rod.start);
  gp_Trsf t;
  t.SetTransformation(gp_Ax3(to_pnt(rod.start), gp_Dir(axis.x, axis.y, axis.z)));
  t.Invert();  // SetTransformation maps the placed frame to the standard one; the rod goes the other way
  return t;
}

ConnectorParts build_connectors(const FlatLattice& lattice, const ConnectorParameters& parameters,
                                Progress& progress) {
  ConnectorParts parts;
  parts.plan = plan_connectors(lattice, parameters);
  const std::size_t n = parts.plan.families.size();
  parts.templates.resize(n);
  parts.volumes.resize(n);
  parts.build_seconds.resize(n);
  progress.set_total(static_cast<std::int64_t>(n) + 1);
  progress.check();
  tbb::parallel_for(std::size_t(0), n, [&](std::size_t k) {
    progress.check();
    const auto start = std::chrono::steady_clock::now();
    parts.templates[k] = connector_solid(Vec3(0.0), parts.plan.families[k].directions, parameters);
    parts.volumes[k] = shape_volume(parts.templates[k]);
    parts.build_seconds[k] = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    progress.advance();
  });
  progress.finish();
  return parts;
}

}  // namespace steady
