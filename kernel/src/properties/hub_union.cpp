#include "steady/properties/hub_union.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pln.hxx>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

#include "steady/core/errors.hpp"
#include "lattice/hub_collars.hpp"
#include "properties/caps_past_cuts.hpp"
#include "properties/checked_fuse.hpp"
#include "properties/hub_solid.hpp"
#include "properties/shared_volume_sampling.hpp"

namespace steady {

namespace {

gp_Pnt pnt(const Vec3& v) { return gp_Pnt(v.x, v.y, v.z); }
gp_Dir dir(const Vec3& v) { return gp_Dir(v.x, v.y, v.z); }

// How a hub's pieces are laid out for its Fuse; each the same solid. OpenCASCADE's Fuse of a crowded hub depends on
// where the sphere's poles and seam lie and where the frustums start inside the ball: on the long sweep's BCC at
// node 0.45, beam/node 0.8, twisted taper, 3 of 16 hubs lost up to 15 % in every order with the sphere's axis
// along z and frustums starting halfway, and each fused whole in another layout (a turned axis, or frustums
// starting at 0.9 of the way to the exit circle).
struct PieceLayout {
  Vec3 sphere_axis{0.0, 0.0, 1.0};
  double frustum_start = 0.5;  // from the plane where the cone touches its end ball (0) to the exit circle (1)
};

// The layouts tried in turn: the first is the one every hub had before.
const PieceLayout kPieceLayouts[] = {
    {Vec3(0.0, 0.0, 1.0), 0.5},
    {Vec3(0.30, 0.70, 0.64), 0.5},
    {Vec3(-0.80, 0.10, 0.59), 0.5},
    {Vec3(0.0, 0.0, 1.0), 0.9},
    {Vec3(0.50, -0.50, 0.70), 0.9},
};

// The pieces of a hub as OpenCASCADE primitives: its ball and, per stump, the frustum of the beam's cone from
// inside the ball to the cut. A frustum starts between the plane where the cone touches its end ball and the exit
// circle, where its circle lies inside the ball, so ball and frustum cross transversally (in the hull model the
// two planes coincide and the cone touches the ball: the result is checked below).
std::vector<TopoDS_Shape> hub_pieces(const Hub& hub, const Vec3& origin, const PieceLayout& layout = {}) {
  std::vector<TopoDS_Shape> pieces;
  const gp_Ax2 sphere_axes(pnt(hub.ball.center - origin), dir(glm::normalize(layout.sphere_axis)));
  pieces.push_back(BRepPrimAPI_MakeSphere(sphere_axes, hub.ball.radius).Shape());
  for (const Stump& s : hub.stumps) {
    const BeamCone& cone = s.cone;
    if (!cone.has_lateral_surface()) continue;  // one end ball inside the other: the beam adds nothing
    const double touch = cone.ra * cone.sin_phi;
    const double x0 = touch + layout.frustum_start * (s.exit_position - touch);
    const double x1 = s.cut_position;
    if (!(x1 > x0)) continue;  // the node ball reaches past the cut: hub_properties refuses such hubs
    const double r0 = cone.radius_at(x0), r1 = cone.radius_at(x1);
    const gp_Ax2 ax(pnt(cone.a + x0 * cone.axis - origin), dir(cone.axis));
    if (std::abs(r0 - r1) <= 1e-12 * std::max(r0, r1))
      pieces.push_back(BRepPrimAPI_MakeCylinder(ax, r0, x1 - x0).Shape());
    else
      pieces.push_back(BRepPrimAPI_MakeCone(ax, r0, r1, x1 - x0).Shape());
  }
  return pieces;
}

// The diagonal of a box around the hubs (translated by -origin; their balls and cut disks): the scale of the
// Fuse's fuzzy values.
double hubs_extent(const std::vector<Hub>& hubs) {
  const auto bounds = hubs_bounds(hubs);
  return glm::length(bounds.second - bounds.first);
}

struct CutPlane {
  Vec3 center{0.0}, normal{0.0};
  double radius = 0.0;
};

bool on_cut_plane(const TopoDS_Face& face, const std::vector<CutPlane>& cuts) {
  BRepAdaptor_Surface surface(face, Standard_False);
  if (surface.GetType() != GeomAbs_Plane) return false;
  const gp_Pln plane = surface.Plane();
  const gp_Dir n = plane.Axis().Direction();
  const gp_Pnt p = plane.Location();
  for (const CutPlane& c : cuts) {
    if (std::abs(std::abs(n.X() * c.normal.x + n.Y() * c.normal.y + n.Z() * c.normal.z) - 1.0) > 1e-9) continue;
    const Vec3 d(p.X() - c.center.x, p.Y() - c.center.y, p.Z() - c.center.z);
    if (std::abs(glm::dot(d, c.normal)) <= 1e-9 * std::max(1.0, c.radius)) return true;
  }
  return false;
}

// Moments of a solid about the frame's origin, its area without the faces on cut planes.
MassMoments solid_moments(const TopoDS_Shape& shape, const std::vector<CutPlane>& cuts, double tolerance,
                          double& error) {
  GProp_GProps volume;
  error = BRepGProp::VolumeProperties(shape, volume, tolerance, Standard_True);
  MassMoments m;
  m.volume = volume.Mass();
  const gp_Pnt g = volume.CentreOfMass();
  const Vec3 c(g.X(), g.Y(), g.Z());
  m.first = m.volume * c;
  // OpenCASCADE gives the inertia about the centre of mass: I = tr(S) Id - S for the central second moment S.
  const gp_Mat inertia = volume.MatrixOfInertia();
  Mat3 I(0.0);
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col) I[col][r] = inertia.Value(r + 1, col + 1);
  const double trace = I[0][0] + I[1][1] + I[2][2];
  const Mat3 central = Mat3(0.5 * trace) - I;
  m.second = central + m.volume * glm::outerProduct(c, c);
  for (TopExp_Explorer x(shape, TopAbs_FACE); x.More(); x.Next()) {
    const TopoDS_Face face = TopoDS::Face(x.Current());
    if (on_cut_plane(face, cuts)) continue;
    GProp_GProps surface;
    BRepGProp::SurfaceProperties(face, surface, tolerance);
    m.area += surface.Mass();
  }
  return m;
}

// A hub fused alone, measured, and checked against its exact volume: OpenCASCADE's Fuse of a crowded hub's ball and
// frustums can return a valid solid that silently lacks a piece (seen: 8 % of an FCC hub; 10 % of a BCC hub in the
// hull model fused at once, which one by one fuses whole). A hub's pieces are exact primitives, so only the exact
// Fuses are tried. An accepted Fuse may still be off by its tolerance, and the cluster's union inherits that error
// where the hub meets no other: the correction subtracts these measured hubs, not the exact ones, so that only
// what lies where hubs meet remains (checked there by the lines). On the HubUnion tests' lattices this brought
// the volumes from 7e-10..2.4e-8 to 7e-10..1.1e-8 of BRepGProp's whole-lattice Fuse.
struct MeasuredHub {
  TopoDS_Shape solid;
  MassMoments moments;
};

// What a user can change when a Fuse fails at hubs whose beams touch their ball tangentially (as thick as the node
// there, or the hull model): OpenCASCADE's Fuses at tangent contacts are 1e-5 off or lose pieces in every order and
// layout, while slightly thinner beams cross the ball and fuse (on the long sweep's 100 densest designs other than
// octets, every one at beam/node 0.9 is measured; 12 of the 13 refused are at 1.0 or in the hull model).
std::string tangent_hint(const std::vector<Hub>& hubs) {
  for (const Hub& h : hubs)
    for (const Stump& s : h.stumps)
      if (s.cone.has_lateral_surface() && s.cone.ra >= h.ball.radius * (1.0 - 1e-9))
        return "; its beams touch their balls tangentially (as thick as the node, or the hull model), where "
               "OpenCASCADE's Fuse is unreliable: make the beams a little thinner than their nodes (beam/node 0.9 "
               "is measured in every dense design tried)";
  return "";
}

// The moments (about the node center) that the hub's whole ball, as fused, adds to hub_properties' hub
// (caps_past_cuts.hpp); throws std::runtime_error naming the hub where they cannot be had.
MassMoments checked_caps(const Hub& h) {
  std::string refusal;
  const MassMoments caps = caps_past_cuts(h, refusal);
  if (!refusal.empty())
    throw std::runtime_error("hub union: the hub of " + to_string(h.node) + " cannot be measured: " + refusal);
  return caps;
}

// Relative. Where beams touch their ball (the hull model) every Fuse of a screwed BCC hub is 1e-5 off (0.316582
// for 0.316579), and its cluster's union then differs from the hubs' sum by 1e-6 more: refused, as it should be.
constexpr double kHubFuseTolerance = 1e-6;

MeasuredHub measured_hub_solid(const Hub& h, const Vec3& origin, double exact_volume, double tolerance) {
  const std::string name = "the hub of " + to_string(h.node);
  std::vector<CutPlane> cuts;
  for (const Stump& s : h.stumps) cuts.push_back({s.cut.center - origin, s.cut.normal, s.cut.radius});
  MeasuredHub out;
  std::string first_refusal;
  for (const PieceLayout& layout : kPieceLayouts) {
    try {
      out.solid = checked_fuse(hub_pieces(h, origin, layout), hubs_extent({h}), [&](const TopoDS_Shape& solid) {
        double error = 0.0;
        out.moments = solid_moments(solid, cuts, tolerance, error);
        const double volume = out.moments.volume;
        if (std::abs(volume - exact_volume) <= kHubFuseTolerance * exact_volume) return std::string();
        return "OpenCASCADE's Fuse of " + name + " has volume " + std::to_string(volume) +
               " where the hub's exact volume is " + std::to_string(exact_volume) +
               "; its overlaps with other hubs cannot be measured";
      }, name, /*fuzzy_retries=*/false);
      return out;
    } catch (const std::runtime_error& refusal) {
      if (first_refusal.empty()) first_refusal = refusal.what();
    }
  }
  throw std::runtime_error(first_refusal + " (nor with the sphere's axis turned or the frustums starting elsewhere)" +
                           tangent_hint({h}));
}

struct NodeKey {
  std::int64_t i, j, k;
  int n;
  bool operator<(const NodeKey& o) const { return std::tie(i, j, k, n) < std::tie(o.i, o.j, o.k, o.n); }
};

std::int64_t find_root(std::vector<std::int64_t>& parent, std::int64_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

// ---- moved cuts: the exact correction without a Boolean ---------------------------------------------------

// Where the stumps of a hub run free (axial positions from its node, one per stump): beyond its collar a stump
// meets no other stump of its hub. A hub whose caps keep apart needs no room: its stumps are free at the exit.
// Tight collars (just beyond the envelope) leave the most room for moved cuts; the volume does not depend on them.
std::vector<double> free_positions(const Hub& h) {
  std::vector<double> out;
  if (!any_stump_caps_overlap(hub_shape(h))) {
    for (const Stump& s : h.stumps) out.push_back(s.exit_position);
    return out;
  }
  for (double c : core_collars(core_stumps(h), core_kind(h), kMaxCollarPosition, CollarFit::Tight))
    out.push_back(c * h.ball.radius);
  return out;
}

// Overlapping hubs of different nodes most often come from one crowded hub whose stumps meet beyond their
// beams' mid-planes: the meeting spills into the neighbours' halves (the triangle C, A, B of an FCC cell, whose
// beams CA and CB still meet past their middles, makes hubs A and B overlap). Moving those beams' cuts past the
// crowded hub's collars, by the B-rep's rule (cut_between_collars), gives every meeting back to one hub; when
// then no two hubs overlap (checked piece by piece, as the overlap report does), the lattice is again the
// disjoint union of its hubs and the correction is exact: the moved hubs' properties minus the same hubs' with
// mid-plane cuts, each from hub_properties (closed form or quadrature, no Boolean). False, with nothing added,
// when a beam has no room for its cut or overlaps remain: the caller then fuses the clusters.
bool moved_cut_correction(const Lattice& lattice, const std::vector<NodeId>& overlapping, const Vec3& reference,
                          const HubPropertiesOptions& options, HubUnionCorrection& out) {
  std::map<NodeKey, Hub> hubs;  // as built (mid-plane cuts)
  auto hub_at = [&](const NodeId& n) -> const Hub& {
    const NodeKey key{n.i, n.j, n.k, n.n};
    auto it = hubs.find(key);
    if (it == hubs.end()) it = hubs.emplace(key, hub(lattice, n)).first;
    return it->second;
  };
  std::map<NodeKey, std::vector<double>> free;
  auto free_at = [&](const Hub& h) -> const std::vector<double>& {
    const NodeKey key{h.node.i, h.node.j, h.node.k, h.node.n};
    auto it = free.find(key);
    if (it == free.end()) it = free.emplace(key, free_positions(h)).first;
    return it->second;
  };
  std::map<NodeKey, Hub> moved;  // hubs with at least one moved cut
  try {
    for (const NodeId& n : overlapping) {
      const Hub near_hub = hub_at(n);
      for (std::size_t s = 0; s < near_hub.stumps.size(); ++s) {
        const Stump& stump = near_hub.stumps[s];
        const NodeId other = stump.at_start ? lattice.beam_end(stump.beam) : lattice.beam_start(stump.beam);
        const Hub far_hub = hub_at(other);
        std::size_t t = 0;
        while (t < far_hub.stumps.size() &&
               !(far_hub.stumps[t].beam == stump.beam && far_hub.stumps[t].at_start != stump.at_start))
          ++t;
        if (t == far_hub.stumps.size()) return false;
        const double length = stump.cone.length;
        const double from = free_at(near_hub)[s];  // may lie inside the ball: the hub then ends at its cut disk
        const double to = length - free_at(far_hub)[t];
        if (!(from < to)) return false;  // no room for a cut: the beam is shorter than its two hubs need
        const double cut = cut_between_collars(from, to, stump.cut_position);
        if (cut == stump.cut_position) continue;
        for (const auto& [h, k, position] : {std::tuple<const Hub&, std::size_t, double>{near_hub, s, cut},
                                             std::tuple<const Hub&, std::size_t, double>{far_hub, t, length - cut}}) {
          const NodeKey key{h.node.i, h.node.j, h.node.k, h.node.n};
          auto it = moved.find(key);
          if (it == moved.end()) it = moved.emplace(key, h).first;
          move_cut(it->second.stumps[k], position);
        }
        ++out.moved_cuts;
      }
    }
  } catch (const InvalidInput&) {
    return false;  // a hub whose collars cannot be placed
  }
  if (moved.empty()) return false;
  for (const auto& [key, h] : moved)
    for (std::size_t s = 0; s < h.stumps.size(); ++s)
      if (h.stumps[s].cut_position < h.ball.radius && cut_disk_meets_other_stumps(h, s)) return false;
  // New overlaps can only involve pieces that overlapped before (the moved stumps cover the same beams), so the
  // overlapping hubs and the moved ones are all that need checking.
  std::vector<const Hub*> check;
  for (const NodeId& n : overlapping) {
    const auto it = moved.find(NodeKey{n.i, n.j, n.k, n.n});
    check.push_back(it != moved.end() ? &it->second : &hub_at(n));
  }
  for (const auto& [key, h] : moved)
    if (std::find(overlapping.begin(), overlapping.end(), h.node) == overlapping.end()) check.push_back(&h);
  for (std::size_t a = 0; a < check.size(); ++a)
    for (std::size_t b = a + 1; b < check.size(); ++b)
      if (hubs_overlap(*check[a], *check[b])) return false;
  MassMoments correction;
  for (const auto& [key, h] : moved) {
    SimilarityTransform shift;
    shift.translation = h.ball.center - reference;
    correction += transformed(hub_properties(hub_shape(h), options).moments, shift);
    correction -= transformed(hub_properties(hub_shape(hub_at(h.node)), options).moments, shift);
  }
  out.moments = correction;
  out.moved_cut_hubs = static_cast<std::int64_t>(moved.size());
  return true;
}

}  // namespace

TopoDS_Shape hub_solid(const Hub& hub, const Vec3& origin) {
  const double exact = hub_properties(hub_shape(hub)).moments.volume + checked_caps(hub).volume;
  return measured_hub_solid(hub, origin, exact, 1e-9).solid;
}

HubUnionCorrection hub_union_correction(const Lattice& lattice, const std::vector<HubOverlap>& overlaps,
                                        const Vec3& reference, const HubPropertiesOptions& options,
                                        Progress& progress) {
  HubUnionCorrection out;
  if (overlaps.empty()) return out;
  // Clusters: connected components of the overlap pairs.
  std::map<NodeKey, std::int64_t> index;
  std::vector<NodeId> nodes;
  auto id_of = [&](const NodeId& n) {
    const auto [it, added] = index.emplace(NodeKey{n.i, n.j, n.k, n.n}, static_cast<std::int64_t>(nodes.size()));
    if (added) nodes.push_back(n);
    return it->second;
  };
  std::vector<std::pair<std::int64_t, std::int64_t>> pairs;
  for (const HubOverlap& o : overlaps) pairs.emplace_back(id_of(o.a), id_of(o.b));
  if (static_cast<std::int64_t>(nodes.size()) > kMaxUnionHubs)
    throw ResourceLimit("lattice: " + std::to_string(nodes.size()) +
                        " hubs overlap hubs of other nodes; the exact union is computed for up to " +
                        std::to_string(kMaxUnionHubs) + " (thin the beams or nodes, or space the groups further apart)");
  std::vector<std::int64_t> parent(nodes.size());
  std::iota(parent.begin(), parent.end(), 0);
  for (const auto& [a, b] : pairs) parent[find_root(parent, a)] = find_root(parent, b);
  std::map<std::int64_t, std::vector<std::int64_t>> by_root;
  for (std::int64_t n = 0; n < static_cast<std::int64_t>(nodes.size()); ++n) by_root[find_root(parent, n)].push_back(n);
  out.hubs = static_cast<std::int64_t>(nodes.size());
  if (moved_cut_correction(lattice, nodes, reference, options, out)) return out;
  out.moved_cuts = 0;
  std::vector<std::vector<std::int64_t>> clusters;
  for (auto& [root, members] : by_root) clusters.push_back(std::move(members));
  out.clusters = static_cast<std::int64_t>(clusters.size());

  const double tolerance = std::max(1e-10, options.tolerance);
  std::vector<MassMoments> corrections(clusters.size());
  std::vector<double> errors(clusters.size(), 0.0), volumes(clusters.size(), 0.0);
  progress.set_total(static_cast<std::int64_t>(clusters.size()));
  tbb::parallel_for(std::size_t(0), clusters.size(), [&](std::size_t c) {
    progress.check();
    std::vector<TopoDS_Shape> hub_solids;
    std::vector<Hub> members;
    std::vector<CutPlane> cuts;
    MassMoments hub_sum;  // of the hubs as fused and measured
    MassMoments caps;     // of their balls beyond their cuts: in the Fuse's hubs, not in hub_properties'
    double largest = 0.0;
    for (std::int64_t n : clusters[c]) {
      const Hub h = hub(lattice, nodes[n]);
      const HubProperties p = hub_properties(hub_shape(h), options);
      SimilarityTransform shift;
      shift.translation = h.ball.center - reference;
      const MassMoments hub_caps = transformed(checked_caps(h), shift);
      MeasuredHub measured = measured_hub_solid(h, reference, p.moments.volume + hub_caps.volume, tolerance);
      hub_sum += measured.moments;
      caps += hub_caps;
      largest = std::max(largest, measured.moments.volume);
      hub_solids.push_back(std::move(measured.solid));
      for (const Stump& s : h.stumps) cuts.push_back({s.cut.center - reference, s.cut.normal, s.cut.radius});
      members.push_back(h);
    }
    const std::string what = "the cluster of hubs around " + to_string(nodes[clusters[c].front()]);
    // Lines through where the hubs meet: 1.6 million put the shared volume of a 32-hub octet cluster within
    // 2.3e-5 to 1.5e-4 of itself in 8 to 10 s (docs/properties.md). With 400,000 lines and 6 sigma allowed, a Fuse
    // 2.7e-4 of its lattice off passed at 5.6 sigma; now it lies 8.3 sigma out.
    constexpr int kLines = 1600000;
    const std::pair<double, double> sampled = sampled_shared_volume(members, kLines, 0x5eed + c);
    const double shared = sampled.first, sigma = sampled.second;  // named copies: a lambda below reads them
    MassMoments u;
    try {
      checked_fuse(hub_solids, hubs_extent(members), [&](const TopoDS_Shape& united) {
        if (!BRepCheck_Analyzer(united).IsValid()) return "OpenCASCADE's Fuse gave an invalid solid for " + what;
        u = solid_moments(united, cuts, tolerance, errors[c]);
        const double slack = 1e-7 * hub_sum.volume;
        if (!(u.volume <= hub_sum.volume + slack && u.volume >= largest - slack))
          return "OpenCASCADE's Fuse of " + what + " has volume " + std::to_string(u.volume) + ", outside [" +
                 std::to_string(largest) + ", " + std::to_string(hub_sum.volume) + "]";
        // The Fuse's shared volume against sampling where the hubs meet (the slack: the hubs' measured volumes).
        const double fused_shared = hub_sum.volume - u.volume;
        if (!(std::abs(fused_shared - shared) <= 5.0 * sigma + 1e-7 * hub_sum.volume))
          return "OpenCASCADE's Fuse of " + what + " has volume " + std::to_string(u.volume) + ", so its hubs share " +
                 std::to_string(fused_shared) + ", where sampling their meetings gives " + std::to_string(shared) +
                 " +- " + std::to_string(sigma);
        return std::string();
      }, what);
    } catch (const std::runtime_error& refusal) {
      throw std::runtime_error(refusal.what() + tangent_hint(members));
    }
    corrections[c] = u - hub_sum + caps;  // the sum over hubs holds hub_properties', without the caps
    volumes[c] = u.volume;
    progress.advance();
  });
  double total_volume = 0.0, total_error = 0.0;
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    out.moments += corrections[c];
    total_volume += volumes[c];
    total_error += errors[c] * volumes[c];
  }
  out.volume_error = total_volume > 0.0 ? total_error / total_volume : 0.0;
  return out;
}

}  // namespace steady
