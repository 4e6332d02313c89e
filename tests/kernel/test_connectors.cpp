// Connectors of constant-radius lattices (oracle 16 of the spec): the families' placed templates equal the
// connectors built directly at each node in world coordinates; the template solids against brute-force point
// membership of Ball ∩ ExtendedHub(sleeve) − ExtendedHub(hole); family counts of a cubic grid; rods that keep
// apart; STEP files read back; bad input and too-short beams refused with the parameter named.
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <gtest/gtest.h>

#include <functional>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <random>
#include <set>

#include "steady/brep/brep_io.hpp"
#include "steady/brep/connector_step.hpp"
#include "steady/brep/connectors.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/core/errors.hpp"
#include "steady/cots/becots_lattice.hpp"
#include "test_lattices.hpp"

namespace {

using namespace steady;

ConnectorParameters parameters(double rod_radius, double sleeve = 1.6, double reach = 2.5) {
  ConnectorParameters p;
  p.rod_radius = rod_radius;
  p.sleeve = sleeve;
  p.reach = reach;
  return p;
}

// Parameters whose reach lies in the middle of the range that fits the lattice.
ConnectorParameters fitting(const FlatLattice& f, double rod_radius, double sleeve = 1.6) {
  ConnectorParameters p = parameters(rod_radius, sleeve);
  const auto [low, high] = connector_reach_range(f, p);
  EXPECT_LT(low, high);
  p.reach = 0.5 * (low + high);
  return p;
}

double shortest_beam(const FlatLattice& f) {
  double shortest = INFINITY;
  for (const FlatBeam& b : f.beams) shortest = std::min(shortest, glm::length(f.balls[b.b].center - f.balls[b.a].center));
  return shortest;
}

// Brute-force membership of the connector at `center`: the definition, point by point. Capsules are whole beams
// with both end balls (the node's one core_bulge larger); `ends` are the neighbours' centers.
bool in_capsules(const Vec3& p, const Vec3& center, const std::vector<Vec3>& ends, double radius, double bulge) {
  if (glm::length(p - center) <= radius * (1.0 + bulge)) return true;
  for (const Vec3& end : ends) {
    const Vec3 axis = end - center;
    const double t = std::clamp(glm::dot(p - center, axis) / glm::dot(axis, axis), 0.0, 1.0);
    if (glm::length(p - (center + t * axis)) <= radius) return true;
  }
  return false;
}

bool in_connector(const Vec3& p, const Vec3& center, const std::vector<Vec3>& ends, const ConnectorParameters& c) {
  const double rho = c.rod_radius;
  return glm::length(p - center) <= c.reach * rho && in_capsules(p, center, ends, c.sleeve * rho, c.core_bulge) &&
         !in_capsules(p, center, ends, c.hole * rho, c.core_bulge);
}

// How far p is from the nearest surface the definition uses (spheres, cylinders): points closer than a
// tolerance may be classified either way.
double surface_distance(const Vec3& p, const Vec3& center, const std::vector<Vec3>& ends, const ConnectorParameters& c) {
  const double rho = c.rod_radius;
  const double r = glm::length(p - center);
  const double core = 1.0 + c.core_bulge;
  double d = std::min({std::abs(r - c.reach * rho), std::abs(r - core * c.sleeve * rho), std::abs(r - core * c.hole * rho)});
  for (const Vec3& end : ends) {
    const Vec3 axis = glm::normalize(end - center);
    const double along = glm::dot(p - center, axis);
    const double radial = glm::length(p - center - along * axis);
    if (along > 0.0) d = std::min({d, std::abs(radial - c.sleeve * rho), std::abs(radial - c.hole * rho)});
  }
  return d;
}

bool occ_inside(const TopoDS_Shape& solid, const Vec3& p) {
  BRepClass3d_SolidClassifier classifier(solid, gp_Pnt(p.x, p.y, p.z), 1e-9);
  return classifier.State() == TopAbs_IN;
}

// Volume, area, centroid and inertia tensor (about the world origin) of a solid.
struct Moments {
  double volume = 0.0, area = 0.0;
  gp_Pnt centroid;
  gp_Mat inertia;
};

Moments moments(const TopoDS_Shape& shape) {
  GProp_GProps v, a;
  BRepGProp::VolumeProperties(shape, v, 1e-10);
  BRepGProp::SurfaceProperties(shape, a, 1e-10);
  return {v.Mass(), a.Mass(), v.CentreOfMass(), v.MatrixOfInertia()};
}

// The connector of `ball` built directly (Booleans in world coordinates) against its family's placed template:
// same volume, area, centroid and inertia, and the same side for random points away from the surfaces.
void expect_congruent(const FlatLattice& f, const ConnectorParts& parts, std::int64_t ball, std::mt19937_64& rng) {
  const ConnectorParameters& c = parts.plan.parameters;
  const int family = parts.plan.family_of_ball[ball];
  const ConnectorPlacement& m = parts.plan.families[family].members[parts.plan.member_of_ball[ball]];
  std::vector<Vec3> directions, ends;
  for (const std::int64_t* e = f.incident_begin(ball); e != f.incident_end(ball); ++e) {
    ends.push_back(f.balls[f.other_ball(*e, ball)].center);
    directions.push_back(ends.back() - f.balls[ball].center);
  }
  const TopoDS_Shape direct = connector_solid(f.balls[ball].center, directions, c);
  const TopoDS_Shape placed = parts.templates[family].Moved(TopLoc_Location(connector_transform(m)));
  ASSERT_TRUE(is_valid(direct) && is_valid(placed)) << "ball " << ball;
  const Moments a = moments(direct), b = moments(placed);
  const double size = c.reach * c.rod_radius;
  EXPECT_NEAR(a.volume, b.volume, 1e-6 * b.volume) << "ball " << ball;
  EXPECT_NEAR(a.area, b.area, 1e-6 * b.area) << "ball " << ball;
  EXPECT_LT(a.centroid.Distance(b.centroid), 1e-6 * size) << "ball " << ball;
  const double scale = b.volume * size * size;  // the inertia's order of magnitude
  for (int r = 1; r <= 3; ++r)
    for (int s = 1; s <= 3; ++s) EXPECT_NEAR(a.inertia(r, s), b.inertia(r, s), 1e-6 * scale) << "ball " << ball;
  std::uniform_real_distribution<double> u(-size, size);
  int compared = 0;
  for (int k = 0; k < 40; ++k) {
    const Vec3 p = f.balls[ball].center + Vec3(u(rng), u(rng), u(rng));
    if (surface_distance(p, f.balls[ball].center, ends, c) < 1e-6 * size) continue;
    const bool expected = in_connector(p, f.balls[ball].center, ends, c);
    EXPECT_EQ(occ_inside(direct, p), expected) << "ball " << ball << " direct, point " << k;
    EXPECT_EQ(occ_inside(placed, p), expected) << "ball " << ball << " placed, point " << k;
    ++compared;
  }
  EXPECT_GT(compared, 30);
}

// Nodes in the same position class (which boundaries of the index box they lie on) of a steady brick whose steps
// commute have similar hubs: one family each.
void expect_classes_in_one_family(const Lattice& lattice, const ConnectorPlan& plan) {
  const Counts n = lattice.counts();
  std::map<std::vector<int>, std::set<int>> families_of_class;
  for (std::int64_t k = 0; k < n.w; ++k)
    for (std::int64_t j = 0; j < n.v; ++j)
      for (std::int64_t i = 0; i < n.u; ++i)
        for (int node = 0; node < lattice.node_count(); ++node) {
          const std::vector<int> position{node, i == 0, i == n.u - 1, j == 0, j == n.v - 1, k == 0, k == n.w - 1};
          families_of_class[position].insert(plan.family_of_ball[lattice.ball_index({i, j, k, node})]);
        }
  for (const auto& [position, families] : families_of_class) EXPECT_EQ(families.size(), 1u);
  EXPECT_LE(plan.families.size(), families_of_class.size());
}

BecotsMap cone() { return BecotsMap({0, 0, 0}, {0.1, 1, 0.2}, {1.3, 1.2, -0.3}, {1, 0, 0.1}); }

// A bent, twisted and growing brick: U turns about the z axis, V screws along it, W dilates from a point on it.
// The three commute, so every hub is a similar copy of its position class's first.
Lattice bent_twisted_brick() {
  test::BrickDefinition d;
  d.nodes = {{{3, 0, 0}, 0.2}};
  for (int axis = 0; axis < 3; ++axis) d.beams.push_back({0, axis == 0, axis == 1, axis == 2, 0, 0.1, 0.1});
  d.counts = {5, 2, 2};
  d.u = {Similarity::rotation(0.3, {0, 0, 1}, {0, 0, 0})};
  d.v = {Similarity::screw(0.2, {0, 0, 1}, {0, 0, 0}, 1.0)};
  d.w = {Similarity::dilation(1.3, {0, 0, 0})};
  return Lattice(d);
}

TEST(Connectors, FamiliesOfABecotsTriangleLatticeEqualTheDirectlyBuiltConnectors) {
  const Lattice lattice = becots_lattice(cone(), becots_connectivity("triangle"), {5, 4, 1}, 0.01);
  const FlatLattice f = flatten(lattice);
  const ConnectorParts parts = build_connectors(f, fitting(f, shortest_beam(f) / 10.0));
  expect_classes_in_one_family(lattice, parts.plan);
  EXPECT_LT(parts.plan.families.size(), 10u);
  std::mt19937_64 rng(16);
  // The last member of each family: for a single member, its own template turned into its frame.
  for (const ConnectorFamily& family : parts.plan.families) expect_congruent(f, parts, family.members.back().ball, rng);
}

TEST(Connectors, FamiliesOfABecotsKagomeLatticeFollowItsNodePatterns) {
  const Lattice lattice = becots_lattice(cone(), becots_connectivity("kagome"), {4, 3, 1}, 0.01);
  const FlatLattice f = flatten(lattice);
  const ConnectorParts parts = build_connectors(f, fitting(f, shortest_beam(f) / 10.0));
  expect_classes_in_one_family(lattice, parts.plan);
  std::mt19937_64 rng(17);
  for (const ConnectorFamily& family : parts.plan.families) expect_congruent(f, parts, family.members.back().ball, rng);
}

TEST(Connectors, FamiliesOfABentTwistedBrickEqualTheDirectlyBuiltConnectors) {
  const Lattice lattice = bent_twisted_brick();
  const FlatLattice f = flatten(lattice);
  const ConnectorParts parts = build_connectors(f, fitting(f, shortest_beam(f) / 10.0, 1.5));
  expect_classes_in_one_family(lattice, parts.plan);
  EXPECT_GT(parts.plan.families.size(), 1u);
  std::mt19937_64 rng(18);
  for (const ConnectorFamily& family : parts.plan.families)
    if (family.members.size() > 1) expect_congruent(f, parts, family.members.back().ball, rng);
}

TEST(Connectors, TemplateVolumesMatchMonteCarloMembership) {
  std::mt19937_64 rng(5);
  const ConnectorParameters c = parameters(0.5, 1.7, 3.0);
  for (int trial = 0; trial < 4; ++trial) {
    // 1 to 5 directions at least 60 degrees apart (so the reach holds the rods), at a random center.
    std::vector<Vec3> directions;
    while (directions.size() < static_cast<std::size_t>(1 + trial + (trial > 2))) {
      const Vec3 d = test::random_unit(rng);
      bool apart = true;
      for (const Vec3& e : directions) apart = apart && glm::dot(d, e) < 0.5;
      if (apart) directions.push_back(d);
    }
    const Vec3 center = test::random_vec(rng, 3.0);
    std::vector<Vec3> ends;
    for (const Vec3& d : directions) ends.push_back(center + 10.0 * d);  // beams longer than the reach
    const TopoDS_Shape solid = connector_solid(center, directions, c);
    ASSERT_TRUE(is_valid(solid));
    const double volume = shape_volume(solid);
    const double half = c.reach * c.rod_radius;
    std::uniform_real_distribution<double> u(-half, half);
    const int samples = 200000;
    int inside = 0;
    for (int k = 0; k < samples; ++k) inside += in_connector(center + Vec3(u(rng), u(rng), u(rng)), center, ends, c);
    const double box = 8.0 * half * half * half, fraction = static_cast<double>(inside) / samples;
    const double sigma = box * std::sqrt(fraction * (1.0 - fraction) / samples);
    EXPECT_NEAR(volume, box * fraction, 4.0 * sigma) << directions.size() << " beams";
    // Pointwise: OpenCASCADE's classifier agrees with the definition away from the surfaces.
    for (int k = 0; k < 300; ++k) {
      const Vec3 p = center + Vec3(u(rng), u(rng), u(rng));
      if (surface_distance(p, center, ends, c) < 1e-6) continue;
      EXPECT_EQ(occ_inside(solid, p), in_connector(p, center, ends, c)) << directions.size() << " beams, point " << k;
    }
  }
}

TEST(Connectors, CubicGridHasCornerEdgeFaceAndInnerFamilies) {
  const FlatLattice f = test::grid_lattice(5);
  const ConnectorPlan plan = plan_connectors(f, parameters(0.08));
  // 5^3 nodes: 8 corners (3 beams), 12 x 3 on edges (4), 6 x 9 on faces (5), 27 inside (6).
  std::multiset<std::pair<std::size_t, std::size_t>> found;  // (degree, members)
  for (const ConnectorFamily& family : plan.families) found.insert({family.directions.size(), family.members.size()});
  const std::multiset<std::pair<std::size_t, std::size_t>> expected{{3, 8}, {4, 36}, {5, 54}, {6, 27}};
  EXPECT_EQ(found, expected);
  // Placements carry each template's directions onto its member's beams, one to one.
  for (const ConnectorFamily& family : plan.families)
    for (const ConnectorPlacement& m : family.members) {
      std::set<std::int64_t> neighbours, reached;
      for (const std::int64_t* e = f.incident_begin(m.ball); e != f.incident_end(m.ball); ++e)
        neighbours.insert(f.other_ball(*e, m.ball));
      EXPECT_NEAR(glm::determinant(m.rotation), 1.0, 1e-12);
      for (const Vec3& d : family.directions) {
        const Vec3 w = glm::round(m.center + m.rotation * d);
        EXPECT_LT(glm::length(m.center + m.rotation * d - w), 1e-12);
        const std::int64_t id = static_cast<std::int64_t>((w.z * 5 + w.y) * 5 + w.x);  // grid_lattice's numbering
        EXPECT_TRUE(neighbours.count(id)) << "ball " << m.ball;
        reached.insert(id);
      }
      EXPECT_EQ(reached, neighbours) << "ball " << m.ball;
    }
  EXPECT_EQ(plan.rods.size(), f.beams.size());
  // Every node has beams at right angles, so every rod ends rho cot(45 degrees) = rho inside each node: one length.
  ASSERT_EQ(plan.cut_list.size(), 1u);
  EXPECT_NEAR(plan.cut_list[0].length, 1.0 - 2 * 0.08, 1e-12);
  EXPECT_EQ(plan.cut_list[0].rods.size(), f.beams.size());
}

TEST(Connectors, RodsEndWhereTheyMeetNoOtherRodOfTheirNode) {
  std::mt19937_64 rng(9);
  const FlatLattice f = test::grid_lattice(3);
  const ConnectorPlan plan = plan_connectors(f, parameters(0.1));
  for (const Rod& rod : plan.rods) {
    const gp_Pnt end = gp_Pnt(0, 0, rod.length).Transformed(rod_transform(rod));
    const gp_Pnt start = gp_Pnt(0, 0, 0).Transformed(rod_transform(rod));
    EXPECT_LT(end.Distance(gp_Pnt(rod.end.x, rod.end.y, rod.end.z)), 1e-12);
    EXPECT_LT(start.Distance(gp_Pnt(rod.start.x, rod.start.y, rod.start.z)), 1e-12);
    // Axis-aligned rods at right angles end one rod radius from the node: rho cot(45 degrees).
    const bool a_has_others = f.degree(rod.a) > 1, b_has_others = f.degree(rod.b) > 1;
    EXPECT_NEAR(rod.depth_a, a_has_others ? 0.1 : 0.0, 1e-12);
    EXPECT_NEAR(rod.depth_b, b_has_others ? 0.1 : 0.0, 1e-12);
  }
  // Random nodes: points sampled in each rod (beyond its end depth) lie in no other rod of the node.
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Vec3> d;
    for (int k = 0; k < 2 + trial % 5; ++k) d.push_back(test::random_unit(rng));
    const double rho = 0.3;
    std::vector<double> depth;
    for (std::size_t s = 0; s < d.size(); ++s) depth.push_back(rod_end_depth(d, s, rho));
    std::uniform_real_distribution<double> u(-1.0, 1.0), along(0.0, 3.0);
    for (std::size_t s = 0; s < d.size(); ++s)
      for (int k = 0; k < 2000; ++k) {
        const Vec3 e1 = glm::normalize(glm::cross(d[s], test::random_unit(rng))), e2 = glm::cross(d[s], e1);
        const double a = u(rng), b = u(rng);
        if (a * a + b * b > 1.0) continue;
        const Vec3 p = (depth[s] + along(rng)) * d[s] + rho * (a * e1 + b * e2);
        for (std::size_t o = 0; o < d.size(); ++o) {
          if (o == s) continue;
          const double x = glm::dot(p, d[o]);
          const bool inside = x > depth[o] && glm::length(p - x * d[o]) < rho * (1.0 - 1e-9);
          ASSERT_FALSE(inside) << "trial " << trial << " rods " << s << " and " << o;
        }
      }
  }
}

