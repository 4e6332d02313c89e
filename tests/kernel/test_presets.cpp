// Preset unit cells: every lattice a preset builds has exactly the beams a brute force over all pairs of its balls
// finds at the preset's neighbour distance (for FCC, only pairs with a cell corner), each beam that long, every
// node kept inside the box of cells, and the crystal's coordination numbers on interior nodes.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <map>

#include "steady/core/errors.hpp"
#include "steady/lattice/presets.hpp"

namespace steady {
namespace {

struct Expected {
  std::map<int, int> interior_degree;  // node of the basis -> beams at an interior node (the coordination number)
};

// The crystal's coordination numbers, from its geometry (not from the patterns).
const std::map<std::string, Expected> kCoordination = {
    {"cubic", {{{0, 6}}}},
    {"BCC", {{{0, 8}, {1, 8}}}},
    {"FCC", {{{0, 12}, {1, 4}, {2, 4}, {3, 4}}}},  // a corner meets 12 face centres, a face centre its 4 corners
    {"octet", {{{0, 12}, {1, 12}, {2, 12}, {3, 12}}}},
    {"diamond", {{{0, 4}, {4, 4}}}},
    {"Kelvin", {{{0, 4}, {5, 4}}}},
    {"honeycomb", {{{0, 5}, {1, 5}, {2, 5}, {3, 5}}}},  // three in the hexagon plane, two along W
};

TEST(Presets, BeamsAreExactlyTheNeighbourPairsOfTheBalls) {
  const std::array<std::int64_t, 3> cells{3, 3, 3};
  const double size = 2.0;
  for (const std::string& name : preset_names()) {
    const PresetCell& cell = preset_cell(name);
    const Lattice lat = preset_lattice(name, cells, size, 0.1, 0.05);
    const double distance = cell.neighbour_distance * size;
    std::vector<Ball> balls;
    std::vector<NodeId> ids;
    lat.for_each_ball([&](std::int64_t, const NodeId& id, const Ball& b) {
      balls.push_back(b);
      ids.push_back(id);
    });
    // every ball inside the box of whole cells
    const Vec3 box = cell.aspect * size * Vec3(3.0);
    for (const Ball& b : balls)
      for (int a = 0; a < 3; ++a) {
        EXPECT_GE(b.center[a], -1e-12) << name;
        EXPECT_LE(b.center[a], box[a] + 1e-12) << name;
      }
    // brute force over all pairs
    std::int64_t pairs = 0;
    std::vector<int> degree(balls.size(), 0);
    for (std::size_t p = 0; p < balls.size(); ++p)
      for (std::size_t q = p + 1; q < balls.size(); ++q) {
        if (std::abs(glm::length(balls[p].center - balls[q].center) - distance) > 1e-9) continue;
        if (cell.corner_beams_only && ids[p].n != 0 && ids[q].n != 0) continue;
        ++pairs;
        ++degree[p];
        ++degree[q];
      }
    EXPECT_EQ(lat.beam_count(), pairs) << name;
    lat.for_each_beam([&](std::int64_t, const BeamId&, const BeamGeometry& g) {
      EXPECT_NEAR(glm::length(g.end.center - g.start.center), distance, 1e-9) << name;
    });
    // coordination of nodes in the middle cell
    const Expected& expected = kCoordination.at(name);
    for (std::size_t p = 0; p < balls.size(); ++p) {
      if (ids[p].i != 1 || ids[p].j != 1 || ids[p].k != 1) continue;
      const auto it = expected.interior_degree.find(ids[p].n);
      if (it != expected.interior_degree.end()) EXPECT_EQ(degree[p], it->second) << name << " node " << ids[p].n;
    }
  }
}

TEST(Presets, BadRequestsNameTheParameter) {
  auto message = [](const std::function<void()>& f) {
    try {
      f();
    } catch (const InvalidInput& e) {
      return std::string(e.what());
    }
    return std::string("accepted");
  };
  EXPECT_NE(message([] { preset_lattice("gyroid", {1, 1, 1}, 1.0, 0.1, 0.0); }).find("name: unknown preset 'gyroid' (known: cubic"),
            std::string::npos);
  EXPECT_NE(message([] { preset_lattice("BCC", {0, 1, 1}, 1.0, 0.1, 0.0); }).find("cells:"), std::string::npos);
  EXPECT_NE(message([] { preset_lattice("BCC", {1, 1, 1}, 1.0, 0.1, 0.2); }).find("beam_radius:"), std::string::npos);
  EXPECT_NE(message([] { preset_lattice("BCC", {1, 1, 1}, -1.0, 0.1, 0.0); }).find("cell_size:"), std::string::npos);
}

}  // namespace
}  // namespace steady
