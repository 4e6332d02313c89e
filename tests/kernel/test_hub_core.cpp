// Hub cores (crowded hubs and the hull model): each core closed by disks at its collars must be a valid solid
// whose volume (BRepGProp) matches an independent quadrature of the hub's radial function; lattices built from
// cores must be valid solids whose volume is the cores' quadrature plus the beams' frustums between collars.
#include <gtest/gtest.h>

#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom_Circle.hxx>
#include <Geom_Plane.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Wire.hxx>

#include <random>

#include "steady/lattice/beam_frustum.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/presets.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "brep/hub_core.hpp"
#include "lattice/circle_frames.hpp"
#include "lattice/hub_collars.hpp"
#include "steady/brep/trim.hpp"
#include "test_support.hpp"
#include "brick_definition.hpp"
#include "sample_lattices.hpp"

namespace steady {
namespace {

CoreStump hull_stump(const Vec3& d, double sin_phi) {
  CoreStump s;
  s.direction = glm::normalize(d);
  s.sin_phi = sin_phi;
  s.end_radius = 1.0;
  s.exit = sin_phi;  // the tangent circle
  return s;
}

// A hub's stumps in its canonical frame as a failing case printed them, all of one end radius.
struct StumpRecord {
  Vec3 direction;
  double sin_phi, exit;
};
std::vector<CoreStump> stumps_of(const std::vector<StumpRecord>& hub, double end_radius) {
  std::vector<CoreStump> stumps;
  for (const StumpRecord& h : hub) {
    CoreStump s;
    s.direction = h.direction;
    s.sin_phi = h.sin_phi;
    s.end_radius = end_radius;
    s.exit = h.exit;
    stumps.push_back(s);
  }
  return stumps;
}

// The quadrature converges fast where faces meet tangentially (the hull model: 1e-6 at 1200) and only to first
// order across transversal kinks (sphere and thinner stumps: ~1e-4 at 2400).
void expect_core(const std::vector<CoreStump>& stumps, CoreKind kind, const std::string& what) {
  const std::vector<double> collars = place_collars(stumps, kind, 50.0);
  const auto core = build_hub_core(stumps, kind, collars);
  const TopoDS_Shape solid = closed_core(*core);
  EXPECT_TRUE(is_valid(solid)) << what << ":\n" << validity_report(solid);
  const bool hull = kind == CoreKind::Hull;
  const double expected = core_volume_by_quadrature(stumps, collars, hull ? 1000 : 2000);
  EXPECT_NEAR(shape_volume(solid) / expected, 1.0, hull ? 2e-5 : 5e-4) << what;
}

// StumpReach::beyond_ball answers a direction by one dot product below the exit circle's cos; wherever the full
// reach exceeds the ball (the only case a hub's piece depends on) it must give that reach, and 0 or at most 1
// elsewhere. Random stumps: tapering both ways, thin to tangent (the hull model's end radius 1), directions drawn
// evenly and within 1e-7 of the exit circle, where a wrong threshold would show first.
TEST(StumpReach, BeyondTheBallAsTheFullReach) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(-1.0, 1.0), slope(-0.3, 0.3), radius(0.2, 1.0), near(-1e-7, 1e-7);
  auto random_direction = [&] {
    Vec3 d;
    do d = Vec3(unit(rng), unit(rng), unit(rng));
    while (glm::length(d) < 0.1 || glm::length(d) > 1.0);
    return glm::normalize(d);
  };
  int beyond = 0, checked = 0;
  for (int trial = 0; trial < 200; ++trial) {
    CoreStump s;
    s.direction = random_direction();
    s.sin_phi = slope(rng);
    s.end_radius = trial % 5 == 0 ? 1.0 : radius(rng);
    const double exit_k = std::cos(std::asin(s.end_radius) - std::asin(s.sin_phi));  // where the cone meets the sphere
    const StumpReach reach(s, 1.5 + 2.0 * (0.5 + 0.5 * unit(rng)));
    const Vec3 u = any_perpendicular(s.direction), v = glm::cross(s.direction, u);
    for (int i = 0; i < 2000; ++i) {
      Vec3 w = random_direction();
      if (i % 2 == 1) {  // on the exit circle, give or take 1e-7 in cos
        const double k = std::clamp(exit_k + near(rng), -1.0, 1.0), t = M_PI * unit(rng);
        w = k * s.direction + std::sqrt(1.0 - k * k) * (std::cos(t) * u + std::sin(t) * v);
      }
      const double full = reach(w), quick = reach.beyond_ball(w);
      ++checked;
      if (full > 1.0) {
        ++beyond;
        ASSERT_EQ(quick, full) << "trial " << trial << ", sin_phi " << s.sin_phi << ", end radius " << s.end_radius
                               << ", cos to the axis " << glm::dot(w, s.direction) << ", exit at " << exit_k;
      } else {
        ASSERT_LE(quick, 1.0) << "trial " << trial;
      }
    }
  }
  EXPECT_GT(beyond, checked / 20);  // the directions beyond the ball are well represented
}

TEST(HubCore, HullModelHubs) {
  const Vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  // Corner of a cubic lattice, equal radii: cylinders meeting in ellipses, an octant of the sphere exposed.
  expect_core({hull_stump(x, 0), hull_stump(y, 0), hull_stump(z, 0)}, CoreKind::Hull, "corner");
  // Interior node of a cubic lattice: six cylinders, no sphere left.
  expect_core({hull_stump(x, 0), hull_stump(-x, 0), hull_stump(y, 0), hull_stump(-y, 0), hull_stump(z, 0),
               hull_stump(-z, 0)},
              CoreKind::Hull, "cubic");
  // Graded: cones narrowing or widening away from the node.
  expect_core({hull_stump(x, 0.2), hull_stump(y, -0.15), hull_stump(z, 0.1), hull_stump(-x - y, 0.05)}, CoreKind::Hull,
              "graded");
  // Body-centred: eight diagonals meeting four at a time.
  std::vector<CoreStump> bcc;
  for (int i = 0; i < 8; ++i) bcc.push_back(hull_stump(Vec3(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1), 0.1));
  expect_core(bcc, CoreKind::Hull, "bcc");
}

TEST(HubCore, RandomHullHubs) {
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int built = 0;
  for (int trial = 0; trial < 14; ++trial) {
    // Random directions at least 40 degrees apart (closer stumps would collide far from the hub, and are refused).
    std::vector<CoreStump> stumps;
    const int n = 2 + trial % 6;
    for (int attempt = 0; attempt < 1000 && static_cast<int>(stumps.size()) < n; ++attempt) {
      const Vec3 d = test::random_unit(rng);
      const double slope = 0.25 * (2 * u01(rng) - 1);
      bool apart = true;
      for (const CoreStump& s : stumps) apart = apart && glm::dot(s.direction, d) < std::cos(40 * M_PI / 180);
      if (apart) stumps.push_back(hull_stump(d, slope));
    }
    try {
      expect_core(stumps, CoreKind::Hull, "random hull hub " + std::to_string(trial));
      ++built;
    } catch (const InvalidInput& e) {
      // Stumps leaving in nearly the same direction are refused with a reason, never built wrong.
      EXPECT_NE(std::string(e.what()).find("hub:"), std::string::npos);
    }
  }
  EXPECT_GE(built, 10);
}

CoreStump thin_stump(const Vec3& d, double sin_phi, double end_radius) {
  CoreStump s;
  s.direction = glm::normalize(d);
  s.sin_phi = sin_phi;
  s.end_radius = end_radius;
  const double c = std::sqrt(1 - sin_phi * sin_phi);
  s.exit = end_radius * sin_phi + c * std::sqrt(1 - end_radius * end_radius);
  return s;
}

TEST(HubCore, TransversalHubs) {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int built = 0;
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<CoreStump> stumps;
    const int n = 3 + trial % 4;
    for (int k = 0; k < n; ++k) {
      const Vec3 d = test::random_unit(rng);
      const double end_radius = 0.4 + 0.3 * u01(rng);
      stumps.push_back(thin_stump(d, 0.1 * (2 * u01(rng) - 1), end_radius));
    }
    try {
      expect_core(stumps, CoreKind::Transversal, "transversal hub " + std::to_string(trial));
      ++built;
    } catch (const InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find("hub:"), std::string::npos);
    }
  }
  EXPECT_GE(built, 3);
}


