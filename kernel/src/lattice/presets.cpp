#include "steady/lattice/presets.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "steady/core/errors.hpp"

namespace steady {
namespace {

// Positions are exact multiples of 1/12 (Kelvin's quarters, honeycomb's thirds): any tolerance well below those
// separates neighbours from the next shell.
constexpr double kDistanceTolerance = 1e-9;

std::vector<PresetCell> make_presets() {
  const Vec3 corner(0.0), body(0.5);
  const std::vector<Vec3> faces = {{0.5, 0.5, 0.0}, {0.5, 0.0, 0.5}, {0.0, 0.5, 0.5}};
  std::vector<Vec3> fcc = {corner};
  fcc.insert(fcc.end(), faces.begin(), faces.end());
  std::vector<Vec3> diamond = fcc;
  for (const Vec3& p : fcc) diamond.push_back(p + Vec3(0.25));
  // Kelvin foam (truncated octahedra packed body-centred): the permutations of (0, 1/4 or 3/4, 1/2).
  std::set<std::tuple<double, double, double>> kelvin_set;
  for (double q : {0.25, 0.75}) {
    std::array<double, 3> v = {0.0, q, 0.5};
    std::sort(v.begin(), v.end());
    do kelvin_set.insert({v[0], v[1], v[2]});
    while (std::next_permutation(v.begin(), v.end()));
  }
  std::vector<Vec3> kelvin;
  for (const auto& [x, y, z] : kelvin_set) kelvin.push_back({x, y, z});
  // Honeycomb: hexagons of edge 1 in a rectangular cell 3 x sqrt(3), stacked along W at distance 1.
  const std::vector<Vec3> honeycomb = {{0.0, 0.0, 0.0}, {1.0 / 3.0, 0.0, 0.0}, {0.5, 0.5, 0.0}, {5.0 / 6.0, 0.5, 0.0}};
  return {
      {"cubic", {corner}, Vec3(1.0), 1.0, false},                         // edges of the cube
      {"BCC", {corner, body}, Vec3(1.0), std::sqrt(3.0) / 2.0, false},    // body diagonals
      {"FCC", fcc, Vec3(1.0), std::sqrt(2.0) / 2.0, true},                // face diagonals
      {"octet", fcc, Vec3(1.0), std::sqrt(2.0) / 2.0, false},             // 12 nearest neighbours
      {"diamond", diamond, Vec3(1.0), std::sqrt(3.0) / 4.0, false},       // 4 nearest neighbours
      {"Kelvin", kelvin, Vec3(1.0), std::sqrt(2.0) / 4.0, false},         // edges of the truncated octahedra
      {"honeycomb", honeycomb, Vec3(3.0, std::sqrt(3.0), 1.0), 1.0, false},  // cell size: the hexagon's edge
  };
}

const std::vector<PresetCell>& presets() {
  static const std::vector<PresetCell> all = make_presets();
  return all;
}

}  // namespace

const std::vector<std::string>& preset_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const PresetCell& p : presets()) out.push_back(p.name);
    return out;
  }();
  return names;
}

const PresetCell& preset_cell(const std::string& name, const std::string& field) {
  std::string known;
  for (const PresetCell& p : presets()) {
    if (p.name == name) return p;
    known += (known.empty() ? "" : ", ") + p.name;
  }
  fail_input(field, "unknown preset '" + name + "' (known: " + known + ")");
}

std::vector<BeamPattern> preset_beam_patterns(const PresetCell& cell) {
  std::vector<BeamPattern> patterns;
  const int n = static_cast<int>(cell.basis.size());
  for (int n1 = 0; n1 < n; ++n1)
    for (int n2 = 0; n2 < n; ++n2)
      for (int di = -1; di <= 1; ++di)
        for (int dj = -1; dj <= 1; ++dj)
          for (int dk = -1; dk <= 1; ++dk) {
            const bool zero = di == 0 && dj == 0 && dk == 0;
            if (n1 == n2 && zero) continue;
            const Vec3 delta = (cell.basis[n2] + Vec3(di, dj, dk) - cell.basis[n1]) * cell.aspect;
            if (std::abs(glm::length(delta) - cell.neighbour_distance) > kDistanceTolerance) continue;
            if (cell.corner_beams_only && n1 != 0 && n2 != 0) continue;
            // each pair once, written with a non-negative offset (lexicographically)
            if (std::make_tuple(di, dj, dk) < std::make_tuple(0, 0, 0) || (zero && n1 > n2)) continue;
            patterns.push_back({n1, di, dj, dk, n2});
          }
  return patterns;
}

std::vector<NodeId> preset_outside_nodes(const PresetCell& cell, const std::array<std::int64_t, 3>& cells) {
  std::set<std::tuple<std::int64_t, std::int64_t, std::int64_t, int>> omitted;
  for (int n = 0; n < static_cast<int>(cell.basis.size()); ++n)
    for (int a = 0; a < 3; ++a) {
      if (cell.basis[n][a] == 0.0) continue;  // only a node offset along a sticks out of the last layer along a
      std::int64_t lo[3] = {0, 0, 0}, hi[3] = {cells[0] + 1, cells[1] + 1, cells[2] + 1};
      lo[a] = cells[a];
      hi[a] = cells[a] + 1;
      for (std::int64_t i = lo[0]; i < hi[0]; ++i)
        for (std::int64_t j = lo[1]; j < hi[1]; ++j)
          for (std::int64_t k = lo[2]; k < hi[2]; ++k) omitted.insert({i, j, k, n});
    }
  std::vector<NodeId> out;
  for (const auto& [i, j, k, n] : omitted) out.push_back({i, j, k, n});
  return out;
}

Lattice preset_lattice(const std::string& name, const std::array<std::int64_t, 3>& cells, double cell_size,
                       double node_radius, double beam_radius) {
  const PresetCell& cell = preset_cell(name, "name");
  for (int a = 0; a < 3; ++a)
    if (cells[a] < 1) fail_input("cells", "every count must be >= 1 (got " + std::to_string(cells[a]) + ")");
  require_positive(cell_size, "cell_size");
  require_positive(node_radius, "node_radius");
  if (!(beam_radius >= 0.0 && beam_radius <= node_radius))
    fail_input("beam_radius", "must be in [0, node_radius] (got " + std::to_string(beam_radius) + ")");
  std::vector<TemplateNode> nodes;
  for (const Vec3& b : cell.basis) nodes.push_back({b * cell.aspect * cell_size, node_radius});
  std::vector<BeamPattern> beams = preset_beam_patterns(cell);
  if (beam_radius > 0.0 && beam_radius < node_radius)
    for (BeamPattern& b : beams) b.from_radius = b.to_radius = beam_radius;
  const Vec3 edge = cell.aspect * cell_size;
  return Lattice({nodes, beams,
                  SteadyBrickLayout::steps({cells[0] + 1, cells[1] + 1, cells[2] + 1},
                                           Similarity::translation({edge.x, 0, 0}),
                                           Similarity::translation({0, edge.y, 0}),
                                           Similarity::translation({0, 0, edge.z})),
                  preset_outside_nodes(cell, cells)});
}

}  // namespace steady
