#include "brep/grazing_beams.hpp"

#include <BRepAlgoAPI_Splitter.hxx>
#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <gp_Ax2.hxx>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "brep/loose_pieces.hpp"
#include "brep/occ_progress.hpp"
#include "brep/pcurve_pieces.hpp"
#include "brep/trim_phases.hpp"
#include "steady/brep/boundary_volume.hpp"
#include "steady/brep/brep_io.hpp"

namespace steady::trim {

namespace {

// Angle kept between the caps of two stumps of a hub (radians), seen from its centre: the frustum of a grazing beam
// then holds nothing of the hub's other stumps.
constexpr double kCapGap = 1e-3;
// The balance of the volumes of the faces the split made and replaced, relative to their size: the integration's
// own error is about 1e-12 (boundary_volume.hpp), the split's curves are approximations to about 1e-7 of the
// faces' size; a lost or doubled face is of the order of 1.
constexpr double kVolumeCheck = 1e-7;
// Steps along an axis after which it counts as not shown to stay outside (an axis running along the wall).
constexpr int kMaxAxisSteps = 10000;

// The half-angle of the cone of directions, from the centre of ball `ball`, through the exit circle of `beam`.
double cap_half_angle(const FlatLattice& f, const BeamFrustum& fr, std::int64_t beam, std::int64_t ball) {
  const bool at_a = f.beams[beam].a == ball;
  const double exit = at_a ? fr.exit_a : fr.exit_b;
  const double radius = (at_a ? fr.circle_a : fr.circle_b).radius;
  return std::atan2(radius, exit);
}

Vec3 direction_from(const FlatLattice& f, std::int64_t beam, std::int64_t ball) {
  return glm::normalize(f.balls[f.other_ball(beam, ball)].center - f.balls[ball].center);
}

// Whether the stump of `beam` at `ball` is clear of every other stump of that hub outside the ball.
bool alone_at(const FlatLattice& f, const std::vector<BeamFrustum>& frustums, std::int64_t beam, std::int64_t ball) {
  const double own = cap_half_angle(f, frustums[beam], beam, ball);
  const Vec3 u = direction_from(f, beam, ball);
  for (const std::int64_t* e = f.incident_begin(ball); e != f.incident_end(ball); ++e) {
    if (*e == beam || !frustums[*e].exists) continue;
    const double angle = std::acos(std::clamp(glm::dot(u, direction_from(f, *e, ball)), -1.0, 1.0));
    if (angle <= own + cap_half_angle(f, frustums[*e], *e, ball) + kCapGap) return false;
  }
  return true;
}

// Whether the axis between the exit planes stays outside `inner`, and whether the cone may reach into it. Steps by
// distances to the wall: the ball of that radius around a point outside holds none of the wall.
bool axis_outside_cone_reaching_in(const BeamFrustum& fr, const SolidBody& inner, double confusion) {
  const BeamCone& c = fr.cone;
  const double x0 = fr.exit_a, x1 = c.length - fr.exit_b;
  const Vec3 middle = c.a + 0.5 * (x0 + x1) * c.axis;
  const double reach = 0.5 * (x1 - x0) + std::max(c.radius_at(x0), c.radius_at(x1));
  if (inner.distance_lower_bound(middle) > reach) return false;  // the frustum is clear of the wall
  if (inner.contains(c.a + x0 * c.axis)) return false;
  bool reaching = false;
  double x = x0;
  for (int step = 0; step < kMaxAxisSteps; ++step) {
    const Vec3 p = c.a + x * c.axis;
    double d = inner.distance_lower_bound(p);
    if (d <= c.radius_at(x)) d = inner.exact_distance(p);  // near the wall: the exact distance
    if (d <= confusion) return false;                      // the axis touches the wall
    if (d <= c.radius_at(x)) reaching = true;
    if (x >= x1) return reaching;
    x = std::min(x1, x + d);
  }
  return false;
}

// The faces of `shape`'s solids, as oriented in them, whose TShape is not among `others` (a non-destructive Boolean
// keeps the faces it does not touch).
std::vector<TopoDS_Shape> faces_not_in(const TopoDS_Shape& shape, const std::unordered_set<const void*>& others) {
  std::vector<TopoDS_Shape> out;
  for (TopExp_Explorer s(shape, TopAbs_SOLID); s.More(); s.Next())
    for (TopExp_Explorer x(s.Current(), TopAbs_FACE); x.More(); x.Next())
      if (!others.count(x.Current().TShape().get())) out.push_back(x.Current());
  return out;
}

// The flux of (x - o)/3 through oriented faces (their share of a solid's volume, additive for one point o,
// boundary_volume.hpp), and the sum of the faces' shares taken unsigned (the scale of its integration error).
std::pair<double, double> volume_shares(const std::vector<TopoDS_Shape>& faces, const gp_Pnt& o) {
  double sum = 0.0, scale = 0.0;
  for (const TopoDS_Shape& shape : faces) {
    const double share = face_volume_share(TopoDS::Face(shape), o);
    sum += share;
    scale += std::abs(share);
  }
  return {sum, scale};
}

Bnd_Box box_of(const TopoDS_Shape& shape) {
  Bnd_Box b;
  BRepBndLib::Add(shape, b);
  return b;
}

bool same_box(const Bnd_Box& a, const Bnd_Box& b, double tolerance) {
  double a0, a1, a2, a3, a4, a5, b0, b1, b2, b3, b4, b5;
  a.Get(a0, a1, a2, a3, a4, a5);
  b.Get(b0, b1, b2, b3, b4, b5);
  return std::abs(a0 - b0) <= tolerance && std::abs(a1 - b1) <= tolerance && std::abs(a2 - b2) <= tolerance &&
         std::abs(a3 - b3) <= tolerance && std::abs(a4 - b4) <= tolerance && std::abs(a5 - b5) <= tolerance;
}

// Solids of `shape` holding a hub built whole, and the bounding boxes of those holding none (pieces).
struct SolidCensus {
  std::int64_t holding = 0;
  std::vector<Bnd_Box> pieces;
};
SolidCensus census(const TopoDS_Shape& shape, const std::unordered_set<const void*>& whole_hub_faces) {
  SolidCensus out;
  for (TopExp_Explorer s(shape, TopAbs_SOLID); s.More(); s.Next()) {
    if (holds_a_whole_hub(s.Current(), whole_hub_faces))
      ++out.holding;
    else
      out.pieces.push_back(box_of(s.Current()));
  }
  return out;
}

// An axis-aligned box around a frustum, padded by 1.5 times its largest radius (bounding boxes of B-spline faces
// are their control polygons').
struct FrustumBox {
  Vec3 lo, hi;
  bool holds(const Bnd_Box& b) const {  // b inside
    double x0, y0, z0, x1, y1, z1;
    b.Get(x0, y0, z0, x1, y1, z1);
    return x0 >= lo.x && y0 >= lo.y && z0 >= lo.z && x1 <= hi.x && y1 <= hi.y && z1 <= hi.z;
  }
};

}  // namespace

std::vector<std::int64_t> grazing_beams(const FlatLattice& f, const std::vector<BeamFrustum>& frustums,
                                        const SolidBody& inner, Progress& progress) {
  const double confusion = 1e-9 * inner.size();
  std::vector<std::int64_t> out;
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if ((e & 255) == 0) progress.check();
    const BeamFrustum& fr = frustums[e];
    if (!fr.exists || !axis_outside_cone_reaching_in(fr, inner, confusion)) continue;
    if (alone_at(f, frustums, e, f.beams[e].a) && alone_at(f, frustums, e, f.beams[e].b)) out.push_back(e);
  }
  return out;
}