double frustum_volume(const CoreStump& s, double x0, double x1) {
  const double r0 = s.radius_at(x0), r1 = s.radius_at(x1);
  return M_PI * (x1 - x0) * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
}

// Stumps of one end radius are built without a Boolean (the arrangement with the ball's sphere at exit_v). Twins:
// with place_collars' collars, the Fuse of the ball and the stumps; with the tighter core_collars, the same core
// less the frustums between the two collars of each stump (beyond the tight collars no stump meets another, so
// the difference is exactly those frustums). Volumes agree far tighter than a quadrature could tell. Returns
// whether the arrangement built it (tangent exit caps go to the Fuse).
bool expect_equal_radius_core(const std::vector<CoreStump>& stumps, const std::string& what) {
  const std::vector<double> wide = place_collars(stumps, CoreKind::Transversal, 50.0);
  const auto core = build_hub_core(stumps, CoreKind::Transversal, wide);
  const TopoDS_Shape solid = closed_core(*core);
  EXPECT_TRUE(is_valid(solid)) << what << ":\n" << validity_report(solid);
  const TopoDS_Shape read = brep_from_text(brep_to_text(solid), "core");
  EXPECT_TRUE(is_valid(read)) << what << " (read back from its BREP text):\n" << validity_report(read);
  if (core->fused) return false;
  const double volume = shape_volume(solid);
  EXPECT_NEAR(volume / shape_volume(closed_core(*build_transversal_core(stumps, wide))), 1.0, 1e-7) << what;
  EXPECT_NEAR(volume / core_volume_by_quadrature(stumps, wide, 2000), 1.0, 5e-4) << what;
  const std::vector<double> tight = core_collars(stumps, CoreKind::Transversal, 50.0);
  const auto tight_core = build_hub_core(stumps, CoreKind::Transversal, tight);
  const TopoDS_Shape tight_solid = closed_core(*tight_core);
  EXPECT_TRUE(is_valid(tight_solid)) << what << " (tight collars):\n" << validity_report(tight_solid);
  EXPECT_FALSE(tight_core->fused) << what;
  double between = 0.0;
  for (std::size_t k = 0; k < stumps.size(); ++k) between += frustum_volume(stumps[k], tight[k], wide[k]);
  EXPECT_NEAR((shape_volume(tight_solid) + between) / volume, 1.0, 1e-7) << what;
  return true;
}

