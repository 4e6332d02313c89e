#include "mesh/mesh_groups.hpp"

#include <CGAL/Polygon_mesh_processing/corefinement.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <string>

#include "core/disjoint_sets.hpp"
#include "lattice/circle_frames.hpp"
#include "mesh/cgal_mesh.hpp"
#include "mesh/float_safe.hpp"
#include "mesh/loop_fan.hpp"
#include "mesh/mesh_plan.hpp"
#include "mesh/vertex_key.hpp"
#include "query/foreign_contacts.hpp"
#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"

namespace steady {

namespace {

namespace PMP = CGAL::Polygon_mesh_processing;

// One closed operand of a group's union: a hub with the strips of the inner beams it owns (those whose end a it
// is), capped on every other loop by fans (loop_fan.hpp; facing along the loop's axis, `reversed`: against it).
struct Member {
  TriangleMesh mesh;
  std::vector<Vec3> kept;  // centers of the caps on leaving loops

  Vec3 cap(const std::vector<std::uint32_t>& index, bool reversed) { return append_fan(mesh, index, reversed); }
};

// A short beam's two stumps both tessellate its cone between the collars, and the union keeps the outer of the two.
// Rings whose points meet (the facing stumps of symmetric hubs) put the two tessellations on each other there: the
// exact union is then full of slivers that cross once rounded to floats. Hub b's ring (`loop`, placed in
// `vertices`) is turned about the beam's axis, by the turn of a fine grid within one of its steps that keeps its
// points farthest from hub a's (half a step when both have as many points), so that their facets cross at an angle.
// Its points stay on their circle; the union drops the ring with its cap. A union that still folds is tried again
// (mesh_groups) with the ring as placed (`attempt` 1), then a quarter of a step past the farthest turn (2).
void stagger_ring(const MeshPlan& plan, std::int64_t e, const std::vector<std::uint32_t>& loop,
                  std::vector<Vec3>& vertices, int attempt) {
  if (loop.size() < 3 || attempt == 1) return;
  const MeshBeamEnd& a = plan.ends[2 * e];
  const BeamCone& cone = plan.frustums[e].cone;
  const Vec3 u = any_perpendicular(cone.axis), v = glm::cross(cone.axis, u);
  auto angle = [&](const Vec3& p) { return std::atan2(glm::dot(p - cone.a, v), glm::dot(p - cone.a, u)); };
  std::vector<double> at_a, at_b;
  for (std::uint32_t i : plan.templates[plan.hubs[a.hub].templ].loops[a.slot])
    at_a.push_back(angle(placed_vertex(plan, a.hub, i)));
  for (std::uint32_t i : loop) at_b.push_back(angle(vertices[i]));
  std::sort(at_a.begin(), at_a.end());
  at_a.push_back(at_a.front() + 2.0 * M_PI);
  // The smallest angle between a point of b's ring turned by `turn` and a point of a's.
  auto clearance = [&](double turn) {
    double least = M_PI;
    for (double t : at_b) {
      const double w = wrap_into(t + turn, at_a.front());
      const auto next = std::upper_bound(at_a.begin(), at_a.end(), w);
      least = std::min({least, *next - w, w - *(next - 1)});
    }
    return least;
  };
  constexpr int kTurns = 32;
  const double step = 2.0 * M_PI / static_cast<double>(loop.size());
  double best_turn = 0.0, best = clearance(0.0);
  for (int k = 1; k < kTurns; ++k) {
    const double turn = (k < kTurns / 2 ? k : k - kTurns) * step / kTurns;  // small turns first, both ways
    const double c = clearance(turn);
    if (c > best * (1.0 + 1e-9)) best = c, best_turn = turn;
  }
  if (attempt == 2) best_turn += 0.25 * step;
  const double c = std::cos(best_turn), s = std::sin(best_turn);
  for (std::uint32_t i : loop) {
    const Vec3 d = vertices[i] - cone.a;
    const double x = glm::dot(d, u), y = glm::dot(d, v);
    vertices[i] = cone.a + glm::dot(d, cone.axis) * cone.axis + (c * x - s * y) * u + (s * x + c * y) * v;
  }
}

Member hub_member(const MeshPlan& plan, const MeshGroups& groups, const std::vector<char>& short_beam, std::size_t h,
                  int attempt) {
  Member m;
  const HubTemplate& t = plan.templates[plan.hubs[h].templ];
  for (std::size_t v = 0; v < t.vertices.size(); ++v) m.mesh.vertices.push_back(placed_vertex(plan, h, static_cast<std::uint32_t>(v)));
  m.mesh.triangles = t.triangles;
  const int group = groups.of_hub[h];
  for (std::size_t s = 0; s < plan.hubs[h].stumps.size(); ++s) {
    const auto [e, end] = plan.hubs[h].stumps[s];
    const std::vector<std::uint32_t>& loop = t.loops[s];
    if (!groups.inner[e]) {
      m.kept.push_back(m.cap(loop, false));  // faces away from the hub, along the leaving beam
      continue;
    }
    if (end == 1 || short_beam[e]) {
      // The beam's owner closes it on this loop with the same fan, facing the other way; a short beam's other hub
      // covers this cap with its stump.
      if (short_beam[e] && end == 1) stagger_ring(plan, e, loop, m.mesh.vertices, attempt);
      m.cap(loop, false);
      continue;
    }
    // An owned inner beam: its strip from this hub's loop to a copy of the other hub's loop, capped there.
    const MeshBeamEnd& other = plan.ends[2 * e + 1];
    if (groups.of_hub[other.hub] != group) throw std::logic_error("mesh: an inner beam leaves its group");
    std::vector<Vec3> points[2];
    std::vector<std::uint32_t> index[2];
    for (std::uint32_t v : loop) points[0].push_back(m.mesh.vertices[v]), index[0].push_back(v);
    for (std::uint32_t v : plan.templates[plan.hubs[other.hub].templ].loops[other.slot]) {
      points[1].push_back(placed_vertex(plan, other.hub, v));
      index[1].push_back(static_cast<std::uint32_t>(m.mesh.vertices.size()));
      m.mesh.vertices.push_back(points[1].back());
    }
    const std::size_t first = m.mesh.triangles.size();
    m.mesh.triangles.resize(first + index[0].size() + index[1].size());
    const BeamCone& cone = plan.frustums[e].cone;
    strip_triangles(points[0], index[0], points[1], index[1], cone.axis, cone.a, m.mesh.triangles.data() + first);
    m.cap(index[1], true);  // faces away from the beam, into the other hub
  }
  return m;
}

// The union of the members, pairwise in a balanced tree (neighbouring hubs first: members follow the balls'
// order), without the kept caps.
TriangleMesh unite(std::vector<Member> members, std::size_t group_index, Progress& progress) {
  std::vector<Vec3> kept;
  std::vector<ExactMesh> parts;
  for (Member& m : members) {
    kept.insert(kept.end(), m.kept.begin(), m.kept.end());
    parts.push_back(to_half_edge_mesh<ExactMesh>(m.mesh));
  }
  while (parts.size() > 1) {
    std::vector<ExactMesh> next;
    for (std::size_t i = 0; i + 1 < parts.size(); i += 2) {
      progress.check();
      ExactMesh out;
      bool united = false;
      std::string why;
      try {
        // Asked to check the faces it intersects for self-intersections: CGAL's corefinement assumes there are
        // none, and crashes where there are.
        united = PMP::corefine_and_compute_union(parts[i], parts[i + 1], out,
                                                 CGAL::parameters::throw_on_self_intersection(true),
                                                 CGAL::parameters::throw_on_self_intersection(true));
      } catch (const PMP::Corefinement::Self_intersection_exception&) {
        why = ": a member intersects itself";
      } catch (const std::exception& e) {  // CGAL's own checks (a constraint crossing another)
        why = std::string(": ") + e.what();
      }
      if (!united)
        throw std::runtime_error("mesh: CGAL could not unite the hubs of group " + std::to_string(group_index) +
                                 " (elements meeting foreign ones)" + why);
      next.push_back(std::move(out));
    }
    if (parts.size() % 2) next.push_back(std::move(parts.back()));
    parts = std::move(next);
  }
  return without_kept_caps(parts.front(), kept, false,
                           "mesh: the union of a group cut into a loop where a beam leaves it");
}

// Groups of any size are united (the pairwise unions check for a cancel between two); what bounds them is the
// memory of the exact corefinement, which holds every member's triangles with exact points: refused before any
// union (ResourceLimit) when the largest group would not fit, naming what joined its hubs.
void require_union_memory(const MeshPlan& plan, const MeshGroups& out, const ForeignContacts& contacts,
                          std::int64_t shorts) {
  std::uint64_t largest = 0;
  std::size_t hubs = 0;
  for (const MeshGroup& g : out.groups) {
    std::uint64_t triangles = 0;
    for (std::size_t h : g.hubs) triangles += plan.templates[plan.hubs[h].templ].triangles.size();
    if (triangles > largest) largest = triangles, hubs = g.hubs.size();
  }
  require_memory(largest * kUnionBytesPerTriangle,
                 "mesh: the exact union of " + std::to_string(hubs) + " hubs joined in one group (" +
                     std::to_string(largest) + " triangles of their templates) by " +
                     (contacts.empty() ? std::string()
                                       : std::to_string(contacts.issue_count) + " contacts of elements with foreign "
                                         "ones (" + contacts.description + ")" + (shorts ? " and " : "")) +
                     (shorts ? std::to_string(shorts) + " beams too short for their hubs' collars" : ""),
                 "thin the beams or nodes, space the nodes further apart, or use a larger tolerance");
}

// Group g's mesh (members with their short beams' rings turned as `attempt` says, united, rounded to floats,
// checked open exactly at its leaving loops) and its leaving loops' vertices, into `out`; std::runtime_error,
// leaving `out` as it was, when the union fails or folds.
void unite_group(const MeshPlan& plan, MeshGroups& out, const std::vector<char>& short_beam, std::size_t g, int attempt,
                 Progress& progress) {
  const MeshGroup& group = out.groups[g];
  std::vector<Member> members;
  for (std::size_t h : group.hubs) members.push_back(hub_member(plan, out, short_beam, h, attempt));
  TriangleMesh mesh = unite(std::move(members), g, progress);
  make_float_safe(mesh, "a group of united hubs");
  std::unordered_map<VertexKey, std::uint32_t, VertexKeyHash> index;
  for (std::uint32_t i = 0; i < mesh.vertices.size(); ++i) index.emplace(vertex_key(mesh.vertices[i]), i);
  std::unordered_map<std::uint64_t, std::uint32_t> loop_vertex;
  std::int64_t loop_edges = 0;
  for (std::size_t h : group.hubs) {
    const HubTemplate& t = plan.templates[plan.hubs[h].templ];
    for (std::size_t s = 0; s < plan.hubs[h].stumps.size(); ++s) {
      if (out.inner[plan.hubs[h].stumps[s].first]) continue;
      loop_edges += static_cast<std::int64_t>(t.loops[s].size());
      for (std::uint32_t v : t.loops[s]) {
        const auto it = index.find(vertex_key(float_rounded(placed_vertex(plan, h, v))));
        if (it == index.end())
          throw std::runtime_error("mesh: the union of group " + std::to_string(g) +
                                   " lost a vertex of the loop where beam " +
                                   std::to_string(plan.hubs[h].stumps[s].first) + " leaves it");
        loop_vertex.emplace(static_cast<std::uint64_t>(h) << 32 | v, it->second);
      }
    }
  }
  // Open exactly at the leaving loops: a cap the union cut into would leave more border, or a non-manifold edge.
  const MeshEdgeReport edges = mesh_edge_report(mesh);
  if (edges.border_edges != loop_edges || edges.non_manifold_edges || edges.misoriented_edges)
    throw std::runtime_error("mesh: the union of group " + std::to_string(g) + " has " +
                             std::to_string(edges.border_edges) + " open edges where its leaving loops have " +
                             std::to_string(loop_edges) + ", " + std::to_string(edges.non_manifold_edges) +
                             " non-manifold and " + std::to_string(edges.misoriented_edges) + " misoriented");
  out.groups[g].mesh = std::move(mesh);
  out.loop_vertex.insert(loop_vertex.begin(), loop_vertex.end());
}

}  // namespace

MeshGroups mesh_groups(const MeshPlan& plan, const ForeignContacts& contacts, const std::vector<char>& short_beam,
                       Progress& progress) {
  MeshGroups out;
  const FlatLattice& f = *plan.lattice;
  out.of_hub.assign(plan.hubs.size(), -1);
  out.inner.assign(f.beam_count(), 0);
  if (contacts.joined.empty()) return out;
  std::vector<std::int64_t> hub_of_ball(f.ball_count(), -1);
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) hub_of_ball[plan.hubs[h].ball] = static_cast<std::int64_t>(h);
  DisjointSets sets(plan.hubs.size());
  std::vector<char> joined(plan.hubs.size(), 0);
  for (const auto& [a, b] : contacts.joined) {
    const std::int64_t ha = hub_of_ball[a], hb = hub_of_ball[b];
    if (ha < 0 || hb < 0) continue;  // a ball absorbed by its neighbour adds no surface
    sets.join(static_cast<std::size_t>(ha), static_cast<std::size_t>(hb));
    joined[ha] = joined[hb] = 1;
  }
  std::map<std::size_t, int> group_of_root;
  for (std::size_t h = 0; h < plan.hubs.size(); ++h) {
    if (!joined[h]) continue;
    const auto [it, fresh] = group_of_root.emplace(sets.root(h), static_cast<int>(out.groups.size()));
    if (fresh) out.groups.emplace_back();
    out.of_hub[h] = it->second;
    out.groups[it->second].hubs.push_back(h);
  }
  require_union_memory(plan, out, contacts, std::count(short_beam.begin(), short_beam.end(), 1));
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!plan.frustums[e].exists) continue;
    const int ga = out.of_hub[plan.ends[2 * e].hub], gb = out.of_hub[plan.ends[2 * e + 1].hub];
    out.inner[e] = ga >= 0 && ga == gb;
  }
  for (std::size_t g = 0; g < out.groups.size(); ++g) {
    bool has_short = false;
    for (std::size_t h : out.groups[g].hubs)
      for (const auto& stump : plan.hubs[h].stumps) has_short = has_short || short_beam[stump.first];
    // Rings of short beams turned three ways (stagger_ring) before a group is given up.
    for (int attempt = 0;; ++attempt) {
      try {
        unite_group(plan, out, short_beam, g, attempt, progress);
        break;
      } catch (const std::runtime_error& e) {
        if (!has_short || attempt == 2 || !is_geometry_failure(e)) throw;
      }
    }
  }
  return out;
}

}  // namespace steady