GrazingSplit split_off_grazing_beams(const TopoDS_Shape& lattice, const std::vector<BeamFrustum>& frustums,
                                     const std::vector<std::int64_t>& beams,
                                     const std::unordered_set<const void*>& whole_hub_faces, Progress& progress) {
  GrazingSplit out;
  out.lattice = lattice;
  if (beams.empty()) return out;
  TopTools_ListOfShape args, tools;
  args.Append(lattice);
  std::vector<FrustumBox> boxes;
  Vec3 middle(0.0);  // of the frustums' bases: the point the volumes below are integrated about
  for (const std::int64_t e : beams) {
    const BeamFrustum& fr = frustums[e];
    const BeamCone& c = fr.cone;
    const double x0 = fr.exit_a, x1 = c.length - fr.exit_b, r0 = c.radius_at(x0), r1 = c.radius_at(x1);
    const Vec3 p = c.a + x0 * c.axis;
    middle += p / static_cast<double>(beams.size());
    const gp_Ax2 ax(gp_Pnt(p.x, p.y, p.z), gp_Dir(c.axis.x, c.axis.y, c.axis.z));
    // The beam's own cone: the lens's side is on it, and OpenCASCADE treats the two as one surface.
    if (std::abs(r0 - r1) < 1e-12 * std::max(r0, r1))
      tools.Append(BRepPrimAPI_MakeCylinder(ax, r0, x1 - x0).Shape());
    else
      tools.Append(BRepPrimAPI_MakeCone(ax, r0, r1, x1 - x0).Shape());
    const Vec3 q = c.a + x1 * c.axis;
    const double pad = 1.5 * std::max(r0, r1);
    boxes.push_back({glm::min(p, q) - Vec3(pad), glm::max(p, q) + Vec3(pad)});
  }
  BRepAlgoAPI_Splitter splitter;
  splitter.SetArguments(args);
  splitter.SetTools(tools);
  splitter.SetNonDestructive(Standard_True);  // faces the frustums miss stay the very same (whole hubs are found so)
  splitter.SetRunParallel(Standard_True);
  OccProgress occ(progress);
  splitter.Build(occ.range());
  occ.finish();
  std::ostringstream why;
  why.precision(12);
  if (!splitter.IsDone() || splitter.HasErrors()) {
    why << "OpenCASCADE's split of the lattice along " << beams.size() << " grazing beams failed";
    out.kept_reason = why.str();
    return out;
  }
  const TopoDS_Shape split = splitter.Shape();
  const SolidCensus before = census(lattice, whole_hub_faces), after = census(split, whole_hub_faces);
  // No frustum reached into the lattice: it stays as it was (not the Splitter's copy of it).
  if (after.pieces.size() == before.pieces.size() && after.holding == before.holding) return out;
  give_edges_their_own_pcurves(split);  // the split kept the parents' pcurves on pieces of split edges
  const std::unordered_set<const void*> lattice_faces = face_set(lattice);
  // A piece the split made lies in a frustum; one it left alone (the OpenCASCADE copy of a piece the lattice had,
  // which may come with new faces) has the same box as before.
  const double size = std::sqrt(box_of(lattice).SquareExtent());
  const auto unexplained = [&](const Bnd_Box& piece) {
    return std::none_of(boxes.begin(), boxes.end(), [&](const FrustumBox& box) { return box.holds(piece); }) &&
           std::none_of(before.pieces.begin(), before.pieces.end(),
                        [&](const Bnd_Box& old) { return same_box(old, piece, 1e-9 * size); });
  };
  const gp_Pnt near(middle.x, middle.y, middle.z);
  // The volume changes only through the faces the split made or replaced: theirs must balance (the whole lattice's
  // integration would take several seconds).
  const std::vector<TopoDS_Shape> made = faces_not_in(split, lattice_faces),
                                  replaced = faces_not_in(lattice, face_set(split));
  const auto [added, added_scale] = volume_shares(made, near);
  const auto [removed, removed_scale] = volume_shares(replaced, near);
  if (after.holding != before.holding)
    why << after.holding << " solids hold hubs built whole after the split, " << before.holding << " before";
  else if (std::abs(added - removed) > kVolumeCheck * (added_scale + removed_scale))
    why << "the faces the split made enclose " << added - removed << " more than those it replaced";
  else if (std::any_of(after.pieces.begin(), after.pieces.end(), unexplained))
    why << "a piece split off lies outside the grazing beams' frustums";
  else if (!is_valid(split))
    why << "the split lattice is invalid";
  out.kept_reason = why.str();
  if (!out.kept_reason.empty()) return out;
  out.lattice = split;
  out.pieces = static_cast<std::int64_t>(after.pieces.size() - before.pieces.size());
  return out;
}

}  // namespace steady::trim
