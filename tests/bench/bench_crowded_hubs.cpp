// Crowded hubs (issue 17): dense octet lattices whose beams are nearly as thick as their nodes (cells of 2, node
// radius 0.4, beams 0.6 to 0.9 of the node, a slight screw along W so that hubs differ from cell to cell).
//
// Part 1, per distinct hub shape: the core from the envelope arrangement (no Boolean) against the baseline, the
// Boolean Fuse of the ball and its stumps that built every transversal core before: distinct shapes, median
// seconds per shape of each and their ratio, measured side by side in one run.
//
// Part 2, the whole lattice: the B-rep of about 450 beams and of about 10,000 beams (the targets: under 2 s
// and under 30 s), then the 10,000-beam octet at beam/node 0.9 trimmed into a cylinder with a skin (target: one
// valid solid in under 60 s), through the rim clusters' Cut and through the clipped-and-fused baseline. Validity is
// BRepCheck's; volumes are compared to the closed-form properties.
#include <BRepPrimAPI_MakeCylinder.hxx>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "bench_common.hpp"
#include "brep/hub_core.hpp"
#include "brick_definition.hpp"
#include "lattice/hub_catalog.hpp"
#include "lattice/hub_collars.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/trim.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/presets.hpp"
#include "steady/properties/lattice_properties.hpp"

using namespace steady;
using bench::long_run;
using bench::seconds_of;

