#pragma once
// Which parts of a lattice's mesh may meet the surface the lattice is trimmed to. Hubs (a ball and its half-beams)
// are classified first by a ball around each, one distance query a hub. Within the band of hubs in reach of the
// surface, each element is then classified on its own (a hub's sphere patch, a beam's strip) by balls holding its
// triangles, so that only the elements that may touch the surface go through the Boolean: a hub in reach
// often has its sphere and most of its strips clear of the surface.
#include <cstddef>
#include <memory>
#include <utility>
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

// The surface the lattice is trimmed to (closed and outward), ready for distance and side queries.
class TrimSurface {
 public:
  explicit TrimSurface(const TriangleMesh& surface);
  ~TrimSurface();
  // Per hub, by the ball of its reach: needs the plan's hubs, frustums and ends, no template.
  std::vector<Side> hubs(const MeshPlan& plan) const;
  // Per element, given the hubs' sides: an element is Crossing unless the balls holding its triangles, and any
  // cap closing one of its loops, are clear of the surface. Needs the templates of the hubs
  // that hubs_needed names.
  BandSides elements(const MeshPlan& plan, const std::vector<Side>& hubs) const;

  // The points closer than `gap` to the surface, each with a place `gap` from it on its side (away from its closest
  // point, or along that face's outward normal when on the surface). So that no vertex grazes the wall the Boolean
  // cuts at, which would leave edges below a float's resolution.
  std::vector<std::pair<std::size_t, Vec3>> clear_places(const std::vector<Vec3>& points, double gap) const;

  struct Queries;  // CGAL's tree over the surface

 private:
  std::unique_ptr<Queries> queries_;
};

// The hubs whose templates the trimmed mesh needs: all but those outside, and those at a beam to a hub that is not.
std::vector<char> hubs_needed(const MeshPlan& plan, const std::vector<Side>& hubs);

}  // namespace steady