std::string temp_path(const std::string& name) {
  return (std::filesystem::temp_directory_path() / ("steady_connectors_" + std::to_string(::getpid()) + "_" + name))
      .string();
}

TEST(Connectors, StepFilesReadBackWithTheirSolidsAndPlacements) {
  const Lattice lattice = becots_lattice(cone(), becots_connectivity("triangle"), {4, 3, 1}, 0.01);
  const FlatLattice f = flatten(lattice);
  const ConnectorParts parts = build_connectors(f, fitting(f, shortest_beam(f) / 10.0));
  const std::string family_path = temp_path("family.step");
  write_connector_family_step(family_path, parts, 0);
  const std::vector<StepPart> one = read_step_parts(family_path);
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].name, "Connector_1");
  EXPECT_EQ(solid_count(one[0].shape), 1);
  EXPECT_TRUE(is_valid(one[0].shape));
  EXPECT_NEAR(shape_volume(one[0].shape), parts.volumes[0], 1e-6 * parts.volumes[0]);

  const std::string path = temp_path("assembly.step");
  write_connectors_step(path, parts);
  const std::vector<StepPart> read = read_step_parts(path);
  std::size_t connectors = 0;
  for (const ConnectorFamily& family : parts.plan.families) connectors += family.members.size();
  ASSERT_EQ(read.size(), connectors + parts.plan.rods.size());
  std::map<std::string, std::vector<const StepPart*>> by_name;
  for (const StepPart& p : read) {
    EXPECT_EQ(solid_count(p.shape), 1) << p.name;
    EXPECT_TRUE(is_valid(p.shape)) << p.name;
    by_name[p.name].push_back(&p);
  }
  for (std::size_t k = 0; k < parts.plan.families.size(); ++k) {
    const std::vector<const StepPart*>& copies = by_name[connector_part_name(k)];
    ASSERT_EQ(copies.size(), parts.plan.families[k].members.size());
    // Each copy sits at one member: its centroid is the member's placement of the template's centroid.
    const Moments t = moments(parts.templates[k]);
    for (std::size_t m = 0; m < copies.size(); ++m) {
      const Moments c = moments(copies[m]->shape);
      EXPECT_NEAR(c.volume, parts.volumes[k], 1e-6 * parts.volumes[k]);
      const gp_Pnt expected = t.centroid.Transformed(connector_transform(parts.plan.families[k].members[m]));
      EXPECT_LT(c.centroid.Distance(expected), 1e-6 * parts.plan.parameters.rod_radius);
    }
  }
  for (std::size_t c = 0; c < parts.plan.cut_list.size(); ++c) {
    const RodLength& cut = parts.plan.cut_list[c];
    ASSERT_EQ(by_name[rod_part_name(c)].size(), cut.rods.size());
    const double rho = parts.plan.parameters.rod_radius;
    for (const StepPart* p : by_name[rod_part_name(c)])
      EXPECT_NEAR(shape_volume(p->shape), M_PI * rho * rho * cut.length, 1e-6 * M_PI * rho * rho * cut.length);
  }
  std::filesystem::remove(family_path);
  std::filesystem::remove(path);
}

