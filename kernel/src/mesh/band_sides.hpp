#pragma once
// Which parts of a lattice's mesh may meet the surface the lattice is trimmed to. Hubs (a ball and its half-beams)
// are classified first by a ball around each, one distance query a hub. Within the band of hubs in reach of the
// surface, each element is then classified on its own (a hub's sphere patch, a beam's strip) by the bounding ball
// of its vertices, so that only the elements that may touch the surface go through the Boolean: a hub in reach
// often has its sphere and most of its strips clear of the surface.
#include <vector>

#include "mesh/mesh_plan.hpp"
#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

enum class Side { Inside, Crossing, Outside };

struct BandSides {
  std::vector<Side> patches;  // per hub: its sphere patch
  std::vector<Side> strips;   // per beam: its strip (Outside for a beam with none)
  std::int64_t inside_hubs = 0, crossing_hubs = 0, outside_hubs = 0;  // by reach, before the elements
};

// `surface`: closed and outward. An element is Crossing unless the ball around its vertices (which holds its
// triangles, and any cap closing one of its loops) is clear of the surface.
BandSides classify_band(const MeshPlan& plan, const TriangleMesh& surface);

}  // namespace steady
