// The lattice's mesh against a voxel pipeline (OpenVDB, as PicoGK and nTop-like tools mesh lattices): rasterise
// the same balls and cones as a narrow-band signed distance field, extract the zero surface (volumeToMesh), at a
// voxel size whose mesh deviates from the exact surface no more than ours, measured the same way. One run.
#include <openvdb/openvdb.h>
#include <openvdb/tools/VolumeToMesh.h>

#include <cstdio>

#include "bench_common.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/hub.hpp"
#include "steady/lattice/presets.hpp"
#include "steady/mesh/lattice_mesh.hpp"

using namespace steady;

namespace {

// Signed distance to the convex hull of two balls, in the (axial x, radial rho) half-plane of its axis: beyond the
// tangent circle at a or b the nearest point is on that ball, between them on the cone's generator.
double beam_distance(const BeamCone& c, const Vec3& p) {
  const Vec3 w = p - c.a;
  const double x = glm::dot(w, c.axis), rho = glm::length(w - x * c.axis);
  const double t = (x - c.ra * c.sin_phi) * c.cos_phi - (rho - c.ra * c.cos_phi) * c.sin_phi;
  if (t < 0.0) return std::hypot(x, rho) - c.ra;
  if (t > c.length * c.cos_phi) return std::hypot(x - c.length, rho) - c.rb;
  return x * c.sin_phi + rho * c.cos_phi - c.ra;
}

double union_distance(const FlatLattice& f, const std::vector<BeamCone>& cones, const Vec3& p) {
  double d = 1e300;
  for (const Ball& b : f.balls) d = std::min(d, glm::length(p - b.center) - b.radius);
  for (const BeamCone& c : cones) d = std::min(d, beam_distance(c, p));
  return d;
}

struct VoxelMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<Vec3, 3>> triangles;
};

// A narrow band of 3 voxels each side, element by element (the union is the min of the distances; the interior is
// set to -band), then the zero surface.
VoxelMesh voxel_mesh(const FlatLattice& f, const std::vector<BeamCone>& cones, double voxel) {
  using namespace openvdb;
  const float band = static_cast<float>(3.0 * voxel);
  FloatGrid::Ptr grid = FloatGrid::create(band);
  grid->setTransform(math::Transform::createLinearTransform(voxel));
  grid->setGridClass(GRID_LEVEL_SET);
  FloatGrid::Accessor acc = grid->getAccessor();
  auto splat = [&](const Vec3& lo, const Vec3& hi, auto&& distance) {
    const Coord a(static_cast<int>(std::floor(lo.x / voxel)) - 3, static_cast<int>(std::floor(lo.y / voxel)) - 3,
                  static_cast<int>(std::floor(lo.z / voxel)) - 3);
    const Coord b(static_cast<int>(std::ceil(hi.x / voxel)) + 3, static_cast<int>(std::ceil(hi.y / voxel)) + 3,
                  static_cast<int>(std::ceil(hi.z / voxel)) + 3);
    for (int i = a.x(); i <= b.x(); ++i)
      for (int j = a.y(); j <= b.y(); ++j)
        for (int k = a.z(); k <= b.z(); ++k) {
          // Outside the band: background; deeper inside: clamped to -band (a level set's interior).
          const float d = std::max(static_cast<float>(distance(Vec3(i, j, k) * voxel)), -band);
          if (d >= band) continue;
          const Coord ijk(i, j, k);
          if (!acc.isValueOn(ijk) || d < acc.getValue(ijk)) acc.setValue(ijk, d);
        }
  };
  for (const Ball& b : f.balls)
    splat(b.center - b.radius, b.center + b.radius, [&](const Vec3& p) { return glm::length(p - b.center) - b.radius; });
  for (const BeamCone& c : cones)
    splat(glm::min(c.a - c.ra, c.b - c.rb), glm::max(c.a + c.ra, c.b + c.rb), [&](const Vec3& p) { return beam_distance(c, p); });
  std::vector<Vec3s> points;
  std::vector<Vec3I> tris;
  std::vector<Vec4I> quads;
  tools::volumeToMesh(*grid, points, tris, quads, 0.0, 0.0);
  VoxelMesh out;
  for (const Vec3s& p : points) out.vertices.emplace_back(p.x(), p.y(), p.z());
  for (const Vec3I& t : tris) out.triangles.push_back({out.vertices[t[0]], out.vertices[t[1]], out.vertices[t[2]]});
  for (const Vec4I& q : quads) {
    out.triangles.push_back({out.vertices[q[0]], out.vertices[q[1]], out.vertices[q[2]]});
    out.triangles.push_back({out.vertices[q[0]], out.vertices[q[2]], out.vertices[q[3]]});
  }
  return out;
}

// Largest distance from the exact surface over every `stride`-th triangle's centroid and edge midpoints.
double deviation(const FlatLattice& f, const std::vector<BeamCone>& cones, const std::vector<std::array<Vec3, 3>>& tris,
                 std::size_t stride) {
  double worst = 0.0;
  for (std::size_t i = 0; i < tris.size(); i += stride) {
    const auto& t = tris[i];
    for (const Vec3& p : {(t[0] + t[1] + t[2]) / 3.0, 0.5 * (t[0] + t[1]), 0.5 * (t[1] + t[2]), 0.5 * (t[2] + t[0])})
      worst = std::max(worst, std::abs(union_distance(f, cones, p)));
  }
  return worst;
}

}  // namespace

int main() {
  openvdb::initialize();
  const FlatLattice f = flatten(preset_lattice("BCC", {3, 3, 3}, 2.0, 0.3, 0.15));
  std::vector<BeamCone> cones;
  for (const FlatBeam& b : f.beams) {
    const BeamCone c = beam_cone({f.balls[b.a].center, b.ra}, {f.balls[b.b].center, b.rb});
    if (c.has_lateral_surface()) cones.push_back(c);
  }
  const double tolerance = 0.006;
  std::printf("lattice mesh vs a voxel pipeline (OpenVDB level set + volumeToMesh), BCC 3x3x3: %lld balls, %lld beams\n",
              static_cast<long long>(f.ball_count()), static_cast<long long>(f.beam_count()));
  TriangleMesh mesh;
  const double ours = bench::median_seconds(3, [&] { mesh = lattice_mesh(f, {tolerance}); });
  std::vector<std::array<Vec3, 3>> ours_tris;
  for (const Triangle& t : mesh.triangles) ours_tris.push_back({mesh.vertices[t[0]], mesh.vertices[t[1]], mesh.vertices[t[2]]});
  const double ours_dev = deviation(f, cones, ours_tris, 3);
  std::printf("  ours:   %.3f s, %zu triangles, measured deviation %.2e\n", ours, mesh.triangles.size(), ours_dev);
  // Voxels small enough to deviate no more than ours.
  double voxel = 0.02, seconds = 0.0, dev = 0.0;
  VoxelMesh vm;
  for (int attempt = 0; attempt < 6; ++attempt, voxel *= 0.7) {
    seconds = bench::seconds_of([&] { vm = voxel_mesh(f, cones, voxel); });
    dev = deviation(f, cones, vm.triangles, 3);
    std::printf("  voxels: %.4f voxel, %.3f s, %zu triangles, measured deviation %.2e\n", voxel, seconds,
                vm.triangles.size(), dev);
    if (dev <= ours_dev) break;
  }
  std::printf("  ratio at equal deviation: %.0fx faster than the voxel pipeline%s\n", seconds / ours,
              dev <= ours_dev ? "" : " (the voxels never got as close: ratio is a lower bound)");
  return 0;
}