// The message with which plan_connectors refuses the lattice, or "" when it makes the plan.
std::string refusal(const FlatLattice& f, const ConnectorParameters& p) {
  try {
    plan_connectors(f, p);
    return "";
  } catch (const InvalidInput& e) {
    return e.what();
  }
}

// The reach a clash's refusal advises ("the largest reach that clears them is X"), or NaN when it gives none.
double advised_reach(const std::string& message) {
  const std::string advice = "the largest reach that clears them is ";
  const auto at = message.find(advice);
  return at == std::string::npos ? NAN : std::stod(message.substr(at + advice.size()));
}

TEST(Connectors, BadParametersAreRefusedByName) {
  const FlatLattice f = test::grid_lattice(2);
  auto refuses = [&](ConnectorParameters p, const std::string& field) {
    const std::string m = refusal(f, p);
    EXPECT_EQ(m.rfind(field + ":", 0), 0u) << (m.empty() ? "accepted, expected an error naming " + field : m);
  };
  for (double bad : {0.0, -0.1, std::nan(""), HUGE_VAL}) {
    ConnectorParameters p = parameters(0.1);
    p.rod_radius = bad;
    refuses(p, "rod_radius");
  }
  ConnectorParameters p = parameters(0.1);
  p.sleeve = 1.0;  // not above the hole
  refuses(p, "sleeve");
  p = parameters(0.1);
  p.sleeve = NAN;
  refuses(p, "sleeve");
  p = parameters(0.1);
  p.hole = 0.9;  // a rod would not fit
  refuses(p, "hole");
  p = parameters(0.1, 1.6, 1.5);  // reach below the sleeve
  refuses(p, "reach");
  p = parameters(0.1);
  p.angle_tolerance = NAN;
  refuses(p, "angle_tolerance");
  p = parameters(0.1);
  p.length_tolerance = -1.0;
  refuses(p, "length_tolerance");
  EXPECT_THROW(connector_solid(Vec3(0.0), {}, parameters(0.1)), InvalidInput);
  EXPECT_THROW(connector_solid(Vec3(0.0), {Vec3(0.0)}, parameters(0.1)), InvalidInput);
}

