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

#include <algorithm>
#include <chrono>
#include <random>
#include <cmath>

#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

// The cylinders run this many reach radii from the node: past the ball's sphere, so that their end disks never
// meet it.
constexpr double kCylinderLength = 1.5;
// Connectors are built at this rod radius, then scaled: OpenCASCADE approximates the curves where cylinders meet
// to a tolerance that is nearly absolute (1.5e-4 rod radii at a rod radius of 0.012, 1.3e-8 at 10), and volumes
// follow the tolerance.
constexpr double kBuildRodRadius = 10.0;

gp_Pnt to_pnt(const Vec3& v) { return gp_Pnt(v.x, v.y, v.z); }

// How each try builds the connector: its spheres' poles turned away from where the cylinders meet them (or
// along z as OpenCASCADE puts them), the cylinders fused all at once or one at a time (where all at once breaks,
// one at a time has held, hub_group.cpp), and the fuzzy value in rod radii (smallest first: the edges a fuzzy
// Boolean makes keep a tolerance of that size).
struct Attempt {
  bool turned_poles = true;
  bool one_by_one = false;
  double fuzzy = 0.0;
};
constexpr Attempt kAttempts[] = {{true, false, 0.0}, {true, true, 0.0}, {false, false, 0.0},
                                 {true, false, 1e-7}, {true, true, 1e-7}, {true, false, 1e-6}};
// Points sampled to check a built connector's volume (a Boolean can return a valid solid of the wrong shape):
// 20,000 points give the volume to about 1.5 % (1 sigma); a result more than kSampleSigmas sigmas off is refused.
constexpr int kVolumeSamples = 20000;
constexpr double kSampleSigmas = 6.0;

// A sphere's pole (and so the degenerate points of its parametrization) far from every circle where a cylinder
// meets a sphere of the connector: those circles lie at the angles `circle_angles` from the beam directions. The
// best of 256 directions spread over the sphere, chosen the same way for the same directions.
Vec3 sphere_pole(const std::vector<Vec3>& directions, const std::vector<double>& circle_angles) {
  Vec3 best(0.0, 0.0, 1.0);
  double best_score = -1.0;
  const int n = 256;
  for (int k = 0; k < n; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / n, r = std::sqrt(1.0 - z * z), phi = k * 2.399963229728653;
    const Vec3 pole(r * std::cos(phi), r * std::sin(phi), z);
    double score = INFINITY;
    for (const Vec3& d : directions) {
      const double angle = std::acos(std::clamp(glm::dot(pole, d), -1.0, 1.0));
      for (double a : circle_angles) score = std::min({score, std::abs(angle - a), std::abs(M_PI - angle - a)});
    }
    if (score > best_score) best_score = score, best = pole;
  }
  return best;
}

TopoDS_Shape sphere(double radius, const Vec3& pole) {
  const gp_Dir z(pole.x, pole.y, pole.z);
  const Vec3 x = std::abs(pole.x) < 0.6 ? glm::normalize(glm::cross(pole, Vec3(1, 0, 0))) : glm::normalize(glm::cross(pole, Vec3(0, 1, 0)));
  return BRepPrimAPI_MakeSphere(gp_Ax2(gp_Pnt(0, 0, 0), z, gp_Dir(x.x, x.y, x.z)), radius).Shape();
}