std::vector<Vec3> octet_directions() {
  std::vector<Vec3> out;
  for (int axis = 0; axis < 3; ++axis)
    for (int sa = -1; sa <= 1; sa += 2)
      for (int sb = -1; sb <= 1; sb += 2) {
        Vec3 d(0.0);
        d[(axis + 1) % 3] = sa;
        d[(axis + 2) % 3] = sb;
        out.push_back(d);
      }
  return out;
}

TEST(HubCore, EqualEndRadiusHubs) {
  const Vec3 x(1, 0, 0), y(0, 1, 0), z(0, 0, 1);
  for (double rho : {0.45, 0.6, 0.8, 0.95}) {
    const std::string r = " rho " + std::to_string(rho);
    EXPECT_TRUE(expect_equal_radius_core({thin_stump(x, 0, rho), thin_stump(y, 0, rho), thin_stump(z, 0, rho)},
                                         "corner" + r));
    expect_equal_radius_core({thin_stump(x, 0, rho), thin_stump(-x, 0, rho), thin_stump(y, 0, rho),
                              thin_stump(-y, 0, rho), thin_stump(z, 0, rho), thin_stump(-z, 0, rho)},
                             "cubic" + r);
    expect_equal_radius_core({thin_stump(x, 0.2, rho), thin_stump(y, -0.15, rho), thin_stump(z, 0.1, rho),
                              thin_stump(-x - y, 0.05, rho)},
                             "graded" + r);
  }
}