TEST(Connectors, ATooShortBeamIsNamedWithTheLargestReachThatFits) {
  // Two beams from ball 0: a long one and one of length 0.4 (to ball 2).
  const FlatLattice f = make_flat_lattice({{{0, 0, 0}, 0.1}, {{3, 0, 0}, 0.1}, {{0, 0.4, 0}, 0.1}},
                                          {{0, 1, 0.05, 0.05}, {0, 2, 0.05, 0.05}});
  // Reach 2.5 rod radii: each sleeve runs sqrt(2.5^2 - 1) 0.1 = 0.229 along the beam, more than half of it.
  const std::string m = refusal(f, parameters(0.1));
  ASSERT_FALSE(m.empty()) << "accepted";
  EXPECT_EQ(m.rfind("reach:", 0), 0u) << m;
  EXPECT_NE(m.find("beam 1 (balls 0 and 2, length 0.4)"), std::string::npos) << m;
  // Each sleeve may run at most half the beam: sqrt(reach^2 - 1) 0.1 < 0.2, reach < sqrt(5) = 2.23607.
  EXPECT_NE(m.find("largest reach that fits it is 2.23607"), std::string::npos) << m;
}

// Whether a point belongs to the connector at `center` (rod radius 0.1, the parameters' defaults: sleeve 1.6,
// reach 2.5, hole 1, core 5 % wider) with beams along `directions`: the definition, evaluated directly.
bool in_connector(const Vec3& q, const Vec3& center, const std::vector<Vec3>& directions) {
  const double rho = 0.1, reach = 2.5 * rho, sleeve = 1.6 * rho, hole = rho, core = 1.6 * 1.05 * rho;
  const Vec3 v = q - center;
  if (glm::length(v) > reach) return false;
  bool outer = glm::length(v) <= core, inner = glm::length(v) <= hole * 1.05;
  for (const Vec3& d : directions) {
    const double axial = glm::dot(v, d), radial = glm::length(v - axial * d);
    outer = outer || (axial >= 0.0 && radial <= sleeve);
    inner = inner || (axial >= 0.0 && radial <= hole);
  }
  return outer && !inner;
}

