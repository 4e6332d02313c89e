#pragma once
// What a lattice mesh is made of before any triangle is placed: the hubs with their templates (each distinct hub
// shape tessellated once per scale level), where every beam's strip starts and ends, and the size of the result.
// The mesh itself is then produced piece by piece (place_hub, place_strip), whole (lattice_mesh) or streamed to
// a file chunk after chunk (write_lattice_stl), from the same placement arithmetic so the pieces always match.
#include <array>
#include <cstdint>
#include <exception>
#include <functional>
#include <string>
#include <vector>

#include "lattice/hub_catalog.hpp"
#include "mesh/hub_tessellation.hpp"
#include "mesh/mesh_groups.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/mesh/lattice_mesh.hpp"

namespace steady {

struct MeshHub {
  std::int64_t ball = -1;
  std::vector<std::pair<std::int64_t, int>> stumps;  // (beam, end: 0 at a, 1 at b)
  int templ = -1;
  std::uint64_t first_vertex = 0, first_triangle = 0;
};

// Where a beam's strip starts or ends: one of a hub's loops.
struct MeshBeamEnd {
  std::int64_t hub = -1;
  int slot = -1;
};

struct MeshPlan {
  const FlatLattice* lattice = nullptr;
  std::vector<BeamFrustum> frustums;
  std::vector<MeshHub> hubs;
  std::vector<MeshBeamEnd> ends;  // 2 per beam: at a, at b
  HubCatalog catalog;
  std::vector<HubTemplate> templates;
  MeshGroups groups;                               // hubs of elements meeting foreign ones, united (mesh_groups.hpp)
  std::vector<std::uint64_t> beam_first_triangle;  // beam_count + 1 entries; strips follow all hubs and groups
  std::uint64_t vertex_count = 0, triangle_count = 0;
  LatticeMeshStats stats;
  std::string first_short_beam;  // the first beam too short for its hubs' collars, for messages ("" when none)
};

// At most how many points the template of a hub with `stumps` beams has at relative tolerance `tau`, counting a
// crowded hub's collar circles (mesh_estimate.cpp).
double template_point_bound(double tau, std::size_t stumps);
// What building a template costs per point at its peak, while CGAL triangulates it: 810 to 840 bytes measured
// (one template of 0.48 and 1.37 million points, ru_maxrss), rounded up.
constexpr double kBytesPerTemplatePoint = 1024.0;

// Which hubs will be placed (or hold a loop of a strip that will), given the plan's hubs, frustums and ends before
// any template exists: one char per hub. A trimmed mesh needs no template for the hubs it drops.
using HubsNeeded = std::function<std::vector<char>(const MeshPlan&)>;

// Checks the options and the lattice (InvalidInput naming "tolerance", "lattice" or "hub"), builds the templates:
// all of them, or with `needed` only those of the hubs it names (the others stay empty, and the strips of beams
// at such hubs are not counted). The hubs of elements meeting foreign ones, and of beams too short for their
// collars, are united in groups (mesh_groups.hpp); a group that cannot be united is refused (InvalidInput "hub"
// naming the first short beam when there are short beams).
MeshPlan plan_lattice_mesh(const FlatLattice& lattice, const MeshOptions& options, Progress& progress,
                           const HubsNeeded& needed = {});

// Whether an error thrown while hubs are united or cut is the geometry's failure, which a retry or the short
// beams' refusal may answer: not a cancel, nor a refusal for memory, which say themselves.
bool is_geometry_failure(const std::exception& e);

// The refusal of a lattice whose short beams' united hubs gave no mesh (`why`: the union's or the Boolean's
// error): InvalidInput "hub", naming how many beams are short and the first, and what helps.
[[noreturn]] void fail_short_beams(const MeshPlan& plan, const std::string& why);

// Index in the whole mesh of vertex v of hub h's template (a loop's vertex when the hub is in a group).
std::uint64_t mesh_vertex(const MeshPlan& plan, std::size_t h, std::uint32_t v);

// Vertex v of hub h's template in place.
Vec3 placed_vertex(const MeshPlan& plan, std::size_t h, std::uint32_t v);
// Hub h's vertices and triangles (indices from first_vertex) into the given arrays.
void place_hub(const MeshPlan& plan, std::size_t h, Vec3* vertices, Triangle* triangles);
// Beam e's strip (strip_size(e) triangles, indices into the whole mesh's vertices) into `triangles`.
std::size_t strip_size(const MeshPlan& plan, std::int64_t e);
void place_strip(const MeshPlan& plan, std::int64_t e, Triangle* triangles);
// The strip between loop a (points va, mesh indices ia, counterclockwise about the beam's axis) and loop b (given
// counterclockwise about the opposite direction, as hub b sees its stump): ia.size() + ib.size() triangles.
void strip_triangles(const std::vector<Vec3>& va, const std::vector<std::uint32_t>& ia, const std::vector<Vec3>& vb,
                     std::vector<std::uint32_t> ib, const Vec3& axis, const Vec3& center, Triangle* out);
// The same strip as corner coordinates (what a streamed STL needs).
void place_strip_corners(const MeshPlan& plan, std::int64_t e, std::array<Vec3, 3>* corners);

}  // namespace steady