// The dense octet of issue 17: twelve cylinders along the face diagonals, caps overlapping from beam/node 0.5 on;
// slightly turned copies stand in for the hubs of a screwed lattice, whose near-degenerate meetings broke the Fuse.
TEST(HubCore, OctetHubsOfEveryRatio) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> u01(-1.0, 1.0);
  for (double rho : {0.45, 0.5, 0.55, 0.6, 0.64, 0.7, 0.8, 0.9}) {
    for (int jitter = 0; jitter < 2; ++jitter) {
      std::vector<CoreStump> stumps;
      for (const Vec3& d : octet_directions()) {
        const Vec3 turn = jitter ? 0.02 * Vec3(u01(rng), u01(rng), u01(rng)) : Vec3(0.0);
        stumps.push_back(thin_stump(d + turn, 0, rho));
      }
      const std::string what = "octet rho " + std::to_string(rho) + (jitter ? " jittered" : "");
      const bool arranged = expect_equal_radius_core(stumps, what);
      // Caps exactly tangent (rho = sin 30 degrees) are the Fuse's. Overlapping caps are the arrangement's;
      // disjoint ones (rho < 0.5) too where a seam crossing the loops only around its poles (STEP-safe) exists,
      // which the exact octet has and the jittered one not.
      if (rho > 0.5 || (rho < 0.5 && !jitter)) EXPECT_TRUE(arranged) << what;
    }
  }
}

// Issue 17's long sweep, octet at node 0.25 of the neighbour distance, beam/node 0.5, twisted taper: ball 1's
// hub has exit caps exactly tangent (60 degrees apart) and others nearly so (tapered beams). Its arranged core was
// valid in memory but, read back from its BREP text, its sphere's loop touched itself in a cusp the checker found
// self-intersecting: the verdict hung on the 15 digits of the text (cusp_tolerance.hpp). The stumps are that hub's
// in its canonical frame, to the last digit.
TEST(HubCore, TangentCapsCoreSurvivesItsBrepText) {
  const std::vector<StumpRecord> hub = {
      {{0, 0, 1}, 0.0, 0.86602540378443815},
      {{1, 0, 0}, 0.0, 0.86602540378443815},
      {{-0.99835218437901463, 0.056686281661593008, 0.0089208417221931496}, -0.0061839458916051115, 0.86291687176070908},
      {{-0.0090826190625096798, 0.057714273880839717, -0.99829182538042105}, -0.0062960902777682926, 0.86286019352597454},
      {{-0.50000000000000011, -0.70710678118654757, 0.5}, 0.0, 0.86602540378443815},
      {{0.50000000000000011, -0.70710678118654757, -0.5}, 0.0, 0.86602540378443815},
      {{0.50000000000000011, -0.70710678118654757, 0.5}, 0.0, 0.86602540378443815},
      {{-0.50000000000000056, -0.70710678118654702, -0.50000000000000044}, -0.0062499999999999821, 0.86288348906058665}};
  const std::vector<CoreStump> stumps = stumps_of(hub, 0.50000000000000011);
  const auto core = build_hub_core(stumps, CoreKind::Transversal,
                                   core_collars(stumps, CoreKind::Transversal, kMaxCollarPosition));
  const TopoDS_Shape solid = closed_core(*core);
  ASSERT_TRUE(is_valid(solid)) << validity_report(solid);
  const TopoDS_Shape read = brep_from_text(brep_to_text(solid), "core");
  EXPECT_TRUE(is_valid(read)) << validity_report(read);
  EXPECT_NEAR(shape_volume(read) / shape_volume(solid), 1.0, 1e-12);
}