// The least distance, over a grid of spacing `step` in the box [lo, hi], from a point of the first connector to a
// point of the second (or of a rod: `other` true there); negative when some grid point is in both.
bool grid_finds_common_point(const Vec3& lo, const Vec3& hi, double step, const std::function<bool(const Vec3&)>& one,
                             const std::function<bool(const Vec3&)>& other) {
  for (double x = lo.x; x <= hi.x; x += step)
    for (double y = lo.y; y <= hi.y; y += step)
      for (double z = lo.z; z <= hi.z; z += step)
        if (one({x, y, z}) && other({x, y, z})) return true;
  return false;
}

TEST(Connectors, ClashesWithOtherNodesRodsAndConnectorsAreNamed) {
  const ConnectorParameters p = parameters(0.1);
  const Vec3 up(0, 1, 0);
  // A node 0.25 beside the middle of another node pair's beam: its connector's core (0.168) reaches into that rod
  // (radius 0.1). The brute force on the definitions finds a common point.
  const FlatLattice rod_clash = make_flat_lattice(
      {{{0, 0, 0}, 0.1}, {{10, 0, 0}, 0.1}, {{5, 0.25, 0}, 0.1}, {{5, 10, 0}, 0.1}}, {{0, 1, 0.05, 0.05}, {2, 3, 0.05, 0.05}});
  const auto in_rod = [](const Vec3& q) { return std::hypot(q.y, q.z) <= 0.1 && q.x >= 0.0 && q.x <= 10.0; };
  EXPECT_TRUE(grid_finds_common_point({4.8, 0.0, -0.1}, {5.2, 0.2, 0.1}, 0.005,
                                      [&](const Vec3& q) { return in_connector(q, {5, 0.25, 0}, {up}); }, in_rod));
  const std::string m = refusal(rod_clash, p);
  ASSERT_FALSE(m.empty()) << "accepted";
  EXPECT_EQ(m.rfind("reach:", 0), 0u) << m;
  EXPECT_NE(m.find("connector at ball 2 would meet the rod of beam 0 (balls 0 and 1)"), std::string::npos) << m;
  EXPECT_NE(m.find("no reach clears them"), std::string::npos) << m;  // the core alone reaches the rod
  // 0.3 away the core clears the rod (0.168 + 0.1 < 0.3), the brute force finds no common point, and the plan is made.
  const FlatLattice apart = make_flat_lattice(
      {{{0, 0, 0}, 0.1}, {{10, 0, 0}, 0.1}, {{5, 0.3, 0}, 0.1}, {{5, 10, 0}, 0.1}}, {{0, 1, 0.05, 0.05}, {2, 3, 0.05, 0.05}});
  EXPECT_FALSE(grid_finds_common_point({4.6, -0.1, -0.2}, {5.4, 0.6, 0.2}, 0.005,
                                       [&](const Vec3& q) { return in_connector(q, {5, 0.3, 0}, {up}); }, in_rod));
  EXPECT_NO_THROW(plan_connectors(apart, p));
  // Two nodes with arms at 45 and 135 degrees: 0.6 apart their connectors do not meet (each arm stays within the
  // reach of its node, on its side of x = 0.3), 0.4 apart they do; a shorter reach then clears them, and the
  // message says how short.
  const auto pair = [](double gap) {
    return make_flat_lattice({{{0, 0, 0}, 0.1}, {{gap, 0, 0}, 0.1}, {{5, 5, 0}, 0.1}, {{gap - 5, 5, 0}, 0.1}},
                             {{0, 2, 0.05, 0.05}, {1, 3, 0.05, 0.05}});
  };
  const Vec3 d0 = glm::normalize(Vec3(1, 1, 0)), d1 = glm::normalize(Vec3(-1, 1, 0));
  for (const double gap : {0.6, 0.4}) {
    const bool brute = grid_finds_common_point(
        {-0.3, -0.3, -0.2}, {gap + 0.3, 0.3, 0.2}, 0.004,
        [&](const Vec3& q) { return in_connector(q, {0, 0, 0}, {d0}); },
        [&](const Vec3& q) { return in_connector(q, {gap, 0, 0}, {d1}); });
    EXPECT_EQ(brute, gap < 0.5) << gap;
    if (!brute) {
      EXPECT_NO_THROW(plan_connectors(pair(gap), p)) << gap;
      continue;
    }
    const std::string first = refusal(pair(gap), p);
    ASSERT_FALSE(first.empty()) << "accepted";
    EXPECT_NE(first.find("the connectors at balls 0 and 1 would meet"), std::string::npos) << first;
    const double largest = advised_reach(first);
    ASSERT_FALSE(std::isnan(largest)) << first;
    EXPECT_GT(largest, 1.6 * 1.05);
    EXPECT_LT(largest, 2.5);
    // Following the advice: at that reach the two connectors clear; each rod then still passes the other node's
    // arm (the rods cross there), named with its own largest reach; following that too gives a plan.
    double reach = 0.99 * largest;
    int fixes = 0;
    for (std::string next = refusal(pair(gap), parameters(0.1, 1.6, reach)); !next.empty();
         next = refusal(pair(gap), parameters(0.1, 1.6, reach))) {
      ASSERT_LT(++fixes, 4) << next;  // a plan within three more pieces of advice
      EXPECT_EQ(next.find("the connectors at balls 0 and 1"), std::string::npos) << next;
      const double fix = advised_reach(next);
      ASSERT_FALSE(std::isnan(fix)) << next;
      ASSERT_LT(fix, reach) << next;
      reach = 0.99 * fix;
    }
  }
}

