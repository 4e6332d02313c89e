#include "steady/mesh/lattice_mesh.hpp"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>

#include "mesh/mesh_plan.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"

namespace steady {

TriangleMesh lattice_mesh(const FlatLattice& f, const MeshOptions& options, LatticeMeshStats* stats_out,
                          Progress& progress) {
  progress.set_total(100);
  {
    const ProgressScope scope(&progress);
    require_mesh_memory(f, options.tolerance, "mesh");  // before the templates, which take long at a tiny tolerance
  }
  MeshPlan plan;
  {
    Progress part(progress, 60);
    plan = plan_lattice_mesh(f, options, part);
  }
  const auto t1 = std::chrono::steady_clock::now();
  if (plan.vertex_count > 0xffffffffull)
    throw ResourceLimit("mesh: " + std::to_string(plan.vertex_count) +
                        " vertices exceed the 2^32 an indexed mesh holds: use a larger tolerance, or write STL");
  require_memory(plan.vertex_count * sizeof(Vec3) + plan.triangle_count * sizeof(Triangle),
                 "mesh: " + std::to_string(plan.triangle_count) + " triangles",
                 "use a larger tolerance (fewer triangles), write STL as it is built, or a 3MF beam lattice");
  TriangleMesh mesh;
  mesh.vertices.resize(plan.vertex_count);
  mesh.triangles.resize(plan.triangle_count);
  {
    Progress part(progress, 40, static_cast<std::int64_t>(plan.hubs.size() + f.beam_count()));
    tbb::parallel_for(std::size_t(0), plan.hubs.size(), [&](std::size_t h) {
      if (plan.groups.of_hub[h] < 0)
        place_hub(plan, h, mesh.vertices.data() + plan.hubs[h].first_vertex,
                  mesh.triangles.data() + plan.hubs[h].first_triangle);
      if (h % 1024 == 0) part.advance(1024);
    });
    for (const MeshGroup& g : plan.groups.groups) {
      std::copy(g.mesh.vertices.begin(), g.mesh.vertices.end(), mesh.vertices.begin() + g.first_vertex);
      const auto base = static_cast<std::uint32_t>(g.first_vertex);
      for (std::size_t t = 0; t < g.mesh.triangles.size(); ++t) {
        const Triangle& tri = g.mesh.triangles[t];
        mesh.triangles[g.first_triangle + t] = {base + tri[0], base + tri[1], base + tri[2]};
      }
    }
    tbb::parallel_for(std::int64_t(0), f.beam_count(), [&](std::int64_t e) {
      if (plan.frustums[e].exists && !plan.groups.inner[e])
        place_strip(plan, e, mesh.triangles.data() + plan.beam_first_triangle[e]);
      if (e % 1024 == 0) part.advance(1024);
    });
  }
  plan.stats.placing_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  if (stats_out) *stats_out = plan.stats;
  progress.finish();
  return mesh;
}

TriangleMesh lattice_mesh(const Lattice& lattice, const MeshOptions& options, LatticeMeshStats* stats,
                          Progress& progress) {
  return lattice_mesh(flatten(lattice), options, stats, progress);
}

}  // namespace steady