// A hub of the 3 x 3 x 3 dense octet at beam/node 0.9 with a screw of 0.01 rad a layer (bench_crowded_hubs), in its
// canonical frame to the last digit. Four of its cylinders meet at one point in the exact octet; the screw splits
// that point, and on two cylinders a neighbour stayed active for less than the vertex tolerance. That piece, an arc
// from a vertex back to itself, was made the whole ellipse: a wire running around its cylinder twice (negative
// area), so the core went to the Fuse (6 s instead of 0.01 s). Such pieces are dropped (cone_envelope.cpp).
TEST(HubCore, NeighbourActiveForLessThanTheVertexToleranceLeavesNoEdge) {
  const std::vector<Vec3> directions = {
      {0, 0, 1},
      {0.8660254037844386, 0, 0.50000000000000022},
      {0.28867513459481298, -0.81649658092772626, 0.49999999999999983},
      {0.57735026918962573, 0.81649658092772603, -5.5511151231257827e-17},
      {-0.57735026918962573, -0.81649658092772603, -4.4408920985006262e-16},
      {1.1102230246251565e-16, 1.1102230246251565e-16, -1},
      {-0.28001632685381056, 0.82855831539336955, 0.48485252880417307},
      {0.28867513459481281, -0.81649658092772592, -0.50000000000000022},
      {-0.8631099801266584, 0.0040617995359694126, -0.50499966731700829},
      {-0.86599580466683013, 0.012349703607385853, 0.4998987408668471},
      {0.86602540378443882, -5.5511151231257839e-17, -0.5},
      {-0.2829878913276106, 0.81235413782876043, -0.50990058650137304}};
  std::vector<CoreStump> stumps;
  for (const Vec3& d : directions) {
    CoreStump s;
    s.direction = d;
    s.end_radius = 0.90000000000000002;
    s.exit = std::sqrt(1.0 - s.end_radius * s.end_radius);
    stumps.push_back(s);
  }
  const auto core = build_hub_core(stumps, CoreKind::Transversal,
                                   core_collars(stumps, CoreKind::Transversal, kMaxCollarPosition));
  EXPECT_FALSE(core->fused);
  const TopoDS_Shape solid = closed_core(*core);
  EXPECT_TRUE(is_valid(solid)) << validity_report(solid);
}

// Beams as thick as their nodes (beam/node 1.0) give the hull model, but a taper or a screw computes their end
// radius as 1 plus rounding. The arrangement took it for a ball of radius 1 / (1 + 2e-16) < 1, which the cones
// leave at v = sqrt(negative): NaN everywhere, and "a stump is swallowed by its neighbours up to its collar"
// (issue 17's long sweep: FCC and octet at node 0.25, beam/node 1.0, every kind of step).
TEST(HubCore, TangentBeamsRoundedAboveTheBallRadiusAreTheHullModel) {
  for (double rounding : {0.0, 2.2e-16, 1e-13}) {
    std::vector<CoreStump> stumps;
    for (const Vec3& d : octet_directions()) {
      CoreStump s = hull_stump(d, 0.0);
      s.end_radius = 1.0 + rounding;
      stumps.push_back(s);
    }
    const auto core =
        build_hub_core(stumps, CoreKind::Hull, core_collars(stumps, CoreKind::Hull, kMaxCollarPosition));
    const TopoDS_Shape solid = closed_core(*core);
    EXPECT_TRUE(is_valid(solid)) << "end radius 1 + " << rounding << ":\n" << validity_report(solid);
  }
}