// ExtendedHub(radius) within the connector's ball: the node's ball, core_bulge larger, and a cylinder along each
// direction from inside that ball (where the cylinders of nearly opposite beams do not meet yet) past the reach.
TopTools_ListOfShape capsule_pieces(const std::vector<Vec3>& directions, double radius, double core_bulge,
                                    double reach, const Vec3& pole) {
  TopTools_ListOfShape pieces;
  const double core = radius * (1.0 + core_bulge);
  pieces.Append(sphere(core, pole));
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

// The union of the pieces as one valid solid, or a null shape.
TopoDS_Shape fuse(TopTools_ListOfShape pieces, double fuzzy, bool one_by_one) {
  TopoDS_Shape sum = pieces.First();
  pieces.RemoveFirst();
  TopTools_ListOfShape first, rest;
  for (const TopoDS_Shape& piece : pieces) {
    if (!one_by_one) {
      rest.Append(piece);
      continue;
    }
    first.Clear(), rest.Clear();
    first.Append(sum), rest.Append(piece);
    sum = boolean<BRepAlgoAPI_Fuse>(first, rest, fuzzy);
    if (sum.IsNull()) return sum;
  }
  if (!one_by_one) {
    first.Append(sum);
    sum = boolean<BRepAlgoAPI_Fuse>(first, rest, fuzzy);
  }
  return !sum.IsNull() && solid_count(sum) == 1 && is_valid(sum) ? sum : TopoDS_Shape();
}

// The connector's volume by sampling its definition (build scale, node at the origin), and one standard error.
std::pair<double, double> sampled_volume(const std::vector<Vec3>& directions, const ConnectorParameters& p) {
  const double rho = kBuildRodRadius, reach = p.reach * rho;
  auto in_hub = [&](const Vec3& q, double radius) {
    if (glm::length(q) <= radius * (1.0 + p.core_bulge)) return true;
    for (const Vec3& d : directions) {
      const double along = glm::dot(q, d);
      if (along >= 0.0 && glm::length(q - along * d) <= radius) return true;
    }
    return false;
  };
  std::mt19937_64 rng(20261126);  // fixed: the same connector is checked the same way
  std::uniform_real_distribution<double> u(-reach, reach);
  int inside = 0;
  for (int k = 0; k < kVolumeSamples; ++k) {
    const Vec3 q(u(rng), u(rng), u(rng));
    inside += glm::length(q) <= reach && in_hub(q, p.sleeve * rho) && !in_hub(q, p.hole * rho);
  }
  const double box = 8.0 * reach * reach * reach, f = static_cast<double>(inside) / kVolumeSamples;
  return {box * f, box * std::sqrt(std::max(f * (1.0 - f), 1.0 / kVolumeSamples) / kVolumeSamples)};
}

// One attempt at the build scale (rod radius kBuildRodRadius, node at the origin): the connector's only solid, or a
// null shape.
TopoDS_Shape attempt(const std::vector<Vec3>& directions, const ConnectorParameters& p, const Attempt& how) {
  const double rho = kBuildRodRadius, reach = p.reach * rho, fuzzy = how.fuzzy * rho;
  Vec3 pole(0.0, 0.0, 1.0);
  if (how.turned_poles)
    pole = sphere_pole(directions, {std::asin(1.0 / (1.0 + p.core_bulge)), std::asin(p.sleeve / p.reach),
                                    std::asin(p.hole / p.reach)});
  const TopoDS_Shape sleeves = fuse(capsule_pieces(directions, p.sleeve * rho, p.core_bulge, reach, pole), fuzzy,
                                    how.one_by_one);
  if (sleeves.IsNull()) return sleeves;
  const TopoDS_Shape holes = fuse(capsule_pieces(directions, p.hole * rho, p.core_bulge, reach, pole), fuzzy,
                                  how.one_by_one);
  if (holes.IsNull()) return holes;
  TopTools_ListOfShape ball, outer, inner;
  ball.Append(sphere(reach, pole));
  outer.Append(sleeves);
  inner.Append(holes);
  const TopoDS_Shape bounded = boolean<BRepAlgoAPI_Common>(ball, outer, fuzzy);
  if (bounded.IsNull()) return TopoDS_Shape();
  TopTools_ListOfShape kept;
  kept.Append(bounded);
  const TopoDS_Shape result = boolean<BRepAlgoAPI_Cut>(kept, inner, fuzzy);
  if (result.IsNull() || solid_count(result) != 1) return TopoDS_Shape();
  const TopoDS_Shape solid = TopExp_Explorer(result, TopAbs_SOLID).Current();
  if (!is_valid(solid)) return TopoDS_Shape();
  const auto [sampled, sigma] = sampled_volume(directions, p);
  return std::abs(shape_volume(solid) - sampled) <= kSampleSigmas * sigma ? solid : TopoDS_Shape();
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
  for (const Attempt& how : kAttempts) {
    const TopoDS_Shape solid = attempt(unit, p, how);
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
                              " beams, with its spheres turned or not, fused at once or one at a time, exactly or with fuzzy values up to "
                              "1e-6 rod radii");
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
