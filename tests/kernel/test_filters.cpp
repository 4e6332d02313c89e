// Filters and filtered lattices against brute force: masks follow the filter's definition node by node,
// beams follow their two nodes, Lattice-in-Lattice (and its cascade) keeps exactly the beams whose balls
// both meet the coarse lattice, and filtered queries are the unfiltered answer restricted to the masks.
#include <gtest/gtest.h>

#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepPrimAPI_MakeBox.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepTools.hxx>
#include <BRep_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <cmath>
#include <random>
#include <sstream>

#include "query_oracle.hpp"
#include "sample_lattices.hpp"
#include "steady/brep/body_filter.hpp"
#include "steady/core/errors.hpp"
#include "steady/query/filtered_lattice.hpp"
#include "steady/query/interference.hpp"

namespace steady {
namespace {

std::vector<std::uint8_t> balls_of(const FilteredLattice& f) {
  std::vector<std::uint8_t> m(static_cast<std::size_t>(f.lattice().ball_count()));
  f.ball_mask(m.data());
  return m;
}
std::vector<std::uint8_t> beams_of(const FilteredLattice& f) {
  std::vector<std::uint8_t> m(static_cast<std::size_t>(f.lattice().beam_count()));
  f.beam_mask(m.data());
  return m;
}

// Checks that beams are kept exactly when both end balls are, and returns the kept counts.
std::pair<long, long> check_beams_follow_balls(const FilteredLattice& f) {
  const auto balls = balls_of(f), beams = beams_of(f);
  const Lattice& lat = f.lattice();
  long kb = 0, kbeam = 0;
  for (auto x : balls) kb += x;
  lat.for_each_beam([&](std::int64_t index, const BeamId& id, const BeamGeometry&) {
    const bool expect = balls[lat.ball_index(lat.beam_start(id))] && balls[lat.ball_index(lat.beam_end(id))];
    EXPECT_EQ(beams[index] != 0, expect) << index;
    kbeam += beams[index];
  });
  return {kb, kbeam};
}

TEST(Filters, IndexStencil) {
  const Lattice lat = test::regular_bcc({5, 4, 3});
  // Keep groups whose (i mod 2, j mod 3, k mod 1) cell is set.
  std::vector<std::uint8_t> cells = {1, 0, 1, 0, 1, 1};
  auto f = std::make_shared<FilteredLattice>(lat, index_stencil(cells, 2, 3, 1));
  const auto balls = balls_of(*f);
  lat.for_each_ball([&](std::int64_t index, const NodeId& id, const Ball&) {
    EXPECT_EQ(balls[index], cells[static_cast<std::size_t>((id.i % 2) * 3 + id.j % 3)]);
  });
  const auto [kb, kbeam] = check_beams_follow_balls(*f);
  EXPECT_GT(kb, 0);
  EXPECT_GT(kbeam, 0);
  EXPECT_THROW(index_stencil({1, 0}, 2, 2, 1), InvalidInput);
}

// Brute-force interference of a ball with every kept element of a (filtered) lattice.
struct KeptElements : test::BruteForceQuery {
  explicit KeptElements(const FilteredLattice& f)
      : test::BruteForceQuery(f.lattice(), balls_of(f).data(), beams_of(f).data()) {}
};

TEST(Filters, LatticeInLatticeAndCascade) {
  const Lattice fine = test::regular_bcc({9, 9, 9}, 0.5);
  auto coarse = std::make_shared<FilteredLattice>(
      Lattice::incremental({{{0, 0, 0}, 0.5}}, test::cubic_patterns(), {3, 3, 3}, Similarity::translation({2, 0, 0}),
                           Similarity::translation({0, 2, 0}), Similarity::translation({0, 0, 2})));
  auto lil = std::make_shared<FilteredLattice>(fine, lattice_in_lattice(coarse));
  const auto balls = balls_of(*lil);
  const KeptElements coarse_elements(*coarse);
  long kept = 0;
  fine.for_each_ball([&](std::int64_t x, const NodeId&, const Ball& b) {
    EXPECT_EQ(balls[x] != 0, coarse_elements.meets(b)) << x;
    kept += balls[x];
  });
  EXPECT_GT(kept, 50);
  EXPECT_LT(kept, fine.ball_count());
  check_beams_follow_balls(*lil);
  // Queries on the LiL filter each hit with a query on the coarse lattice, nested in the fine query:
  // the answer must still be the unfiltered one restricted to the masks.
  {
    const auto beams = beams_of(*lil);
    const LatticeQuery plain(fine);
    int nonempty = 0;
    for (std::int64_t x = 0; x < fine.ball_count(); x += 5) {
      const Ball q{fine.ball(fine.ball_id(x)).center, 0.3};
      for (QueryMethod m : {QueryMethod::Auto, QueryMethod::Rows, QueryMethod::Blocks, QueryMethod::Slabs}) {
        const BallQueryResult all = plain.query_ball(q, m), got = FilteredLattice(fine, lattice_in_lattice(coarse), m).query_ball(q);
        BallQueryResult expect;
        for (auto b : all.balls)
          if (balls[b]) expect.balls.push_back(b);
        for (auto b : all.beams)
          if (beams[b]) expect.beams.push_back(b);
        EXPECT_EQ(got.balls, expect.balls) << x;
        EXPECT_EQ(got.beams, expect.beams) << x;
        nonempty += !expect.beams.empty();
      }
    }
    EXPECT_GT(nonempty, 20);
  }
  // Cascade: a finer lattice inside the LiL (materialized, so it is looked up rather than re-filtered).
  lil->materialize();
  const Lattice finer = test::regular_bcc({17, 17, 17}, 0.25);
  auto cascade = std::make_shared<FilteredLattice>(finer, lattice_in_lattice(lil));
  const auto fb = balls_of(*cascade);
  const KeptElements lil_elements(*lil);
  long kept2 = 0;
  finer.for_each_ball([&](std::int64_t x, const NodeId&, const Ball& b) {
    EXPECT_EQ(fb[x] != 0, lil_elements.meets(b)) << x;
    kept2 += fb[x];
  });
  EXPECT_GT(kept2, 50);
  check_beams_follow_balls(*cascade);
}

TEST(Filters, FilteredQueriesAreMaskedQueries) {
  std::mt19937_64 rng(4);
  const Lattice lat = test::bent_twisted_tapered({6, 6, 6});
  auto f = std::make_shared<FilteredLattice>(lat, gyroid(3.0, 0.6));
  const auto balls = balls_of(*f), beams = beams_of(*f);
  const LatticeQuery plain(lat);
  int nonempty = 0;
  for (int q = 0; q < 400; ++q) {
    const Ball e = lat.ball(lat.ball_id(static_cast<std::int64_t>(rng() % lat.ball_count())));
    const Ball query{e.center + test::random_vec(rng, 0.6), 0.5};
    const BallQueryResult all = plain.query_ball(query), got = f->query_ball(query);
    BallQueryResult expect;
    for (auto x : all.balls)
      if (balls[x]) expect.balls.push_back(x);
    for (auto x : all.beams)
      if (beams[x]) expect.beams.push_back(x);
    EXPECT_EQ(got.balls, expect.balls);
    EXPECT_EQ(got.beams, expect.beams);
    nonempty += !expect.balls.empty();
  }
  EXPECT_GT(nonempty, 50);
  // The gyroid definition node by node.
  lat.for_each_ball([&](std::int64_t x, const NodeId&, const Ball& b) {
    const Vec3 p = b.center * (2 * kPi / 3.0);
    const double g = std::sin(p.x) * std::cos(p.y) + std::sin(p.y) * std::cos(p.z) + std::sin(p.z) * std::cos(p.x);
    EXPECT_EQ(balls[x] != 0, std::abs(g) <= 0.6);
  });
}

std::string brep_text(const TopoDS_Shape& s) {
  std::ostringstream os;
  BRepTools::Write(s, os);
  return os.str();
}

TEST(Filters, InsideBodyCallableAndBrep) {
  const Lattice lat = test::regular_bcc({6, 6, 6});
  // A sphere of radius 2.2 about (2.5, 2.5, 2.5): as a callable, and as an OpenCASCADE solid.
  const Vec3 c(2.5, 2.5, 2.5);
  auto sphere = inside(
      [c](const double* p, std::size_t n, std::uint8_t* in) {
        for (std::size_t q = 0; q < n; ++q) in[q] = glm::length(Vec3(p[3 * q], p[3 * q + 1], p[3 * q + 2]) - c) <= 2.2;
      },
      true);
  auto solid = inside_brep(brep_text(BRepPrimAPI_MakeSphere(gp_Pnt(2.5, 2.5, 2.5), 2.2).Shape()));
  const auto a = balls_of(FilteredLattice(lat, sphere));
  const auto b = balls_of(FilteredLattice(lat, solid));
  long kept = 0, agree = 0;
  lat.for_each_ball([&](std::int64_t x, const NodeId&, const Ball& ball) {
    const double d = glm::length(ball.center - c);
    if (std::abs(d - 2.2) > 1e-3) {  // away from the faceted-free but toleranced boundary
      EXPECT_EQ(a[x], b[x]) << x;
      agree += a[x] == b[x];
    }
    kept += a[x];
  });
  EXPECT_GT(kept, 20);
  EXPECT_GT(agree, 300);
  // Combinations: inside the sphere and not inside the box [0,2]^3.
  auto box = inside_brep(brep_text(BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(2, 2, 2)).Shape()));
  const auto both = balls_of(FilteredLattice(lat, all_of({sphere, negate(box)})));
  const auto either = balls_of(FilteredLattice(lat, any_of({sphere, box})));
  const auto in_box = balls_of(FilteredLattice(lat, box));
  for (std::size_t x = 0; x < both.size(); ++x) {
    EXPECT_EQ(both[x], a[x] && !in_box[x]);
    EXPECT_EQ(either[x], a[x] || in_box[x]);
  }
}

TEST(Filters, InsideABodyOfSeveralSolidsIsTheirUnion) {
  // Issue 16: a compound of two overlapping boxes keeps a node inside either (not only the first, not an exclusive
  // or): the same nodes as any_of the two boxes as separate bodies. A face beside the solids is refused.
  const Lattice lat = test::regular_bcc({6, 6, 6});
  const TopoDS_Shape a = BRepPrimAPI_MakeBox(gp_Pnt(0, 0, 0), gp_Pnt(3, 3, 3)).Shape();
  const TopoDS_Shape b = BRepPrimAPI_MakeBox(gp_Pnt(2, 2, 2), gp_Pnt(5, 5, 5)).Shape();
  TopoDS_Compound both;
  BRep_Builder builder;
  builder.MakeCompound(both);
  builder.Add(both, a);
  builder.Add(both, b);
  const auto united = balls_of(FilteredLattice(lat, inside_brep(brep_text(both))));
  const auto in_a = balls_of(FilteredLattice(lat, inside_brep(brep_text(a))));
  const auto in_b = balls_of(FilteredLattice(lat, inside_brep(brep_text(b))));
  long only_a = 0, only_b = 0, kept = 0;
  for (std::size_t x = 0; x < united.size(); ++x) {
    EXPECT_EQ(united[x], in_a[x] || in_b[x]) << x;
    only_a += in_a[x] && !in_b[x];
    only_b += in_b[x] && !in_a[x];
    kept += united[x];
  }
  EXPECT_GT(only_a, 0);
  EXPECT_GT(only_b, 0);
  EXPECT_GT(kept, only_a + only_b);  // some nodes are in both
  builder.Add(both, BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(10, 10, 10), gp_Dir(0, 0, 1)), 0, 1, 0, 1).Face());
  try {
    inside_brep(brep_text(both));
    ADD_FAILURE() << "a face beside the solids was accepted";
  } catch (const InvalidInput& e) {
    EXPECT_EQ(std::string(e.what()).rfind("body: holds 1 faces outside its solids", 0), 0u) << e.what();
  }
}