// Issue 17's long sweep, octet at node 0.45 of the neighbour distance, beam/node 0.5, twisted taper: the exit caps
// are exactly tangent (60 degrees apart, beam/node sin 30 degrees) and the tapered stumps widen, so the arrangement
// refuses the hub and the Fuse builds it. OpenCASCADE's Fuse split the collar disk of stump 3 at 1.02 (with both
// sets of collars tried then) and left it whole 6 % farther out. The stumps are that hub's to the last digit.
TEST(HubCore, FuseThatSplitsACollarIsRetriedWithCollarsFartherOut) {
  const std::vector<StumpRecord> hub = {
      {{1.1102230246251568e-16, 0, 1}, -0.0, 0.86602540378443837},
      {{0.86602540378443882, 0, 0.5}, -0.0, 0.86602540378443837},
      {{-0.57735026918962584, -0.81649658092772615, 0}, 0, 0.8660254037844386},
      {{0.56687266131181591, 0.82288640816193248, 0.03890173671718445}, -0.010802995713489893, 0.86057336982863464},
      {{0.013513078795983239, 0.042105248392565249, -0.99902179393607526}, -0.011713526605891776, 0.86010922619712626},
      {{0.28867513459481287, -0.81649658092772615, -0.5}, 0, 0.8660254037844386},
      {{0.28867513459481298, -0.81649658092772615, 0.5}, 0, 0.86602540378443837},
      {{0.8660254037844386, 7.2164496600635195e-16, -0.50000000000000044}, -0.01125, 0.86034559888023887}};
  const std::vector<CoreStump> stumps = stumps_of(hub, 0.5);
  const std::vector<double> asked = core_collars(stumps, CoreKind::Transversal, kMaxCollarPosition);
  const auto core = build_hub_core(stumps, CoreKind::Transversal, asked);
  EXPECT_TRUE(core->fused);
  EXPECT_GT(core->collar_position[3], asked[3]);  // the collars it used lie farther out
  const TopoDS_Shape solid = closed_core(*core);
  EXPECT_TRUE(is_valid(solid)) << validity_report(solid);
}

// A hull-model lattice (no beam radii): every hub is a core; the volume is the cores' quadratures plus the
// frustums between the collars.
TEST(HubCore, HullModelLatticeTrimsAndSkins) {
  // Cores near the body's boundary go through the trimming Booleans like any hub.
  test::BrickDefinition d;
  d.nodes = {{{0, 0, 0}, 0.22}};
  d.beams = {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}};
  d.counts = {5, 5, 5};
  d.u = {Similarity::translation({1, 0, 0})};
  d.v = {Similarity::translation({0, 1, 0})};
  d.w = {Similarity::translation({0, 0, 1})};
  const FlatLattice f = flatten(Lattice(d));
  // (A sphere centred on the lattice's middle node passes through its symmetric boundary nodes exactly where four
  // cylinders touch the ball at one point; OpenCASCADE's Cut then fails: see docs/brep.md.)
  const TopoDS_Shape body = BRepPrimAPI_MakeSphere(gp_Pnt(2.1, 1.93, 2.04), 2.27).Shape();
  for (double skin : {0.0, 0.25}) {
    TrimOptions o;
    o.skin = skin;
    const TrimResult r = trim_lattice(f, body, o);
    EXPECT_TRUE(is_valid(r.part)) << "skin " << skin << ":\n" << validity_report(r.part);
    EXPECT_EQ(solid_count(r.part), 1) << "skin " << skin;
    EXPECT_GT(shape_volume(r.part), 0.0);
  }
}

