#include "steady/properties/hub_union.hpp"

#include <BRepAdaptor_Surface.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <GProp_GProps.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <gp_Pln.hxx>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <string>
#include <tuple>

#include "steady/core/errors.hpp"
#include "properties/hub_solid.hpp"

namespace steady {

namespace {

gp_Pnt pnt(const Vec3& v) { return gp_Pnt(v.x, v.y, v.z); }
gp_Dir dir(const Vec3& v) { return gp_Dir(v.x, v.y, v.z); }

// The pieces of a hub as OpenCASCADE primitives: its ball and, per stump, the frustum of the beam's cone from
// inside the ball to the cut. A frustum starts halfway between the plane where the cone touches its end ball
// and the exit circle, where its circle lies inside the ball, so ball and frustum cross transversally (in the
// hull model the two planes coincide and the cone touches the ball: the result is checked below).
std::vector<TopoDS_Shape> hub_pieces(const Hub& hub, const Vec3& origin) {
  std::vector<TopoDS_Shape> pieces;
  pieces.push_back(BRepPrimAPI_MakeSphere(pnt(hub.ball.center - origin), hub.ball.radius).Shape());
  for (const Stump& s : hub.stumps) {
    const BeamCone& cone = s.cone;
    if (!cone.has_lateral_surface()) continue;  // one end ball inside the other: the beam adds nothing
    const double x0 = 0.5 * (cone.ra * cone.sin_phi + s.exit_position);
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

TopoDS_Shape fuse_all(const std::vector<TopoDS_Shape>& pieces, const std::string& what) {
  if (pieces.size() == 1) return pieces.front();
  TopTools_ListOfShape args, tools;
  args.Append(pieces.front());
  for (std::size_t i = 1; i < pieces.size(); ++i) tools.Append(pieces[i]);
  BRepAlgoAPI_Fuse fuse;
  fuse.SetArguments(args);
  fuse.SetTools(tools);
  fuse.SetRunParallel(Standard_False);  // clusters already run in parallel
  fuse.Build();
  if (!fuse.IsDone() || fuse.HasErrors())
    throw std::runtime_error("hub union: OpenCASCADE's Fuse failed on " + what);
  return fuse.Shape();
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

struct NodeKey {
  std::int64_t i, j, k;
  int n;
  bool operator<(const NodeKey& o) const { return std::tie(i, j, k, n) < std::tie(o.i, o.j, o.k, o.n); }
};

std::int64_t find_root(std::vector<std::int64_t>& parent, std::int64_t x) {
  while (parent[x] != x) x = parent[x] = parent[parent[x]];
  return x;
}

}  // namespace

TopoDS_Shape hub_solid(const Hub& hub, const Vec3& origin) {
  return fuse_all(hub_pieces(hub, origin), "a hub");
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
  std::vector<std::vector<std::int64_t>> clusters;
  for (auto& [root, members] : by_root) clusters.push_back(std::move(members));
  out.clusters = static_cast<std::int64_t>(clusters.size());
  out.hubs = static_cast<std::int64_t>(nodes.size());

  const double tolerance = std::max(1e-10, options.tolerance);
  std::vector<MassMoments> corrections(clusters.size());
  std::vector<double> errors(clusters.size(), 0.0), volumes(clusters.size(), 0.0);
  progress.set_total(static_cast<std::int64_t>(clusters.size()));
  tbb::parallel_for(std::size_t(0), clusters.size(), [&](std::size_t c) {
    progress.check();
    std::vector<TopoDS_Shape> pieces;
    std::vector<CutPlane> cuts;
    MassMoments hub_sum;
    double largest = 0.0;
    for (std::int64_t n : clusters[c]) {
      const Hub h = hub(lattice, nodes[n]);
      const HubProperties p = hub_properties(hub_shape(h), options);
      SimilarityTransform shift;
      shift.translation = h.ball.center - reference;
      hub_sum += transformed(p.moments, shift);
      largest = std::max(largest, p.moments.volume);
      for (TopoDS_Shape& s : hub_pieces(h, reference)) pieces.push_back(std::move(s));
      for (const Stump& s : h.stumps) cuts.push_back({s.cut.center - reference, s.cut.normal, s.cut.radius});
    }
    const std::string what = "the cluster of hubs around " + to_string(nodes[clusters[c].front()]);
    const TopoDS_Shape united = fuse_all(pieces, what);
    if (!BRepCheck_Analyzer(united).IsValid())
      throw std::runtime_error("hub union: OpenCASCADE's Fuse gave an invalid solid for " + what);
    const MassMoments u = solid_moments(united, cuts, tolerance, errors[c]);
    const double slack = 1e-7 * hub_sum.volume;
    if (!(u.volume <= hub_sum.volume + slack && u.volume >= largest - slack))
      throw std::runtime_error("hub union: OpenCASCADE's Fuse of " + what + " has volume " + std::to_string(u.volume) +
                               ", outside [" + std::to_string(largest) + ", " + std::to_string(hub_sum.volume) + "]");
    corrections[c] = u - hub_sum;
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