// A filter extended one operator at a time in a loop (f = f & g) used to nest once per step and overflow the
// stack when evaluated or described past ~30,000 steps (issue 16, repro 15). Chains of one operator do not
// nest; genuine nesting is refused past kMaxFilterNesting with a message saying what to do instead.
TEST(Filters, LongChainsEvaluateAndDeepNestingIsRefused) {
  const Lattice lat = test::regular_bcc({6, 6, 6});
  const FilterPtr g = gyroid(3.0, 0.4);
  const FilterPtr keep_all = index_stencil({1}, 1, 1, 1);
  FilterPtr chain = g;
  for (int q = 0; q < 100000; ++q) chain = all_of({chain, keep_all});
  EXPECT_EQ(chain->nesting(), 2);
  std::vector<std::uint8_t> a(static_cast<std::size_t>(lat.ball_count())), b(a.size());
  FilteredLattice(lat, chain).ball_mask(a.data());
  FilteredLattice(lat, g).ball_mask(b.data());
  EXPECT_EQ(a, b);
  EXPECT_GT(std::count(a.begin(), a.end(), 1), 0);
  EXPECT_EQ(chain->describe().rfind("(gyroid", 0), 0u);
  chain.reset();  // destroyed by iteration, not recursion
  FilterPtr nested = g;
  std::string refusal;
  try {
    for (int q = 0; q < 2000; ++q) nested = q % 2 ? any_of({all_of({nested, keep_all}), keep_all}) : negate(nested);
  } catch (const InvalidInput& e) {
    refusal = e.what();
  }
  EXPECT_NE(refusal.find("levels deep (at most 1000)"), std::string::npos) << refusal;
  EXPECT_LE(nested->nesting(), kMaxFilterNesting);
}

TEST(Filters, BadBodies) {
  EXPECT_THROW(inside_brep("not a brep"), InvalidInput);
  const TopoDS_Shape face = BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)), -1, 1, -1, 1).Shape();
  try {
    inside_brep(brep_text(face));
    ADD_FAILURE() << "a face is not a solid";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("body"), std::string::npos);
  }
  EXPECT_THROW(gyroid(-1.0, 0.5), InvalidInput);
  EXPECT_THROW(lattice_in_lattice(nullptr), InvalidInput);
  EXPECT_THROW(all_of({}), InvalidInput);
}

}  // namespace
}  // namespace steady