TEST(Connectors, RodsTooCloseForTheReachAreNamedWithTheSmallestReach) {
  // Two beams 20 degrees apart: their rods meet 0.1 cot(10 deg) = 0.567 from the node, beyond a sleeve of reach 2.5.
  const double a = 20.0 * M_PI / 180.0;
  const FlatLattice f = make_flat_lattice({{{0, 0, 0}, 0.1}, {{3, 0, 0}, 0.1}, {{3 * std::cos(a), 3 * std::sin(a), 0}, 0.1}},
                                          {{0, 1, 0.05, 0.05}, {0, 2, 0.05, 0.05}});
  const std::string m = refusal(f, parameters(0.1));
  ASSERT_FALSE(m.empty()) << "accepted";
  EXPECT_EQ(m.rfind("reach:", 0), 0u) << m;
  EXPECT_NE(m.find("at ball 0"), std::string::npos) << m;
  const ConnectorPlan plan = [&] {
    ConnectorParameters p = parameters(0.1, 1.6, 6.0);
    return plan_connectors(f, p);
  }();
  EXPECT_NEAR(plan.min_reach, std::sqrt(std::pow(1.0 / std::tan(a / 2), 2) + 1.6 * 1.6), 1e-12);
}

TEST(Connectors, ProgressCountsFamiliesAndCancelStops) {
  const FlatLattice f = test::grid_lattice(3);
  Progress cancelling([&](double) { return false; });
  cancelling.set_report_interval(std::chrono::milliseconds(0));
  EXPECT_THROW(build_connectors(f, parameters(0.08), cancelling), Cancelled);
  double last = 0.0;
  Progress watching([&](double fraction) {
    last = fraction;
    return true;
  });
  const ConnectorParts parts = build_connectors(f, parameters(0.08), watching);
  EXPECT_EQ(parts.templates.size(), 4u);
  EXPECT_DOUBLE_EQ(last, 1.0);
}

}  // namespace
