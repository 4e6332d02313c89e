#pragma once
// Hubs whose elements meet foreign ones (query/foreign_contacts.hpp), in the mesh. Placed copies of templates and
// strips would cross each other there, so, as the B-rep does, the hubs joined by contacts are meshed as groups:
// each member closed (a hub by flat caps on its loops, a beam inside the group by caps on its strip's two loops)
// and the members united by CGAL's exact corefinement. A hub's cap and its inner beam's cap are the same fan with
// opposite orientations, so the union drops both; a cap on a loop where a beam leaves the group stays clear of
// every other member (the beam meets no foreign element), and is removed after the union, leaving the loop open
// with its vertices bit for bit as placed, where the beam's strip joins it as it joins any hub. A beam too short
// for its hubs' collars joins its two hubs the same way: it has no strip, each hub's stump is capped inside the
// other hub (its stump, or its ball: mesh_plan.cpp), and the union keeps the outer of the two tessellations of the
// cone where they overlap.
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "steady/core/progress.hpp"
#include "steady/mesh/triangle_mesh.hpp"

namespace steady {

struct MeshPlan;
struct ForeignContacts;

struct MeshGroup {
  std::vector<std::size_t> hubs;  // plan hubs
  TriangleMesh mesh;              // in place, rounded to floats, open exactly at the loops of its leaving beams
  std::uint64_t first_vertex = 0, first_triangle = 0;  // in the whole mesh (set by the plan)
};

struct MeshGroups {
  std::vector<int> of_hub;        // per plan hub: its group, or -1
  std::vector<char> inner;        // per beam: both ends in one group (its strip is part of the group's mesh)
  std::vector<MeshGroup> groups;
  // (hub << 32 | template vertex) of every leaving loop's vertex -> its index in the group's mesh
  std::unordered_map<std::uint64_t, std::uint32_t> loop_vertex;
  bool empty() const { return groups.empty(); }
};

// The groups of a plan whose templates exist (every hub of a group needs its own): the hubs joined by `contacts`
// (its pairs of balls, with those of the short beams added), `short_beam` per beam. ResourceLimit when the
// largest group's exact union would not fit in memory; std::runtime_error when CGAL cannot unite a group or the union
// cuts a leaving loop.
MeshGroups mesh_groups(const MeshPlan& plan, const ForeignContacts& contacts, const std::vector<char>& short_beam,
                       Progress& progress);

// Memory of the exact corefinement per triangle of a group's members (exact points, half-edges, the union's
// copy), the bound on a group's size. Measured: a row of 300 overlapping balls (88,144 triangles at 0.01) added
// 40 MB to the process at its peak, about 0.5 KB a triangle; 4 KB leaves room for unions that cut more.
constexpr std::uint64_t kUnionBytesPerTriangle = 4096;

}  // namespace steady