namespace {

constexpr double kCell = 2.0, kNode = 0.4;

// The screw turns about the lattice's middle by 0.01 rad per layer (hubs differ from layer to layer; beams between
// layers tilt by at most 0.01 times the distance from the axis over the layer height).
Lattice dense_octet(double ratio, const Counts& counts) {
  const PresetCell& cell = preset_cell("octet");
  test::BrickDefinition d;
  for (const Vec3& b : cell.basis) d.nodes.push_back({kCell * b, kNode});
  for (BeamPattern p : preset_beam_patterns(cell)) {
    p.from_radius = p.to_radius = kNode * ratio;
    d.beams.push_back(p);
  }
  d.counts = counts;
  d.u = {Similarity::translation({kCell, 0, 0})};
  d.v = {Similarity::translation({0, kCell, 0})};
  const Vec3 middle(kCell * (counts.u - 1) / 2.0, kCell * (counts.v - 1) / 2.0, 0.0);
  d.w = {Similarity::screw(0.01, {0, 0, 1}, middle, kCell)};
  return Lattice(d);
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

void per_shape(double ratio) {
  const FlatLattice f = flatten(dense_octet(ratio, {3, 3, 3}));
  const std::vector<BeamFrustum> frustums = beam_frustums(f);
  std::vector<HubGeometry> hubs;
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    std::vector<std::pair<std::int64_t, int>> stumps;
    hubs.push_back(hub_geometry(f, frustums, i, [&](std::int64_t e) { return frustums[e].exists; }, stumps));
  }
  const HubCatalog catalog = catalog_hubs(hubs);
  std::vector<double> arranged, fused;
  int crowded = 0, fell_back = 0, fuse_failed = 0;
  for (std::size_t s = 0; s < catalog.shapes.size(); ++s) {
    const HubGeometry& rep = hubs[catalog.representatives[s]];
    if (rep.kind == 0) continue;
    ++crowded;
    const std::vector<CoreStump> stumps = core_stumps(catalog.shapes[s], rep.extras);
    const CoreKind kind = core_kind(rep.kind);
    std::shared_ptr<const HubCore> core;
    arranged.push_back(seconds_of([&] { core = build_hub_core(stumps, kind, core_collars(stumps, kind, kMaxCollarPosition)); }));
    fell_back += core->fused;
    try {
      fused.push_back(seconds_of([&] { build_transversal_core(stumps, place_collars(stumps, kind, kMaxCollarPosition)); }));
    } catch (const InvalidInput&) {
      ++fuse_failed;
    }
  }
  const double a = median(arranged), b = median(fused);
  std::printf("%8.2f %8d %9d %14.4f %14.4f %8.0fx %10d %12d\n", ratio, crowded, fell_back, a, b, b / a,
              static_cast<int>(arranged.size()), fuse_failed);
}

void whole(double ratio, const Counts& counts) {
  const Lattice lattice = dense_octet(ratio, counts);
  const FlatLattice f = flatten(lattice);
  LatticeBrep b;
  double t = 0.0;
  try {
    t = seconds_of([&] { b = build_lattice_brep(f); });
  } catch (const InvalidInput& e) {
    std::printf("%8.2f %8lld  refused: %s\n", ratio, (long long)f.beam_count(), e.what());
    return;
  }
  const double exact = lattice_properties(lattice).volume;
  std::printf("%8.2f %8lld %10.2f %8lld %9lld %7lld %6s %7lld %12.1e\n", ratio, (long long)f.beam_count(), t,
              (long long)b.stats.core_hubs, (long long)b.stats.distinct_cores, (long long)b.stats.fused_cores,
              is_valid(b.shape) ? "yes" : "NO", (long long)solid_count(b.shape), shape_volume(b.shape) / exact - 1.0);
}

void trimmed_with_skin(const Counts& counts) {
  const Lattice lattice = dense_octet(0.9, counts);
  const FlatLattice f = flatten(lattice);
  // A cylinder inside the lattice's box of groups, cutting through hubs at its wall and caps.
  const double height = kCell * (counts.w - 1), radius = 0.45 * kCell * (std::min(counts.u, counts.v) - 1);
  const TopoDS_Shape body = BRepPrimAPI_MakeCylinder(
      gp_Ax2(gp_Pnt(kCell * (counts.u - 1) / 2.0, kCell * (counts.v - 1) / 2.0, 0.3), gp_Dir(0, 0, 1)), radius,
      height - 0.6);
  // The band covers the skin's rims: united with the skin by one Cut (rim_cut), against the baseline that clips it
  // and glues it by a Fuse, side by side.
  double seconds[2] = {0.0, 0.0}, volume[2] = {0.0, 0.0};
  for (int way = 0; way < 2; ++way) {
    TrimOptions o;
    o.skin = 0.8;
    o.rim_cut = way == 0;
    TrimResult r;
    try {
      seconds[way] = seconds_of([&] { r = trim_lattice(f, body, o); });
    } catch (const InvalidInput& e) {
      std::printf("trimmed into a cylinder with a 0.8 skin: refused: %s\n", e.what());
      return;
    }
    volume[way] = shape_volume(r.part);
    std::printf("trimmed into a cylinder with a 0.8 skin, %s: %lld beams, %.1f s, %lld solids, valid %s, %lld core "
                "hubs (%lld distinct, %lld fused), %lld rim clusters (%lld not clipped)\n",
                way == 0 ? "rim Cut" : "clipped and fused", (long long)f.beam_count(), seconds[way],
                (long long)solid_count(r.part), is_valid(r.part) ? "yes" : "NO", (long long)r.stats.core_hubs,
                (long long)r.stats.distinct_cores, (long long)r.stats.fused_cores, (long long)r.stats.rim_clusters,
                (long long)r.stats.rim_clusters_unclipped);
  }
  std::printf("rim Cut against clipped and fused: %.2fx faster, volumes %.1e apart (relative)\n",
              seconds[1] / seconds[0], std::abs(volume[0] / volume[1] - 1.0));
}

}  // namespace

int main(int argc, char** argv) {
  const bool long_run_asked = long_run(argc, argv);
  std::setvbuf(stdout, nullptr, _IOLBF, 0);
  std::printf("Part 1: one core per distinct crowded hub of a 3 x 3 x 3 dense octet (medians)\n");
  std::printf("%8s %8s %9s %14s %14s %9s %10s %12s\n", "beam/node", "shapes", "fell back", "arranged [s]", "Fuse [s]",
              "ratio", "timed", "Fuse failed");
  for (double ratio : {0.6, 0.7, 0.8, 0.9}) per_shape(ratio);
  std::printf("\nPart 2: whole lattices (volume error against the closed-form properties)\n");
  std::printf("%8s %8s %10s %8s %9s %7s %6s %7s %12s\n", "beam/node", "beams", "B-rep [s]", "cores", "distinct", "fused",
              "valid", "solids", "volume err");
  for (double ratio : {0.6, 0.7, 0.9}) whole(ratio, {3, 3, 3});
  whole(0.9, {8, 8, 8});
  if (long_run_asked) whole(0.7, {8, 8, 8});
  trimmed_with_skin({8, 8, 8});
  return 0;
}