TEST(HubCore, HullModelLatticeIsOneValidSolid) {
  for (int graded = 0; graded < 2; ++graded) {
    test::BrickDefinition d;
    d.nodes = {{{0, 0, 0}, 0.25}};
    d.beams = {{0, 1, 0, 0, 0}, {0, 0, 1, 0, 0}, {0, 0, 0, 1, 0}};
    d.counts = {3, 3, 3};
    d.u = {graded ? Similarity::swirl(0.05, {0, 0, 1}, {0, 20, 0}, 1.002) : Similarity::translation({1, 0, 0})};
    d.v = {Similarity::translation({0, 1, 0})};
    d.w = {Similarity::translation({0, 0, 1})};
    const FlatLattice f = flatten(Lattice(d));
    const LatticeBrep b = build_lattice_brep(f);
    EXPECT_TRUE(is_valid(b.shape)) << validity_report(b.shape);
    EXPECT_EQ(solid_count(b.shape), 1);
    EXPECT_EQ(b.stats.core_hubs, f.ball_count());
    if (!graded) EXPECT_LE(b.stats.distinct_cores, 27);
    // Expected volume: per hub the core up to its collars (quadrature), per beam the frustum between collars.
    const std::vector<BeamFrustum> frustums = beam_frustums(f);
    double expected = 0.0;
    std::vector<std::vector<double>> collar_of(f.ball_count());
    std::vector<std::vector<std::int64_t>> beam_of(f.ball_count());
    for (std::int64_t i = 0; i < f.ball_count(); ++i) {
      const Ball& ball = f.balls[i];
      std::vector<CoreStump> stumps;
      for (const std::int64_t* e = f.incident_begin(i); e != f.incident_end(i); ++e) {
        const BeamFrustum& fr = frustums[*e];
        const bool at_a = f.beams[*e].a == i;
        CoreStump s;
        s.direction = at_a ? fr.cone.axis : -fr.cone.axis;
        s.sin_phi = at_a ? fr.cone.sin_phi : -fr.cone.sin_phi;
        s.end_radius = 1.0;
        s.exit = s.sin_phi;
        stumps.push_back(s);
        beam_of[i].push_back(*e);
      }
      const std::vector<double> collars = place_collars(stumps, CoreKind::Hull, 50.0);
      collar_of[i] = collars;
      expected += core_volume_by_quadrature(stumps, collars, 800) * std::pow(ball.radius, 3);
    }
    for (std::int64_t e = 0; e < f.beam_count(); ++e) {
      const BeamFrustum& fr = frustums[e];
      auto collar_at = [&](std::int64_t ball) {
        const auto& beams = beam_of[ball];
        const std::size_t k = std::find(beams.begin(), beams.end(), e) - beams.begin();
        return collar_of[ball][k] * f.balls[ball].radius;
      };
      const double x0 = collar_at(f.beams[e].a), x1 = fr.cone.length - collar_at(f.beams[e].b);
      const double r0 = fr.cone.radius_at(x0), r1 = fr.cone.radius_at(x1);
      expected += M_PI * (x1 - x0) * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
    }
    EXPECT_NEAR(shape_volume(b.shape) / expected, 1.0, 2e-5) << (graded ? "graded" : "cubic");
  }
}

// A BCC node whose 8 cylinders (the hull model: beams as thick as the ball) leave along (+-1, +-1, +-1): two
// cylinders 70.53 degrees apart meet in an ellipse reaching cot(35.26 deg) = sqrt(2) ball radii along each axis,
// the envelope's top. Roomy collars sit 0.04 beyond it, tight ones kTightCollarMargin; the arrangement accepts the
// tight ones only with their own clearance, and the core it builds encloses the quadrature's volume.
TEST(HubCore, TightCollarsSitJustBeyondTheEnvelope) {
  std::vector<CoreStump> stumps;
  for (int k = 0; k < 8; ++k)
    stumps.push_back(hull_stump(Vec3(k & 1 ? 1 : -1, k & 2 ? 1 : -1, k & 4 ? 1 : -1), 0.0));
  const std::vector<double> roomy = core_collars(stumps, CoreKind::Hull, kMaxCollarPosition);
  const std::vector<double> tight = core_collars(stumps, CoreKind::Hull, kMaxCollarPosition, CollarFit::Tight);
  // The envelope is sampled at 256 generators and its breakpoints: its peak between them is missed by < 1e-3.
  for (std::size_t k = 0; k < stumps.size(); ++k) {
    EXPECT_NEAR(roomy[k], std::sqrt(2.0) + 2.0 * hull::kCollarClearance, 1e-3) << k;
    EXPECT_NEAR(tight[k], std::sqrt(2.0) + kTightCollarMargin, 1e-3) << k;
  }
  EXPECT_THROW(build_hub_core(stumps, CoreKind::Hull, tight), InvalidInput);  // checked with roomy clearance
  const auto core = build_hub_core(stumps, CoreKind::Hull, tight, CollarFit::Tight);
  const TopoDS_Shape solid = closed_core(*core);
  EXPECT_TRUE(is_valid(solid)) << validity_report(solid);
  EXPECT_NEAR(shape_volume(solid) / core_volume_by_quadrature(stumps, tight, 1000), 1.0, 2e-5);
}

// Issue 17's long sweep refused BCC lattices whose beams are as thick as their nodes (node 0.35 of the neighbour
// distance): roomy collars need 1.018 of each half beam, the stumps' envelopes 0.990. The beams' hubs get tight
// cores and the lattice is one valid solid of the exact volume; hubs whose beams fit keep their roomy cores.
TEST(HubCore, BeamsTooShortForRoomyCollarsBuildWithTightOnes) {
  const double node = 0.35 * 0.5 * std::sqrt(3.0);
  std::vector<BeamPattern> diagonals;
  for (const BeamPattern& p : test::bcc_patterns())
    if (p.from != p.to) diagonals.push_back(p);
  ASSERT_EQ(diagonals.size(), 8u);
  for (bool thinner_corners : {false, true}) {
    std::vector<BeamPattern> beams = diagonals;
    for (BeamPattern& p : beams) p.from_radius = p.to_radius = node;
    const double corner = thinner_corners ? 0.8 * node : node;  // the corners' beams then narrow toward them
    for (BeamPattern& p : beams) (p.from == 0 ? p.from_radius : p.to_radius) = corner;
    const Lattice lattice = Lattice::incremental({{{0, 0, 0}, node}, {{0.5, 0.5, 0.5}, node}}, beams, {2, 2, 2},
                                                 Similarity::translation({1, 0, 0}), Similarity::translation({0, 1, 0}),
                                                 Similarity::translation({0, 0, 1}));
    const LatticeBrep b = build_lattice_brep(flatten(lattice));
    EXPECT_TRUE(is_valid(b.shape)) << validity_report(b.shape);
    EXPECT_EQ(solid_count(b.shape), 1);
    if (!thinner_corners) EXPECT_GT(b.stats.tight_cores, 0);
    EXPECT_LE(b.stats.tight_cores, b.stats.distinct_cores);
    EXPECT_NEAR(shape_volume(b.shape) / lattice_properties(lattice).volume, 1.0, 1e-7)
        << "tight cores " << b.stats.tight_cores << " of " << b.stats.distinct_cores;
  }
}

// The sweep's octet at node 0.35 of the neighbour distance, beam/node 0.8, a slight screw along W (the sweep's
// "screw" step): the neighbours at each end of some beams meet them past the other hub's collar, even a tight one.
Lattice screwed_octet(double ratio) {
  const PresetCell& cell = preset_cell("octet");
  const double node = 0.35 * cell.neighbour_distance;
  std::vector<TemplateNode> nodes;
  for (const Vec3& b : cell.basis) nodes.push_back({b, node});
  std::vector<BeamPattern> beams = preset_beam_patterns(cell);
  for (BeamPattern& p : beams) p.from_radius = p.to_radius = node * ratio;
  return Lattice::incremental(nodes, beams, {2, 2, 2}, Similarity::translation({1, 0, 0}),
                              Similarity::translation({0, 1, 0}),
                              Similarity::screw(0.03, {0, 0, 1}, {0.5, 0.5, 0}, 1.0));
}

// Hubs joined by beams too short even for tight collars are built as one (hub_group.hpp): the lattice is one
// valid solid whose volume is the exact properties' (which unite those hubs by their own Fuse, of other pieces)
// and, as the slow twin, OpenCASCADE's Fuse of every ball and beam cylinder, 5.181725751 (FreeCAD 0.20, once).
TEST(HubCore, HubsJoinedByBeamsTooShortForTheirCollarsAreBuiltAsOne) {
  const Lattice lattice = screwed_octet(0.8);
  const LatticeBrep b = build_lattice_brep(flatten(lattice));
  EXPECT_TRUE(is_valid(b.shape)) << validity_report(b.shape);
  EXPECT_EQ(solid_count(b.shape), 1);
  EXPECT_GT(b.stats.hub_groups, 0);
  EXPECT_GE(b.stats.grouped_hubs, 2 * b.stats.hub_groups);
  const double exact = lattice_properties(lattice).volume;
  EXPECT_NEAR(shape_volume(b.shape) / exact, 1.0, 1e-7) << b.stats.grouped_hubs << " hubs in " << b.stats.hub_groups;
  EXPECT_NEAR(exact, 5.181725751, 1e-6);
}

}  // namespace
}  // namespace steady
