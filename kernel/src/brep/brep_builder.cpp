#include "brep/brep_pieces.hpp"

#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepBndLib.hxx>
#include <Bnd_Box.hxx>
#include <BRep_Builder.hxx>
#include <ShapeFix_ShapeTolerance.hxx>
#include <BRep_Tool.hxx>
#include <GC_MakeCircle.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom2d_Line.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Line.hxx>
#include <Geom_Plane.hxx>
#include <Geom_SphericalSurface.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <mutex>
#include <tuple>
#include <chrono>
#include <map>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "brep/foreign_groups.hpp"
#include "brep/part_check.hpp"
#include "core/disjoint_sets.hpp"
#include "brep/pcurve_pieces.hpp"
#include "brep/sphere_pcurve.hpp"
#include "steady/lattice/beam_frustum.hpp"
#include "lattice/circle_frames.hpp"
#include "steady/query/clean_check.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"
#include "lattice/hub_catalog.hpp"
#include "brep/hub_core.hpp"
#include "brep/hub_group.hpp"
#include "steady/core/memory_budget.hpp"

namespace steady {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// A beam's seam meets an existing vertex of a circle when their parameters agree to this (radians); otherwise the
// circle gets one more vertex.
constexpr double kSameVertexAngle = 1e-9;
// Below this |sin(half-angle)| a beam is a cylinder: OpenCASCADE refuses cones of (near) zero angle.
constexpr double kCylinderSine = 1e-12;
// A cut circle shared between two builds (band and interior of a trim) lies where both builds cut its beam: their
// cut fractions are the same numbers, so only rounding separates the centres (relative to the beam's length).
constexpr double kCutCircleMismatch = 1e-9;
// Memory of one face with its edges, vertices, curves and pcurves (measured: 41,000 faces of a 30,000-beam lattice
// took 209 MB, about 5 KB each; shared pcurves of similar hubs keep it there), with headroom.
constexpr std::uint64_t kBytesPerFace = 8192;

gp_Pnt pnt(const Vec3& v) { return gp_Pnt(v.x, v.y, v.z); }
gp_Dir dir(const Vec3& v) { return gp_Dir(v.x, v.y, v.z); }

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}


// A circle around a beam where faces meet: an exit circle on a clean hub's sphere, a core's collar, a cut, or a
// joint. Its edges run between its vertices.
struct Ring {
  Handle(Geom_Circle) curve;
  Circle circle;                  // normal: the curve's axis
  Vec3 e1{0.0}, e2{0.0};          // world directions of parameters 0 and pi/2
  std::vector<double> params;     // vertex parameters, sorted, in [params[0], params[0] + 2 pi)
  std::vector<TopoDS_Vertex> vertices;
  std::vector<TopoDS_Edge> edges; // edges[k] from params[k] to params[k+1] (the last wraps by 2 pi)
  bool fixed = false;             // its vertices exist already (a core's collar, a cut built earlier)
  double tolerance = kBrepTolerance;
  double edge_end(std::size_t k) const { return k + 1 < params.size() ? params[k + 1] : params[0] + kTwoPi; }
  double param_of(const Vec3& d) const { return std::atan2(glm::dot(d, e2), glm::dot(d, e1)); }
  Vec3 direction_of(double t) const { return std::cos(t) * e1 + std::sin(t) * e2; }
};

// A clean hub's exit circle: where its sphere's layout puts it.
struct EndCircle : Ring {
  std::int64_t hub = -1;
  int slot = -1;
  double axial = 0.0;  // distance of the circle's plane from its node's center, along the beam
};

enum class BeamKind { None, Whole, HalfA, HalfB, Split };

// How a beam's conical faces run: rings from node a's side to node b's, and the seam of each segment.
struct BeamPlan {
  std::vector<int> rings;        // 0: end a, 1: end b, 2: the cut, 3 + k: joint k
  std::vector<double> joints_v;  // cone position v of each joint
  std::vector<Vec3> seam;        // per segment: the direction of its seam (orthogonal to the axis)
};

struct BeamWork {
  BeamKind kind = BeamKind::None;
  EndCircle end[2];
  Ring cut;
  bool cut_is_new = false;
  std::vector<Ring> joints;
  BeamPlan plan;
  std::vector<TopoDS_Face> cones;  // per segment
  std::vector<int> cone_side;      // per segment: 0 when on node a's side of the cut, 1 on node b's
  TopoDS_Face cap[2];              // disks closing the a-side / b-side piece at the cut

  // The ring a plan names: 0 and 1 the ends at balls a and b, 2 the cut, 3 and up the joints.
  Ring& ring(int id) {
    if (id < 2) return end[id];
    if (id == 2) return cut;
    return joints[id - 3];
  }
};

struct HubWork {
  std::int64_t ball = -1;
  std::vector<std::pair<std::int64_t, int>> stumps;  // (beam, end)
  int kind = 0;  // 0: clean (a sphere with holes), 1: hull core, 2: transversal core
  std::vector<TopoDS_Face> faces;
};

struct ShapeWork {
  SphereLayout layout;
  std::vector<std::vector<ArcPcurve>> pcurves;  // per circle, per arc
  double max_error = 0.0;
  std::shared_ptr<const HubCore> core;           // for core hubs
  bool tight = false;                            // its core rebuilt with tight collars (tighten_short_beams)
};

Handle(Geom2d_Line) line2d(double u, double v, double du, double dv) {
  return new Geom2d_Line(gp_Pnt2d(u, v), gp_Dir2d(du, dv));
}

TopoDS_Vertex make_vertex(const BRep_Builder& b, const gp_Pnt& p, double tol) {
  TopoDS_Vertex v;
  b.MakeVertex(v, p, tol);
  return v;
}

// The spherical face of one hub: circles, seam pieces, pole edges, wires.
void build_sphere_face(const BRep_Builder& b, const Ball& ball, const HubPlacement& place, const ShapeWork& shape,
                       HubWork& hub, std::vector<BeamWork>& beams) {
  const SphereLayout& L = shape.layout;
  const Mat3& M = place.rotation;
  const double R = ball.radius;
  const double tol = std::max(kBrepTolerance, 2.0 * R * (shape.max_error + kHubMatchTolerance));
  const Vec3 zw = glm::normalize(M * L.z), xw0 = M * L.x;
  const Vec3 xw = glm::normalize(xw0 - glm::dot(xw0, zw) * zw), yw = glm::cross(zw, xw);
  Handle(Geom_SphericalSurface) surface = new Geom_SphericalSurface(gp_Ax3(pnt(ball.center), dir(zw), dir(xw)), R);
  TopoDS_Face face;
  b.MakeFace(face, surface, kBrepTolerance);

  // Circles: 3D curves, vertices and edges with their (u, v) curves.
  const int n = static_cast<int>(hub.stumps.size());
  auto end_of = [&](int slot) -> EndCircle& { return beams[hub.stumps[slot].first].end[hub.stumps[slot].second]; };
  for (int s = 0; s < n; ++s) {
    EndCircle& ec = end_of(s);
    ec.tolerance = tol;
    ec.curve = new Geom_Circle(gp_Ax2(pnt(ec.circle.center), dir(ec.circle.normal), dir(ec.e1)), ec.circle.radius);
    ec.vertices.clear();
    for (double p : ec.params) ec.vertices.push_back(make_vertex(b, ec.curve->Value(p), tol));
    const CircleLayout& cl = L.circles[s];
    ec.edges.clear();
    for (std::size_t k = 0; k < ec.params.size(); ++k) {
      const double t0 = ec.params[k], t1 = ec.edge_end(k), mid = 0.5 * (t0 + t1);
      std::size_t arc = 0;
      while (arc + 1 < cl.arcs.size() && mid > cl.arcs[arc].t1) ++arc;
      TopoDS_Edge e;
      b.MakeEdge(e, ec.curve, tol);
      b.Add(e, ec.vertices[k].Oriented(TopAbs_FORWARD));
      b.Add(e, ec.vertices[(k + 1) % ec.params.size()].Oriented(TopAbs_REVERSED));
      b.UpdateEdge(e, edge_pcurve(shape.pcurves[s][arc].curve, t0, t1), face, tol);
      b.Range(e, t0, t1);
      ec.edges.push_back(e);
    }
  }
  auto own_vertex = [&](int slot, int own) -> const TopoDS_Vertex& {
    const EndCircle& ec = end_of(slot);
    const double p = L.circles[slot].own_vertices[own];
    const std::size_t k = std::lower_bound(ec.params.begin(), ec.params.end(), p - 1e-12) - ec.params.begin();
    return ec.vertices[k];
  };

  // Seam stops from bottom to top: (latitude, vertex).
  std::vector<std::pair<double, TopoDS_Vertex>> stops;
  TopoDS_Vertex south_pole, north_pole;
  if (L.south < 0) {
    south_pole = make_vertex(b, pnt(ball.center - R * zw), tol);
    stops.emplace_back(-M_PI / 2, south_pole);
  } else {
    stops.emplace_back(L.circles[L.south].crossing_v[0], own_vertex(L.south, 0));
  }
  for (int s : L.straddles) {
    stops.emplace_back(L.circles[s].crossing_v[0], own_vertex(s, 0));
    stops.emplace_back(L.circles[s].crossing_v[1], own_vertex(s, 1));
  }
  if (L.north < 0) {
    north_pole = make_vertex(b, pnt(ball.center + R * zw), tol);
    stops.emplace_back(M_PI / 2, north_pole);
  } else {
    stops.emplace_back(L.circles[L.north].crossing_v[0], own_vertex(L.north, 0));
  }
  // The seam's circle starts at the south pole (t = latitude + pi/2), so that its ranges lie in [0, pi]: a STEP
  // reader finds a circle's range from its vertices in [0, 2 pi), and a range below 0 came back shifted by 2 pi
  // from the seam's lines, which it then dropped and rebuilt.
  Handle(Geom_Circle) meridian = new Geom_Circle(gp_Ax2(pnt(ball.center), dir(-yw), dir(-zw)), R);
  Handle(Geom2d_Line) seam_right = line2d(kTwoPi, -M_PI / 2, 0.0, 1.0), seam_left = line2d(0.0, -M_PI / 2, 0.0, 1.0);
  std::vector<TopoDS_Edge> seam;  // piece k joins stops[2k] and stops[2k+1]
  for (std::size_t k = 0; k + 1 < stops.size(); k += 2) {
    TopoDS_Edge e;
    b.MakeEdge(e, meridian, tol);
    b.Add(e, stops[k].second.Oriented(TopAbs_FORWARD));
    b.Add(e, stops[k + 1].second.Oriented(TopAbs_REVERSED));
    b.UpdateEdge(e, seam_right, seam_left, face, tol);
    b.Range(e, stops[k].first + M_PI / 2, stops[k + 1].first + M_PI / 2);
    seam.push_back(e);
  }
  auto pole_edge = [&](const TopoDS_Vertex& v, double lat) {
    TopoDS_Edge e;
    b.MakeEdge(e);
    b.UpdateEdge(e, line2d(0.0, lat, 1.0, 0.0), face, tol);
    b.Add(e, v.Oriented(TopAbs_FORWARD));
    b.Add(e, v.Oriented(TopAbs_REVERSED));
    b.Degenerated(e, true);
    b.Range(e, 0.0, kTwoPi);
    return e;
  };
  // The edges of one arc of a circle, reversed, in decreasing parameter order: on the sphere every circle runs
  // clockwise in (u, v), its hole on the right.
  auto add_arc = [&](TopoDS_Wire& w, int slot, ArcBranch branch) {
    const EndCircle& ec = end_of(slot);
    const CircleLayout& cl = L.circles[slot];
    const CircleArc& arc = cl.arcs[0].branch == branch ? cl.arcs[0] : cl.arcs[1];
    for (std::size_t k = ec.params.size(); k-- > 0;) {
      const double mid = 0.5 * (ec.params[k] + ec.edge_end(k));
      if (mid > arc.t0 && mid < arc.t1) b.Add(w, ec.edges[k].Oriented(TopAbs_REVERSED));
    }
  };

  TopoDS_Wire outer;
  b.MakeWire(outer);
  if (L.south < 0) {
    b.Add(outer, pole_edge(south_pole, -M_PI / 2).Oriented(TopAbs_FORWARD));
  } else {
    add_arc(outer, L.south, ArcBranch::South);
  }
  for (std::size_t k = 0; k < seam.size(); ++k) {  // up the right side
    b.Add(outer, seam[k].Oriented(TopAbs_FORWARD));
    if (k < L.straddles.size()) add_arc(outer, L.straddles[k], ArcBranch::Right);
  }
  if (L.north < 0) {
    b.Add(outer, pole_edge(north_pole, M_PI / 2).Oriented(TopAbs_REVERSED));
  } else {
    add_arc(outer, L.north, ArcBranch::North);
  }
  for (std::size_t k = seam.size(); k-- > 0;) {  // down the left side
    b.Add(outer, seam[k].Oriented(TopAbs_REVERSED));
    if (k > 0) add_arc(outer, L.straddles[k - 1], ArcBranch::Left);
  }
  outer.Closed(true);
  b.Add(face, outer);
  for (int s = 0; s < n; ++s) {
    if (L.circles[s].role != CircleRole::Inner) continue;
    TopoDS_Wire hole;
    b.MakeWire(hole);
    add_arc(hole, s, ArcBranch::Inner);
    hole.Closed(true);
    b.Add(face, hole);
  }
  hub.faces = {face};
}

// A station of a beam's conical face: a circle at some axial position, with its edges.
struct Station {
  const std::vector<TopoDS_Edge>* edges;
  const std::vector<double>* params;  // edges[k] spans params[k] .. params[k+1] (wrapping)
  TopoDS_Vertex seam_vertex;
  double seam_param = 0.0;
  double sign = 1.0;  // +1: the circle turns counterclockwise about the beam axis, -1: clockwise
  double v = 0.0;     // position along the cone's generator
  double tolerance = kBrepTolerance;
};

void build_cone_face(const BRep_Builder& b, const BeamFrustum& fr, const Vec3& seam_dir, const Station& lower,
                     const Station& upper, TopoDS_Face& out) {
  const Vec3 axis = fr.cone.axis;
  const Vec3 origin = fr.circle_a.center;
  const double r0 = fr.circle_a.radius;
  const double sin_a = -fr.cone.sin_phi, cos_a = fr.cone.cos_phi;  // OpenCASCADE's semi-angle is -phi
  const gp_Ax3 frame(pnt(origin), dir(axis), dir(seam_dir));
  Handle(Geom_Surface) surface;
  if (std::abs(sin_a) < kCylinderSine)
    surface = new Geom_CylindricalSurface(frame, r0);
  else
    surface = new Geom_ConicalSurface(frame, std::asin(sin_a), r0);
  TopoDS_Face face;
  b.MakeFace(face, surface, kBrepTolerance);
  const double tol = std::max(lower.tolerance, upper.tolerance);
  // Seam: the generator at u = 0, parameterized by v (the cone's v is arc length along generators).
  const Vec3 p00 = origin + r0 * seam_dir;
  const Vec3 generator = sin_a * seam_dir + cos_a * axis;
  Handle(Geom_Line) line = new Geom_Line(gp_Ax1(pnt(p00), dir(generator)));
  TopoDS_Edge seam;
  b.MakeEdge(seam, line, tol);
  b.Add(seam, lower.seam_vertex.Oriented(TopAbs_FORWARD));
  b.Add(seam, upper.seam_vertex.Oriented(TopAbs_REVERSED));
  b.UpdateEdge(seam, line2d(kTwoPi, 0.0, 0.0, 1.0), line2d(0.0, 0.0, 0.0, 1.0), face, tol);
  b.Range(seam, lower.v, upper.v);

  struct Placed {
    double u0;
    TopoDS_Edge edge;
  };
  auto place = [&](const Station& st, bool is_lower) {
    std::vector<Placed> out;
    const std::size_t n = st.params->size();
    for (std::size_t k = 0; k < n; ++k) {
      const double t0 = (*st.params)[k], t1 = k + 1 < n ? (*st.params)[k + 1] : (*st.params)[0] + kTwoPi;
      const double u_mid = st.sign * (0.5 * (t0 + t1) - st.seam_param);
      const double shift = -kTwoPi * std::floor(u_mid / kTwoPi);
      // u(t) = sign * (t - seam_param) + shift, on the line v = st.v.
      const TopoDS_Edge& e = (*st.edges)[k];
      b.UpdateEdge(e, line2d(shift - st.sign * st.seam_param, st.v, st.sign, 0.0), face, tol);
      b.Range(e, t0, t1);
      const double ua = st.sign * (t0 - st.seam_param) + shift, ub = st.sign * (t1 - st.seam_param) + shift;
      // Lower station runs in +u, upper in -u.
      const bool forward = is_lower ? st.sign > 0.0 : st.sign < 0.0;
      out.push_back({std::min(ua, ub), TopoDS::Edge(e.Oriented(forward ? TopAbs_FORWARD : TopAbs_REVERSED))});
    }
    std::sort(out.begin(), out.end(), [&](const Placed& x, const Placed& y) { return is_lower ? x.u0 < y.u0 : x.u0 > y.u0; });
    return out;
  };
  TopoDS_Wire wire;
  b.MakeWire(wire);
  for (const Placed& p : place(lower, true)) b.Add(wire, p.edge);
  b.Add(wire, seam.Oriented(TopAbs_FORWARD));
  for (const Placed& p : place(upper, false)) b.Add(wire, p.edge);
  b.Add(wire, seam.Oriented(TopAbs_REVERSED));
  wire.Closed(true);
  b.Add(face, wire);
  out = face;
}

}  // namespace

BrepSelection BrepSelection::everything(const FlatLattice& lattice) {
  BrepSelection s;
  s.balls.assign(lattice.ball_count(), 1);
  s.beams.assign(lattice.beam_count(), 1);
  return s;
}

namespace {


// The frustums of the lattice with the selection's cut places.
std::vector<BeamFrustum> selected_frustums(const FlatLattice& f, const BrepSelection& selection) {
  std::vector<BeamFrustum> frustums = beam_frustums(f);
  if (!selection.cut_fractions.empty()) {
    if (static_cast<std::int64_t>(selection.cut_fractions.size()) != f.beam_count())
      fail_input("selection", "needs one cut fraction per beam");
    for (std::int64_t e = 0; e < f.beam_count(); ++e) {
      const double t = selection.cut_fractions[e];
      if (!(t > 0.0 && t < 1.0)) fail_input("selection", "cut fraction of beam " + std::to_string(e) + " outside (0, 1)");
      frustums[e].cut_fraction = t;
    }
  }
  return frustums;
}

gp_Trsf placement_transform(const Ball& ball, const Mat3& m) { return hub_placement(ball.center, ball.radius, m); }

// A ring read from an existing closed circle edge set (a core's collar copied into place, or a cut built before).
void ring_from_edges(Ring& ring, const Handle(Geom_Circle)& curve, const std::vector<double>& params,
                     const std::vector<TopoDS_Vertex>& vertices, const std::vector<TopoDS_Edge>& edges) {
  ring.curve = curve;
  const gp_Ax2& ax = curve->Position();
  ring.circle = {Vec3(ax.Location().X(), ax.Location().Y(), ax.Location().Z()),
                 Vec3(ax.Direction().X(), ax.Direction().Y(), ax.Direction().Z()), curve->Radius()};
  ring.e1 = Vec3(ax.XDirection().X(), ax.XDirection().Y(), ax.XDirection().Z());
  ring.e2 = glm::cross(ring.circle.normal, ring.e1);
  ring.params = params;
  ring.vertices = vertices;
  ring.edges = edges;
  ring.fixed = true;
  for (const TopoDS_Edge& e : edges) ring.tolerance = std::max(ring.tolerance, BRep_Tool::Tolerance(e));
}

// Adds a vertex parameter to a free ring (kept sorted in its window) unless one is already there; returns the
// parameter used.
double add_vertex(Ring& ring, const Vec3& direction) {
  const double t = ring.param_of(direction);
  for (double p : ring.params)
    if (std::abs(wrap_into(t - p + M_PI, 0.0) - M_PI) < kSameVertexAngle) return p;
  if (ring.fixed) throw std::logic_error("brep builder: a vertex was added to a fixed ring");
  if (ring.params.empty()) {
    ring.params.push_back(t);
    return t;
  }
  const double w = wrap_into(t, ring.params[0]);
  ring.params.insert(std::upper_bound(ring.params.begin(), ring.params.end(), w), w);
  return w;
}

// The parameter of `direction` among a ring's vertices, or NaN.
double vertex_at(const Ring& ring, const Vec3& direction) {
  const double t = ring.param_of(direction);
  for (double p : ring.params)
    if (std::abs(wrap_into(t - p + M_PI, 0.0) - M_PI) < kSameVertexAngle) return p;
  return std::nan("");
}

// Creates the vertices and edges of a free ring from its parameters (its curve and frame set).
void make_ring_edges(const BRep_Builder& b, Ring& ring) {
  ring.vertices.clear();
  ring.edges.clear();
  for (double p : ring.params) ring.vertices.push_back(make_vertex(b, ring.curve->Value(p), ring.tolerance));
  for (std::size_t k = 0; k < ring.params.size(); ++k) {
    TopoDS_Edge e;
    b.MakeEdge(e, ring.curve, ring.tolerance);
    b.Add(e, ring.vertices[k].Oriented(TopAbs_FORWARD));
    b.Add(e, ring.vertices[(k + 1) % ring.params.size()].Oriented(TopAbs_REVERSED));
    b.Range(e, ring.params[k], ring.edge_end(k));
    ring.edges.push_back(e);
  }
}

}  // namespace

namespace {

// Work units of build_brep_pieces: laying out a distinct hub shape (or building its core) costs about as much as
// this many spherical faces; a spherical face about two conical ones.
constexpr std::int64_t kShapeUnits = 20;
constexpr std::int64_t kHubUnits = 2;
constexpr std::int64_t kBeamUnits = 1;
// A hub in a group's Fuse costs at least what a distinct core's Fuse does (a group's Fuse grows faster than its hubs).
constexpr std::int64_t kGroupHubUnits = kShapeUnits;

// Everything one build of pieces works on; its steps below fill it in order.
struct PieceBuild {
  const FlatLattice& f;
  const BrepSelection& selection;
  Progress& progress;
  std::vector<BeamFrustum> frustums;
  std::vector<char> ball_built;      // per ball
  std::vector<BeamWork> beams;       // per beam
  std::vector<HubWork> hubs;         // per built ball
  std::vector<HubGeometry> geometry; // per hub
  HubCatalog catalog;                // the hubs' distinct shapes
  std::vector<ShapeWork> shapes;     // per distinct shape: its sphere layout, or its core
  const BRep_Builder builder;
  std::int64_t hub_groups = 0, grouped_hubs = 0;  // crowded hubs built as one (group_short_beams)
  std::int64_t foreign_groups = 0, foreign_hubs = 0;  // hubs meeting foreign ones, built as one
  std::string group_failure;                      // why a group could not be built, for the error
  std::int64_t built_beams = 0;                   // beams with faces to build (lay_out_shapes)
  // After the cores, the bar's rest: the groups' Fuses, then the faces (build_brep_pieces); the units it keeps
  // for the groups and those they took.
  Progress* tail = nullptr;
  std::int64_t group_units_reserved = 0, group_units_given = 0;
  // Collars placed beyond their beams' cuts (place_core) with what to say of each, all of them thrown together
  // (throw_collars_past_cuts).
  std::vector<std::pair<CollarPastCut::End, std::string>> collars_past_cuts{};
  std::mutex collars_past_cuts_mutex{};
};

// The message names the first beam end in order, whatever order the parallel placement found them in.
void throw_collars_past_cuts(const PieceBuild& b) {
  if (b.collars_past_cuts.empty()) return;
  std::vector<std::pair<CollarPastCut::End, std::string>> found = b.collars_past_cuts;
  std::sort(found.begin(), found.end(), [](const auto& x, const auto& y) {
    return std::tie(x.first.beam, x.first.end) < std::tie(y.first.beam, y.first.end);
  });
  std::vector<CollarPastCut::End> ends;
  for (const auto& [end, message] : found) ends.push_back(end);
  const std::string more =
      ends.size() > 1 ? " and " + std::to_string(ends.size() - 1) + " more beam ends like it" : std::string();
  throw CollarPastCut(found.front().second + more, std::move(ends));
}

void check_selection(const FlatLattice& f, const BrepSelection& selection) {
  if (static_cast<std::int64_t>(selection.balls.size()) != f.ball_count() ||
      static_cast<std::int64_t>(selection.beams.size()) != f.beam_count() ||
      (!selection.open_cuts.empty() && static_cast<std::int64_t>(selection.open_cuts.size()) != f.beam_count()) ||
      (!selection.split.empty() && static_cast<std::int64_t>(selection.split.size()) != f.beam_count()))
    fail_input("selection", "needs one flag per ball and per beam");
  auto too_small = [](double r) { return r < kMinimumBrepRadius; };
  auto g = [](double x) {  // std::to_string prints 1e-7 as 0.000000
    std::ostringstream os;
    os << x;
    return os.str();
  };
  for (std::int64_t i = 0; i < f.ball_count(); ++i)
    if (selection.balls[i] && too_small(f.balls[i].radius))
      fail_input("radius", "ball " + std::to_string(i) + " has radius " + g(f.balls[i].radius) + ", below the " +
                               g(kMinimumBrepRadius) + " a B-rep can hold (OpenCASCADE's tolerance is 1e-7): scale the model up, e.g. "
                               "work in micrometres");
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    const FlatBeam& b = f.beams[e];
    if (selection.beams[e] && (too_small(b.ra) || too_small(b.rb)))
      fail_input("radius", "beam " + std::to_string(e) + " has an end radius of " + g(std::min(b.ra, b.rb)) +
                               ", below the " + g(kMinimumBrepRadius) + " a B-rep can hold: scale the model up");
  }
  std::uint64_t faces = 0;
  for (char b : selection.balls) faces += b ? 1 : 0;
  for (char b : selection.beams) faces += b ? 2 : 0;
  require_memory(faces * kBytesPerFace, "the B-rep of " + std::to_string(faces) + " faces",
                 "build a preview, a mesh (to_mesh, STL) or a 3MF beam lattice, or a part of the lattice (a filter)");
}

// Which balls are built, and how each beam is: whole, one half, two halves meeting at the cut, or not at all.
void classify_beams(PieceBuild& b) {
  const FlatLattice& f = b.f;
  const std::vector<char> absorbed = absorbed_balls(f, b.frustums);
  b.ball_built.resize(f.ball_count());
  for (std::int64_t i = 0; i < f.ball_count(); ++i) b.ball_built[i] = b.selection.balls[i] && !absorbed[i];
  b.beams.resize(f.beam_count());
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!b.selection.beams[e] || !b.frustums[e].exists) continue;
    const bool a = b.ball_built[f.beams[e].a], c = b.ball_built[f.beams[e].b];
    const bool split = !b.selection.split.empty() && b.selection.split[e];
    b.beams[e].kind = a && c ? (split ? BeamKind::Split : BeamKind::Whole)
                             : a ? BeamKind::HalfA : c ? BeamKind::HalfB : BeamKind::None;
  }
}

// Hubs, their geometry, and whether their exit circles keep apart (clean) or overlap (a core).
void gather_hubs(PieceBuild& b) {
  const FlatLattice& f = b.f;
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    if (!b.ball_built[i]) continue;
    HubWork h;
    h.ball = i;
    HubGeometry g = hub_geometry(f, b.frustums, i, [&](std::int64_t e) { return b.beams[e].kind != BeamKind::None; },
                                 h.stumps);
    h.kind = g.kind;
    for (std::size_t s = 0; s < h.stumps.size(); ++s) {
      const auto [e, end] = h.stumps[s];
      EndCircle& ec = b.beams[e].end[end];
      ec.hub = static_cast<std::int64_t>(b.hubs.size());
      ec.slot = static_cast<int>(s);
      ec.circle = g.exits[s];
      ec.axial = end == 0 ? b.frustums[e].exit_a : b.frustums[e].exit_b;
    }
    b.hubs.push_back(std::move(h));
    b.geometry.push_back(std::move(g));
  }
}

// Each distinct hub shape once: a clean one's sphere layout and the pcurves of its circles, a crowded one's core.
void lay_out_shapes(PieceBuild& b) {
  b.progress.check();
  b.catalog = catalog_hubs(b.geometry);
  b.shapes.resize(b.catalog.shapes.size());
  for (const BeamWork& w : b.beams) b.built_beams += w.kind != BeamKind::None;
  std::vector<double> largest_radius(b.shapes.size(), 0.0);  // of the balls each shape is placed on
  for (std::size_t h = 0; h < b.hubs.size(); ++h) {
    double& r = largest_radius[b.catalog.placements[h].shape];
    r = std::max(r, b.f.balls[b.hubs[h].ball].radius);
  }
  b.progress.set_total(kShapeUnits * static_cast<std::int64_t>(b.shapes.size()) +
                       kHubUnits * static_cast<std::int64_t>(b.hubs.size()) + kBeamUnits * b.built_beams + 1);
  tbb::parallel_for(std::size_t(0), b.shapes.size(), [&](std::size_t s) {
    b.progress.check();
    ShapeWork& w = b.shapes[s];
    const std::int64_t rep = b.catalog.representatives[s];
    if (b.hubs[rep].kind == 0) {
      w.layout = layout_sphere(b.catalog.shapes[s], b.selection.seams);
      w.pcurves.resize(w.layout.circles.size());
      for (std::size_t c = 0; c < w.layout.circles.size(); ++c)
        for (const CircleArc& arc : w.layout.circles[c].arcs) {
          w.pcurves[c].push_back(approximate_arc_pcurve(w.layout, static_cast<int>(c), arc,
                                                        sphere_pcurve_tolerance(largest_radius[s])));
          w.max_error = std::max(w.max_error, w.pcurves[c].back().max_error);
        }
      b.progress.advance(kShapeUnits);
      return;
    }
    const std::vector<CoreStump> stumps = core_stumps(b.catalog.shapes[s], b.geometry[rep].extras);
    const CoreKind kind = core_kind(b.hubs[rep].kind);
    w.core = build_hub_core(stumps, kind, core_collars(stumps, kind, kMaxCollarPosition));
    b.progress.advance(kShapeUnits);
  });
}

// Core hubs: a copy of their core in place, and their collars read as fixed rings.
void place_core(PieceBuild& b, HubWork& hub, std::size_t h) {
  const HubPlacement& place = b.catalog.placements[h];
  const HubCore& core = *b.shapes[place.shape].core;
  const Ball& ball = b.f.balls[hub.ball];
  BRepBuilderAPI_Transform copy(core.faces, placement_transform(ball, place.rotation), Standard_True);
  ShapeFix_ShapeTolerance().LimitTolerance(copy.Shape(), kBrepTolerance, 0.0);
  for (TopExp_Explorer x(copy.Shape(), TopAbs_FACE); x.More(); x.Next()) hub.faces.push_back(TopoDS::Face(x.Current()));
  for (std::size_t s = 0; s < hub.stumps.size(); ++s) {
    EndCircle& ec = b.beams[hub.stumps[s].first].end[hub.stumps[s].second];
    const TopoDS_Edge collar = TopoDS::Edge(copy.ModifiedShape(core.collars[s]));
    Standard_Real first, last;
    Handle(Geom_Circle) curve = Handle(Geom_Circle)::DownCast(BRep_Tool::Curve(collar, first, last));
    if (curve.IsNull()) throw std::runtime_error("brep builder: a core's collar is not a circle");
    TopoDS_Vertex v;
    for (TopExp_Explorer x(collar, TopAbs_VERTEX); x.More(); x.Next()) v = TopoDS::Vertex(x.Current());
    ring_from_edges(ec, curve, {first}, {v}, {collar});
    ec.axial = core.collar_position[s] * ball.radius;
    // A whole beam only needs its two hubs' stumps to fit along it (check_whole_beams_fit); a split one
    // needs each to end before its cut.
    const std::int64_t e = hub.stumps[s].first;
    if (b.beams[e].kind == BeamKind::Whole) continue;
    const BeamFrustum& fr = b.frustums[e];
    const double to_cut = hub.stumps[s].second == 0 ? fr.cut_position() : fr.cone.length - fr.cut_position();
    if (!(ec.axial < to_cut * (1.0 - 1e-9))) {
      std::string message = "hub: ball " + std::to_string(hub.ball) + ": beam " + std::to_string(e) +
                            " is too short for the collar its crowded hub needs (collar at " +
                            std::to_string(ec.axial) + ", cut at " + std::to_string(to_cut) + ")";
      const std::lock_guard<std::mutex> lock(b.collars_past_cuts_mutex);
      b.collars_past_cuts.push_back({{e, hub.stumps[s].second, ec.axial}, std::move(message)});
    }
  }
}

// Whole beams along which their two hubs' stumps do not fit (their collars or exits pass each other).
std::vector<std::int64_t> short_whole_beams(const PieceBuild& b) {
  std::vector<std::int64_t> out;
  for (std::int64_t e = 0; e < b.f.beam_count(); ++e) {
    const BeamWork& w = b.beams[e];
    if (w.kind == BeamKind::Whole && !(w.end[0].axial + w.end[1].axial < b.frustums[e].cone.length * (1.0 - 1e-9)))
      out.push_back(e);
  }
  return out;
}

// Per ball, the index of its hub (-1 for a ball not built).
std::vector<std::int64_t> hub_of_balls(const PieceBuild& b) {
  std::vector<std::int64_t> hub_of(b.f.ball_count(), -1);
  for (std::size_t h = 0; h < b.hubs.size(); ++h) hub_of[b.hubs[h].ball] = static_cast<std::int64_t>(h);
  return hub_of;
}

// Hubs that may be built in a group: those meeting foreign elements and those at short whole beams. The groups
// of both kinds hold no others, and no hub is in two.
std::int64_t hubs_that_may_group(const PieceBuild& b) {
  std::vector<char> may(b.hubs.size(), 0);
  for (std::int64_t e : short_whole_beams(b))
    for (const EndCircle& ec : b.beams[e].end)
      if (ec.hub >= 0) may[ec.hub] = 1;
  if (b.selection.foreign != nullptr) {
    const std::vector<std::int64_t> hub_of = hub_of_balls(b);
    for (const auto& [x, y] : b.selection.foreign->joined)
      for (std::int64_t ball : {x, y})
        if (hub_of[ball] >= 0) may[hub_of[ball]] = 1;
  }
  return std::count(may.begin(), may.end(), char(1));
}

// The share of the bar of each group's Fuse, out of what the tail keeps for groups (hubs_that_may_group).
std::vector<std::int64_t> group_units(PieceBuild& b, const std::vector<std::vector<std::size_t>>& groups) {
  std::vector<std::int64_t> out;
  for (const std::vector<std::size_t>& g : groups) {
    out.push_back(std::min(kGroupHubUnits * static_cast<std::int64_t>(g.size()),
                           b.group_units_reserved - b.group_units_given));
    b.group_units_given += out.back();
  }
  return out;
}

// Beams too short for the roomy collars of their crowded hubs get a second chance: the distinct cores at their
// ends are built again with tight collars (CollarFit::Tight, just beyond the envelope) and their hubs placed
// again. A shape whose tight core is not nearer the ball on every stump (the arrangement refused it and the Fuse
// took far collars) keeps its roomy core. The other cores stay roomy: their thin bands of cone are what trimming's
// Booleans have been measured on.
void tighten_short_beams(PieceBuild& b) {
  const std::vector<std::int64_t> short_beams = short_whole_beams(b);
  if (short_beams.empty()) return;
  std::vector<char> tighten(b.shapes.size(), 0);
  for (std::int64_t e : short_beams)
    for (const EndCircle& ec : b.beams[e].end)
      if (ec.hub >= 0 && b.hubs[ec.hub].kind != 0) tighten[b.catalog.placements[ec.hub].shape] = 1;
  tbb::parallel_for(std::size_t(0), b.shapes.size(), [&](std::size_t s) {
    if (!tighten[s]) return;
    b.progress.check();
    const std::int64_t rep = b.catalog.representatives[s];
    const std::vector<CoreStump> stumps = core_stumps(b.catalog.shapes[s], b.geometry[rep].extras);
    const CoreKind kind = core_kind(b.hubs[rep].kind);
    std::shared_ptr<const HubCore> tight;
    try {
      tight = build_hub_core(stumps, kind, core_collars(stumps, kind, kMaxCollarPosition, CollarFit::Tight),
                             CollarFit::Tight);
    } catch (const InvalidInput&) {
      return;
    }
    const std::vector<double>& roomy = b.shapes[s].core->collar_position;
    for (std::size_t k = 0; k < roomy.size(); ++k)
      if (!(tight->collar_position[k] <= roomy[k])) return;
    b.shapes[s].core = tight;
    b.shapes[s].tight = true;
  });
  tbb::parallel_for(std::size_t(0), b.hubs.size(), [&](std::size_t h) {
    if (b.hubs[h].kind == 0 || !b.shapes[b.catalog.placements[h].shape].tight) return;
    b.hubs[h].faces.clear();
    place_core(b, b.hubs[h], h);
  });
  throw_collars_past_cuts(b);
}

// A fused group's faces go to its first hub, its other hubs keep none, and the beams leaving it start at the
// group's collars (fixed rings) instead of their hubs' own circles.
template <class Inner>
void adopt_group(PieceBuild& b, const std::vector<std::size_t>& members, const HubGroup& fused, const Inner& inner) {
  for (std::size_t i = 0; i < members.size(); ++i) {
    HubWork& hub = b.hubs[members[i]];
    hub.faces.clear();
    if (i == 0)
      for (TopExp_Explorer x(fused.faces, TopAbs_FACE); x.More(); x.Next()) hub.faces.push_back(TopoDS::Face(x.Current()));
    for (std::size_t s = 0; s < hub.stumps.size(); ++s) {
      const std::int64_t e = hub.stumps[s].first;
      if (inner(e)) continue;
      const TopoDS_Edge& collar = fused.collars[i][s];
      Standard_Real first, last;
      Handle(Geom_Circle) curve = Handle(Geom_Circle)::DownCast(BRep_Tool::Curve(collar, first, last));
      TopoDS_Vertex v;
      for (TopExp_Explorer x(collar, TopAbs_VERTEX); x.More(); x.Next()) v = TopoDS::Vertex(x.Current());
      ring_from_edges(b.beams[e].end[hub.stumps[s].second], curve, {first}, {v}, {collar});
    }
  }
}

// Groups of hubs are built as one whatever their size: a Fuse grows about as n^1.6 with its n hubs (docs/brep.md:
// minutes for hundreds of hubs), but it reports progress and stops at a cancel. What bounds them is memory, per
// face of the members' closed cores (a ball patch, and a cone and a collar disk per stump): building a BCC's 248
// hubs in one group (3,164 faces) peaked at 0.87 GB, 0.28 MB a face; its ~430 hubs of 6 x 6 x 6 cells (5,754
// faces) held 1.6 GB 34 min into their Fuse. 1 MB a face leaves room for worse Fuses: ~1,300 such hubs in 16 GB.
constexpr std::uint64_t kFuseBytesPerFace = 1024 * 1024;

// Refuses, before any Fuse, groups whose Fuses (run side by side) would not fit in memory: ResourceLimit naming them.
void require_group_memory(const PieceBuild& b, const std::vector<std::vector<std::size_t>>& groups) {
  std::uint64_t faces = 0, hubs = 0;
  for (const std::vector<std::size_t>& g : groups)
    for (std::size_t h : g) {
      faces += 1 + 2 * b.hubs[h].stumps.size();  // the ball's patch; per stump its cone and collar disk
      ++hubs;
    }
  require_memory(faces * kFuseBytesPerFace,
                 "OpenCASCADE's Fuse of " + std::to_string(hubs) + " hubs built as one (" +
                     std::to_string(groups.size()) + " group" + (groups.size() == 1 ? "" : "s") + ")",
                 "thin the beams or nodes, space the nodes further apart, or build a part of the lattice (a filter)");
}

// Hubs joined by beams still too short for their collars (after tighten_short_beams) are built as one: the
// connected groups of such beams' hubs, each by one Fuse of its members' closed cores (hub_group.hpp). The
// group's faces go to its first hub; its other hubs keep none; the beams inside it are no longer built (their
// two stumps overlap and cover them); the beams leaving it run from the group's collars as from a core's. A group
// with a clean hub, or a Fuse that fails its checks, is left as it was (its beams are then reported by
// check_whole_beams_fit, with the reason). Groups too large for memory are refused (require_group_memory).
void group_short_beams(PieceBuild& b) {
  const std::vector<std::int64_t> short_beams = short_whole_beams(b);
  if (short_beams.empty()) return;
  const std::size_t n = b.hubs.size();
  DisjointSets sets(n);
  for (std::int64_t e : short_beams) {
    const std::int64_t ha = b.beams[e].end[0].hub, hb = b.beams[e].end[1].hub;
    if (ha < 0 || hb < 0) continue;
    sets.join(static_cast<std::size_t>(ha), static_cast<std::size_t>(hb));
  }
  std::map<std::size_t, std::vector<std::size_t>> by_root;
  for (std::int64_t e : short_beams)
    for (const EndCircle& ec : b.beams[e].end) {
      if (ec.hub < 0) continue;
      std::vector<std::size_t>& g = by_root[sets.root(static_cast<std::size_t>(ec.hub))];
      if (std::find(g.begin(), g.end(), static_cast<std::size_t>(ec.hub)) == g.end()) g.push_back(ec.hub);
    }
  std::vector<std::vector<std::size_t>> groups;
  for (auto& [r, members] : by_root) {
    bool with_clean = false;
    for (std::size_t h : members) with_clean = with_clean || b.hubs[h].kind == 0;
    if (with_clean) {
      b.group_failure = "a hub of a short beam has no core";
      continue;
    }
    std::sort(members.begin(), members.end());
    groups.push_back(std::move(members));
  }
  require_group_memory(b, groups);
  std::vector<std::int64_t> group_of(n, -1);
  for (std::size_t g = 0; g < groups.size(); ++g)
    for (std::size_t h : groups[g]) group_of[h] = static_cast<std::int64_t>(g);
  // A beam is inside a group when it is short: its two stumps overlap and cover it. A beam between two hubs of
  // a group that fits between their collars (the third side of a triangle of short beams) is built as usual.
  std::vector<char> is_short(b.f.beam_count(), 0);
  for (std::int64_t e : short_beams) is_short[e] = 1;
  auto inner = [&](std::int64_t e) {
    const BeamWork& w = b.beams[e];
    return is_short[e] && w.kind == BeamKind::Whole && w.end[0].hub >= 0 && w.end[1].hub >= 0 &&
           group_of[w.end[0].hub] >= 0 && group_of[w.end[0].hub] == group_of[w.end[1].hub];
  };
  std::vector<std::string> failures(groups.size());
  std::vector<char> built(groups.size(), 0);
  std::vector<HubGroup> fused(groups.size());
  const std::vector<std::int64_t> units = group_units(b, groups);
  tbb::parallel_for(std::size_t(0), groups.size(), [&](std::size_t g) {
    b.progress.check();
    std::vector<GroupMember> members;
    for (std::size_t h : groups[g]) {
      const HubPlacement& place = b.catalog.placements[h];
      const std::int64_t rep = b.catalog.representatives[place.shape];
      const Ball& ball = b.f.balls[b.hubs[h].ball];
      GroupMember m;
      m.core = b.shapes[place.shape].core.get();
      m.stumps = core_stumps(b.catalog.shapes[place.shape], b.geometry[rep].extras);
      m.center = ball.center;
      m.radius = ball.radius;
      m.rotation = place.rotation;
      for (const auto& [e, end] : b.hubs[h].stumps) m.inner.push_back(inner(e));
      members.push_back(std::move(m));
    }
    try {
      Progress fuse(*b.tail, units[g]);
      fused[g] = fuse_hub_group(members, g, "of crowded nodes joined by beams too short for their collars", fuse);
      built[g] = 1;
    } catch (const InvalidInput& error) {
      failures[g] = error.what();
    }
  });
  for (std::size_t g = 0; g < groups.size(); ++g) {
    if (!built[g]) {
      b.group_failure = failures[g];
      continue;
    }
    ++b.hub_groups;
    b.grouped_hubs += static_cast<std::int64_t>(groups[g].size());
    adopt_group(b, groups[g], fused[g], inner);
  }
  // Inner beams last: `inner` reads their kind.
  for (std::int64_t e = 0; e < b.f.beam_count(); ++e)
    if (inner(e) && built[group_of[b.beams[e].end[0].hub]]) b.beams[e].kind = BeamKind::None;
}

// Hubs whose elements meet foreign ones (selection.foreign, foreign_groups.hpp) are built in groups: the connected
// components of the contacts and of the short beams at their hubs, each one Fuse of its members closed at
// member_collar. The beams inside a group are no longer built; the beams leaving it start at its collars. Runs
// after tight collars (tighten_short_beams) and before the groups of short beams, which then leave these hubs
// alone. A group whose Fuse fails its checks is an error naming the contacts (the lattice is not clean there);
// groups too large for memory are refused (require_group_memory).
void group_foreign_contacts(PieceBuild& b) {
  const ForeignContacts* contacts = b.selection.foreign;
  if (contacts == nullptr || contacts->empty()) return;
  const FlatLattice& f = b.f;
  auto refuse = [&](const std::string& why) {
    fail_input("lattice", "is not clean (" + std::to_string(contacts->issue_count) + " contact" +
                              (contacts->issue_count == 1 ? "" : "s") + " between elements of different nodes: " +
                              contacts->description + "), and " + why +
                              ": thin the beams or nodes, or space the nodes further apart");
  };
  const std::vector<std::int64_t> hub_of = hub_of_balls(b);
  DisjointSets sets(b.hubs.size());
  std::vector<char> in_contact(b.hubs.size(), 0);
  for (const auto& [x, y] : contacts->joined) {
    const std::int64_t hx = hub_of[x], hy = hub_of[y];
    if (hx >= 0) in_contact[hx] = 1;
    if (hy >= 0) in_contact[hy] = 1;
    if (hx >= 0 && hy >= 0) sets.join(static_cast<std::size_t>(hx), static_cast<std::size_t>(hy));
  }
  for (std::int64_t e : short_whole_beams(b))
    sets.join(static_cast<std::size_t>(b.beams[e].end[0].hub), static_cast<std::size_t>(b.beams[e].end[1].hub));
  std::map<std::size_t, std::vector<std::size_t>> by_root;
  for (std::size_t h = 0; h < b.hubs.size(); ++h)
    if (in_contact[h]) by_root[sets.root(h)];
  for (std::size_t h = 0; h < b.hubs.size(); ++h) {
    auto it = by_root.find(sets.root(h));
    if (it != by_root.end()) it->second.push_back(h);
  }
  std::vector<std::vector<std::size_t>> groups;
  std::vector<std::int64_t> group_of(b.hubs.size(), -1);
  for (auto& [root, members] : by_root) {
    for (std::size_t h : members) group_of[h] = static_cast<std::int64_t>(groups.size());
    groups.push_back(std::move(members));
  }
  require_group_memory(b, groups);
  auto inner = [&](std::int64_t e) {
    const BeamWork& w = b.beams[e];
    return w.kind == BeamKind::Whole && group_of[w.end[0].hub] >= 0 && group_of[w.end[0].hub] == group_of[w.end[1].hub];
  };
  // Where each member's stumps end (in ball radii), from the hubs' own collars before any group changes them.
  auto collar_of = [&](const HubWork& hub, std::size_t s) {
    const auto [e, end] = hub.stumps[s];
    const BeamWork& w = b.beams[e];
    const BeamFrustum& fr = b.frustums[e];
    const double here = w.end[end].axial;
    if (w.kind == BeamKind::Whole) return member_collar(here, w.end[1 - end].axial, fr.cone.length, inner(e));
    const double to_cut = end == 0 ? fr.cut_position() : fr.cone.length - fr.cut_position();
    return member_collar(here, 0.0, to_cut, false);
  };
  std::vector<std::vector<std::shared_ptr<const HubCore>>> cores(groups.size());
  std::vector<HubGroup> fused(groups.size());
  std::vector<std::string> failures(groups.size());
  const std::vector<std::int64_t> units = group_units(b, groups);
  tbb::parallel_for(std::size_t(0), groups.size(), [&](std::size_t g) {
    b.progress.check();
    try {
      std::vector<GroupMember> members;
      for (std::size_t h : groups[g]) {
        const HubWork& hub = b.hubs[h];
        const Ball& ball = f.balls[hub.ball];
        GroupMember m;
        m.rotation = b.catalog.placements[h].rotation;
        m.stumps = member_stumps(f, b.frustums, hub.ball, hub.stumps, m.rotation);
        m.center = ball.center;
        m.radius = ball.radius;
        std::vector<double> collars;
        for (std::size_t s = 0; s < hub.stumps.size(); ++s) {
          m.inner.push_back(inner(hub.stumps[s].first));
          collars.push_back(collar_of(hub, s) / ball.radius);
        }
        cores[g].push_back(hub.stumps.empty() ? lone_ball_core()
                                              : build_hub_core(m.stumps, member_kind(m.stumps), collars, CollarFit::Tight));
        m.core = cores[g].back().get();
        // The core may have taken collars farther out (its Fuse's fallback): a leaving beam must still fit.
        for (std::size_t s = 0; s < hub.stumps.size(); ++s)
          if (!m.inner[s] && !(m.core->collar_position[s] <= collars[s] * (1.0 + 1e-9)))
            fail_input("hub", "the core of ball " + std::to_string(hub.ball) + " needs a collar farther out on beam " +
                                  std::to_string(hub.stumps[s].first) + " than the beam has room for");
        members.push_back(std::move(m));
      }
      Progress fuse(*b.tail, units[g]);
      fused[g] = fuse_hub_group(members, g, "whose elements meet elements of other nodes", fuse);
    } catch (const InvalidInput& error) {
      failures[g] = error.what();
    }
  });
  for (std::size_t g = 0; g < groups.size(); ++g)
    if (!failures[g].empty())
      refuse("the " + std::to_string(groups[g].size()) + " hubs around ball " +
             std::to_string(b.hubs[groups[g][0]].ball) + " could not be built as one (" + failures[g] + ")");
  for (std::size_t g = 0; g < groups.size(); ++g) {
    for (std::size_t i = 0; i < groups[g].size(); ++i) {
      HubWork& hub = b.hubs[groups[g][i]];
      if (hub.kind == 0) hub.kind = 2;  // no sphere layout of its own any more: a core's collars
      for (std::size_t s = 0; s < hub.stumps.size(); ++s)
        if (!inner(hub.stumps[s].first))
          b.beams[hub.stumps[s].first].end[hub.stumps[s].second].axial =
              cores[g][i]->collar_position[s] * b.f.balls[hub.ball].radius;
    }
    adopt_group(b, groups[g], fused[g], inner);
    ++b.foreign_groups;
    b.foreign_hubs += static_cast<std::int64_t>(groups[g].size());
  }
  for (std::int64_t e = 0; e < f.beam_count(); ++e)
    if (b.beams[e].kind == BeamKind::Whole && inner(e)) b.beams[e].kind = BeamKind::None;
}

// How far along beam e its end `end` reaches into the beam with every beam radius at that hub scaled by k: the
// collar the hub's core would need (the exit circle of a clean hub, which only shrinks with k), or infinity when
// no collar fits.
double start_with_radii_scaled(const PieceBuild& b, std::int64_t e, int end, double k) {
  const EndCircle& ec = b.beams[e].end[end];
  const HubWork& hub = b.hubs[ec.hub];
  if (hub.kind == 0) return ec.axial;
  const HubGeometry& g = b.geometry[ec.hub];
  std::vector<CoreStump> stumps = core_stumps(canonical_caps(g, Mat3(1.0)), g.extras);
  for (CoreStump& st : stumps) {
    // The beam is the hull of its end balls: sin(phi) = (r_here - r_there) / length scales with the radii.
    st.end_radius *= k;
    st.sin_phi *= k;
    const double c = std::sqrt((1.0 - st.sin_phi) * (1.0 + st.sin_phi));
    st.exit = st.end_radius * st.sin_phi + c * std::sqrt((1.0 - st.end_radius) * (1.0 + st.end_radius));
  }
  try {
    return core_collars(stumps, CoreKind::Transversal, kMaxCollarPosition, CollarFit::Tight)[ec.slot] * g.ball.radius;
  } catch (const InvalidInput&) {
    return std::numeric_limits<double>::infinity();
  }
}

// The largest factor on the beam radii at both hubs of beam e under which their stumps fit along it (0: none).
double fitting_radius_factor(const PieceBuild& b, std::int64_t e) {
  const double length = b.frustums[e].cone.length;
  auto fits = [&](double k) {
    return start_with_radii_scaled(b, e, 0, k) + start_with_radii_scaled(b, e, 1, k) < length * (1.0 - 1e-3);
  };
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 24; ++it) (fits(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

// A whole beam between two hubs must be longer than the stumps its two hubs need: where their neighbours meet
// it from both sides, no hub-by-hub construction holds (the beams of a triangle meeting near its middle). The
// error counts such beams, names the first with its balls and reaches, and the factor on the beam radii at
// their balls under which all of them (up to kReportedShortBeams examined) fit.
constexpr std::size_t kReportedShortBeams = 64;
void check_whole_beams_fit(const PieceBuild& b) {
  const std::vector<std::int64_t> short_beams = short_whole_beams(b);
  if (short_beams.empty()) return;
  const std::size_t examined = std::min(short_beams.size(), kReportedShortBeams);
  std::vector<double> factors(examined);
  tbb::parallel_for(std::size_t(0), examined, [&](std::size_t k) { factors[k] = fitting_radius_factor(b, short_beams[k]); });
  const double factor = *std::min_element(factors.begin(), factors.end());
  const std::int64_t e = short_beams[0];
  const BeamWork& w = b.beams[e];
  std::ostringstream os;
  os.precision(4);
  os << short_beams.size() << " beam" << (short_beams.size() > 1 ? "s are" : " is")
     << " too short for the collars of their crowded hubs, e.g. beam " << e << " (balls " << b.f.beams[e].a
     << " and " << b.f.beams[e].b << "): its neighbours at the two balls meet it up to " << w.end[0].axial << " and "
     << w.end[1].axial << " from their centres, more than its length " << b.frustums[e].cone.length << " together";
  if (factor > 0.0)
    os << "; beam radii at most " << factor << " of today's at the balls of " << (examined > 1 ? "these beams" : "this beam")
       << " (or smaller balls) would fit";
  else
    os << "; thinner beams or smaller balls there";
  if (!b.group_failure.empty()) os << " (building their hubs as one failed: " << b.group_failure << ")";
  fail_input("hub", os.str());
}

// A beam's plan: its rings from end a to end b and the seam of every segment. A seam must leave both rings of its
// segment at a vertex: free rings (clean exit circles, new cuts) take a vertex where it is needed; two fixed rings
// with no common vertex get a joint between them.
void plan_beam(PieceBuild& b, std::int64_t e, const CutEdges& cut_edges) {
  BeamWork& w = b.beams[e];
  for (EndCircle& ec : w.end) {  // frames of clean hubs' circles
    if (ec.hub < 0 || b.hubs[ec.hub].kind != 0) continue;
    const HubPlacement& place = b.catalog.placements[ec.hub];
    const CircleLayout& cl = b.shapes[place.shape].layout.circles[ec.slot];
    const Vec3 n = ec.circle.normal, e1 = place.rotation * cl.e1;
    ec.e1 = glm::normalize(e1 - glm::dot(e1, n) * n);
    ec.e2 = glm::cross(n, ec.e1);
    ec.params = cl.own_vertices;
  }
  const BeamFrustum& fr = b.frustums[e];
  if (w.kind != BeamKind::Whole) {
    auto found = cut_edges.find(e);
    if (found != cut_edges.end()) {
      const CutCircle& c = found->second;
      // Shared with an earlier build: its half-beam's seam would otherwise span this build's cut while its
      // vertices sit on that circle (an unorientable face; docs/brep.md, "open cuts at moved places").
      const gp_Pnt at = c.curve->Location();
      if (glm::length(Vec3(at.X(), at.Y(), at.Z()) - fr.cut_circle().center) > kCutCircleMismatch * fr.length())
        throw std::logic_error("brep builder: beam " + std::to_string(e) +
                               "'s shared cut circle lies elsewhere than this build's cut");
      ring_from_edges(w.cut, c.curve, c.params, c.vertices, c.edges);
    } else {
      const Circle cc = fr.cut_circle();
      w.cut.circle = cc;
      w.cut.e1 = any_perpendicular(cc.normal);
      w.cut.e2 = glm::cross(cc.normal, w.cut.e1);
      w.cut_is_new = true;
    }
  }
  const Vec3 axis = fr.cone.axis;
  switch (w.kind) {
    case BeamKind::Whole: w.plan.rings = {0, 1}; break;
    case BeamKind::HalfA: w.plan.rings = {0, 2}; break;
    case BeamKind::HalfB: w.plan.rings = {2, 1}; break;
    default: w.plan.rings = {0, 2, 1}; break;
  }
  auto flat = [&](const Vec3& d) { return glm::normalize(d - glm::dot(d, axis) * axis); };
  std::vector<int> rings = w.plan.rings;
  std::vector<int> planned;
  std::vector<Vec3> seams;
  for (std::size_t k = 0; k + 1 < rings.size(); ++k) {
    Ring& p = w.ring(rings[k]);
    Ring& q = w.ring(rings[k + 1]);
    if (planned.empty()) planned.push_back(rings[k]);
    if (p.fixed && q.fixed) {
      // A common vertex, or a joint between them.
      bool found = false;
      for (double t : p.params) {
        const Vec3 d = flat(p.direction_of(t));
        if (!std::isnan(vertex_at(q, d))) {
          seams.push_back(d);
          found = true;
          break;
        }
      }
      if (!found) {
        Ring joint;
        w.joints.push_back(joint);
        const int id = 3 + static_cast<int>(w.joints.size()) - 1;
        seams.push_back(flat(p.direction_of(p.params[0])));
        seams.push_back(flat(q.direction_of(q.params[0])));
        planned.push_back(id);
      }
    } else if (p.fixed || (!q.fixed && !p.params.empty())) {
      const Vec3 d = flat(p.direction_of(p.params[0]));
      seams.push_back(d);
      add_vertex(q, d);
    } else {
      if (q.params.empty()) throw std::logic_error("brep builder: a segment between two rings with no vertex");
      const Vec3 d = flat(q.direction_of(q.params[0]));
      seams.push_back(d);
      add_vertex(p, d);
    }
    planned.push_back(rings[k + 1]);
  }
  w.plan.rings = planned;
  w.plan.seam = seams;
}

// Cone position v of each of a beam's planned rings (the cone is anchored at the exit circle of node a); joints
// half way between their neighbours. InvalidInput when the rings do not follow each other along the beam.
std::vector<double> ring_positions(const BeamWork& w, const BeamFrustum& fr, std::int64_t e) {
  const double to_v = 1.0 / fr.cone.cos_phi;
  auto v_of = [&](int id) {
    if (id == 0) return (w.end[0].axial - fr.exit_a) * to_v;
    if (id == 1) return (fr.cone.length - w.end[1].axial - fr.exit_a) * to_v;
    if (id == 2) return (fr.cut_position() - fr.exit_a) * to_v;
    return 0.0;
  };
  std::vector<double> v(w.plan.rings.size());
  for (std::size_t k = 0; k < v.size(); ++k) v[k] = v_of(w.plan.rings[k]);
  for (std::size_t k = 0; k < v.size(); ++k)
    if (w.plan.rings[k] >= 3) v[k] = 0.5 * (v[k - 1] + v[k + 1]);
  for (std::size_t k = 0; k + 1 < v.size(); ++k)
    if (!(v[k] < v[k + 1])) fail_input("beam", std::to_string(e) + " is too short for the rings its hubs put on it");
  return v;
}

// New cuts and joints: circles on the cone with the planned vertices.
void make_new_rings(const BRep_Builder& builder, BeamWork& w, const BeamFrustum& fr, const std::vector<double>& v) {
  const Vec3 axis = fr.cone.axis;
  for (std::size_t k = 0; k < w.plan.rings.size(); ++k) {
    const int id = w.plan.rings[k];
    if (!(id >= 3 || (id == 2 && w.cut_is_new))) continue;
    Ring& r = w.ring(id);
    const double x = fr.exit_a + v[k] * fr.cone.cos_phi;
    r.circle = {fr.cone.a + x * axis, axis, fr.cone.radius_at(x)};
    if (id >= 3) {
      // A joint carries the seams of both its segments.
      r.e1 = w.plan.seam[k - 1];
      r.e2 = glm::cross(axis, r.e1);
      r.params.clear();
      add_vertex(r, w.plan.seam[k - 1]);
      add_vertex(r, w.plan.seam[k]);
    }
    r.curve = new Geom_Circle(gp_Ax2(pnt(r.circle.center), dir(axis), dir(r.e1)), r.circle.radius);
    make_ring_edges(builder, r);
  }
}

// One conical face per segment between consecutive rings.
void build_cone_faces(const BRep_Builder& builder, BeamWork& w, const BeamFrustum& fr, const std::vector<double>& v) {
  const Vec3 axis = fr.cone.axis;
  double cut_v = std::nan("");
  for (std::size_t k = 0; k < w.plan.rings.size(); ++k)
    if (w.plan.rings[k] == 2) cut_v = v[k];
  for (std::size_t k = 0; k + 1 < w.plan.rings.size(); ++k) {
    auto station = [&](std::size_t at) {
      const Ring& r = w.ring(w.plan.rings[at]);
      Station st;
      st.edges = &r.edges;
      st.params = &r.params;
      st.seam_param = vertex_at(r, w.plan.seam[k]);
      if (std::isnan(st.seam_param)) throw std::logic_error("brep builder: a seam misses its ring's vertices");
      const std::size_t idx = std::find(r.params.begin(), r.params.end(), st.seam_param) - r.params.begin();
      st.seam_vertex = r.vertices[idx];
      st.sign = glm::dot(r.circle.normal, axis) > 0.0 ? 1.0 : -1.0;
      st.v = v[at];
      st.tolerance = r.tolerance;
      return st;
    };
    TopoDS_Face face;
    build_cone_face(builder, fr, w.plan.seam[k], station(k), station(k + 1), face);
    w.cones.push_back(face);
    w.cone_side.push_back(std::isnan(cut_v) ? 0 : (v[k + 1] <= cut_v ? 0 : 1));
  }
}

// The disks closing a cut beam's piece(s) at its cut.
void build_cut_caps(const BRep_Builder& builder, BeamWork& w, const Vec3& axis) {
  const Ring& c = w.cut;
  Handle(Geom_Plane) plane = new Geom_Plane(gp_Ax3(pnt(c.circle.center), dir(c.circle.normal), dir(c.e1)));
  Handle(Geom2d_Circle) pcurve = new Geom2d_Circle(gp_Ax2d(gp_Pnt2d(0, 0), gp_Dir2d(1, 0)), c.circle.radius);
  const bool side_a = w.kind == BeamKind::HalfA || w.kind == BeamKind::Split;
  const bool side_b = w.kind == BeamKind::HalfB || w.kind == BeamKind::Split;
  for (int side = 0; side < 2; ++side) {
    if (!(side == 0 ? side_a : side_b)) continue;
    TopoDS_Face& cap = w.cap[side];
    builder.MakeFace(cap, plane, kBrepTolerance);
    for (std::size_t k = 0; k < c.edges.size(); ++k) {
      builder.UpdateEdge(c.edges[k], pcurve, cap, c.tolerance);
      builder.Range(c.edges[k], c.params[k], c.edge_end(k));
    }
    TopoDS_Wire wire;
    builder.MakeWire(wire);
    // The cut's normal points along the beam (from a to b): its edges run counterclockwise around it.
    const bool along = glm::dot(c.circle.normal, axis) > 0.0;
    for (const TopoDS_Edge& edge : c.edges) builder.Add(wire, edge.Oriented(along ? TopAbs_FORWARD : TopAbs_REVERSED));
    wire.Closed(true);
    builder.Add(cap, wire);
    // The disk faces away from the half it closes.
    if (side == 1) cap.Orientation(TopAbs_REVERSED);
  }
}

// A beam's conical faces, new cuts and joints, and its caps (unless its cut stays open for gluing).
void build_beam(PieceBuild& b, std::int64_t e) {
  BeamWork& w = b.beams[e];
  const BeamFrustum& fr = b.frustums[e];
  const std::vector<double> v = ring_positions(w, fr, e);
  make_new_rings(b.builder, w, fr, v);
  build_cone_faces(b.builder, w, fr, v);
  if (w.kind != BeamKind::Whole && (b.selection.open_cuts.empty() || !b.selection.open_cuts[e]))
    build_cut_caps(b.builder, w, fr.cone.axis);
}

// The pieces, by owner; the new cut circles join `cut_edges`.
BrepPieces collect_pieces(PieceBuild& b, CutEdges& cut_edges) {
  const FlatLattice& f = b.f;
  BrepPieces out;
  for (const HubWork& h : b.hubs) {
    for (const TopoDS_Face& face : h.faces) {
      out.faces.push_back(face);
      out.face_owner.push_back(h.ball);
    }
    out.stats.core_hubs += h.kind != 0;
  }
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    BeamWork& w = b.beams[e];
    if (w.kind == BeamKind::None) continue;
    ++out.stats.beams;
    for (std::size_t k = 0; k < w.cones.size(); ++k) {
      out.faces.push_back(w.cones[k]);
      out.face_owner.push_back(w.cone_side[k] == 0 && w.kind != BeamKind::HalfB ? f.beams[e].a : f.beams[e].b);
    }
    for (int side = 0; side < 2; ++side) {
      if (w.cap[side].IsNull()) continue;
      out.faces.push_back(w.cap[side]);
      out.face_owner.push_back(side == 0 ? f.beams[e].a : f.beams[e].b);
      out.caps.push_back({e, side, w.cap[side]});
      ++out.stats.cut_caps;
    }
    out.stats.joints += static_cast<std::int64_t>(w.joints.size());
    if (w.cut_is_new) cut_edges.emplace(e, CutCircle{w.cut.curve, w.cut.params, w.cut.vertices, w.cut.edges});
  }
  out.stats.balls = static_cast<std::int64_t>(b.hubs.size());
  out.stats.hub_groups = b.hub_groups;
  out.stats.grouped_hubs = b.grouped_hubs;
  out.stats.foreign_groups = b.foreign_groups;
  out.stats.foreign_hubs = b.foreign_hubs;
  out.stats.faces = static_cast<std::int64_t>(out.faces.size());
  out.stats.distinct_hubs = static_cast<std::int64_t>(b.shapes.size());
  for (const ShapeWork& w : b.shapes) {
    out.stats.distinct_cores += w.core != nullptr;
    out.stats.fused_cores += w.core != nullptr && w.core->fused;
    out.stats.tight_cores += w.tight;
    for (const CircleLayout& c : w.layout.circles) out.stats.seam_crossing_circles += c.role != CircleRole::Inner;
  }
  return out;
}

}  // namespace

BrepPieces build_brep_pieces(const FlatLattice& f, const BrepSelection& selection, CutEdges& cut_edges,
                             Progress& progress) {
  check_selection(f, selection);
  const auto start = std::chrono::steady_clock::now();
  PieceBuild b{f, selection, progress, selected_frustums(f, selection), {}, {}, {}, {}, {}, {}, BRep_Builder(), 0, 0, {}};
  classify_beams(b);
  gather_hubs(b);
  lay_out_shapes(b);
  const double layout_seconds = seconds_since(start);
  const auto topology_start = std::chrono::steady_clock::now();
  tbb::parallel_for(std::size_t(0), b.hubs.size(), [&](std::size_t h) {
    if (b.hubs[h].kind == 0) return;
    progress.check();
    place_core(b, b.hubs[h], h);
  });
  throw_collars_past_cuts(b);
  // Tight collars first: the beams they make fit need not join a foreign contact's group.
  if (selection.crowded_fallbacks) tighten_short_beams(b);
  // The rest of the bar, the faces' share, is shared with the groups' Fuses now that the hubs that may join one
  // are known: a group's Fuse takes minutes from a few hundred hubs, and the bar moves while it runs.
  const std::int64_t face_units = kHubUnits * static_cast<std::int64_t>(b.hubs.size()) + kBeamUnits * b.built_beams;
  Progress tail(progress, face_units);
  b.group_units_reserved = kGroupHubUnits * hubs_that_may_group(b);
  tail.set_total(b.group_units_reserved + face_units);
  b.tail = &tail;
  group_foreign_contacts(b);
  if (selection.crowded_fallbacks) group_short_beams(b);
  tail.advance(b.group_units_reserved - b.group_units_given);  // the share of the hubs that joined no group
  check_whole_beams_fit(b);
  tbb::parallel_for(std::int64_t(0), f.beam_count(), [&](std::int64_t e) {
    if (b.beams[e].kind == BeamKind::None) return;
    if (e % 64 == 0) progress.check();
    plan_beam(b, e, cut_edges);
  });
  tbb::parallel_for(std::size_t(0), b.hubs.size(), [&](std::size_t h) {  // spherical faces of clean hubs
    tail.advance(kHubUnits);
    if (b.hubs[h].kind != 0) return;
    const HubPlacement& place = b.catalog.placements[h];
    build_sphere_face(b.builder, f.balls[b.hubs[h].ball], place, b.shapes[place.shape], b.hubs[h], b.beams);
  });
  tbb::parallel_for(std::int64_t(0), f.beam_count(), [&](std::int64_t e) {
    if (b.beams[e].kind == BeamKind::None) return;
    tail.advance(kBeamUnits);
    build_beam(b, e);
  });
  tail.finish();  // the share of the beams that a group took in (they have no faces of their own)
  b.tail = nullptr;
  progress.check();  // the last chance to stop: cut_edges changes below
  BrepPieces out = collect_pieces(b, cut_edges);
  out.stats.layout_seconds = layout_seconds;
  out.stats.topology_seconds = seconds_since(topology_start);
  progress.finish();
  return out;
}

std::vector<double> stump_starts(const FlatLattice& f, const std::vector<BeamFrustum>& frustums,
                                 const std::vector<char>& beams, std::int64_t ball) {
  if (static_cast<std::int64_t>(frustums.size()) != f.beam_count() ||
      static_cast<std::int64_t>(beams.size()) != f.beam_count())
    fail_input("beams", "stump_starts needs one frustum and one flag per beam");
  if (ball < 0 || ball >= f.ball_count()) fail_input("ball", std::to_string(ball) + " is not a ball of the lattice");
  std::vector<std::pair<std::int64_t, int>> stumps;
  const HubGeometry g =
      hub_geometry(f, frustums, ball, [&](std::int64_t e) { return beams[e] && frustums[e].exists; }, stumps);
  std::vector<double> starts(f.degree(ball), std::nan(""));
  if (g.kind == 0) {
    for (const auto& [e, end] : stumps)
      starts[f.incident_slot(ball, e)] = end == 0 ? frustums[e].exit_a : frustums[e].exit_b;
    return starts;
  }
  // The collars as the core's build places them (in ball radii), from the caps in the world frame.
  const std::vector<double> collars =
      core_collars(core_stumps(canonical_caps(g, Mat3(1.0)), g.extras), core_kind(g.kind), kMaxCollarPosition);
  for (std::size_t s = 0; s < stumps.size(); ++s)
    starts[f.incident_slot(ball, stumps[s].first)] = collars[s] * g.ball.radius;
  return starts;
}

std::vector<char> place_cuts_between_collars(const FlatLattice& f, std::vector<BeamFrustum>& frustums,
                                             const KnownCollars& known) {
  std::vector<HubGeometry> hubs(f.ball_count());
  std::vector<std::vector<std::pair<std::int64_t, int>>> stumps(f.ball_count());
  tbb::parallel_for(std::int64_t(0), f.ball_count(), [&](std::int64_t i) {
    hubs[i] = hub_geometry(f, frustums, i, [&](std::int64_t e) { return frustums[e].exists; }, stumps[i]);
  });
  std::vector<char> no_room(f.beam_count(), 0);
  bool crowded = false;
  for (const HubGeometry& g : hubs) crowded = crowded || g.kind != 0;
  if (!crowded) return no_room;
  const HubCatalog catalog = catalog_hubs(hubs);
  std::vector<std::vector<double>> collars(catalog.shapes.size());
  tbb::parallel_for(std::size_t(0), catalog.shapes.size(), [&](std::size_t s) {
    const HubGeometry& rep = hubs[catalog.representatives[s]];
    if (rep.kind == 0) return;
    try {
      collars[s] = core_collars(core_stumps(catalog.shapes[s], rep.extras), core_kind(rep.kind), kMaxCollarPosition);
    } catch (const InvalidInput&) {  // no collar fits: the build says so
    }
  });
  // Per beam end: where its stump starts (NaN: the exit circle of a clean hub).
  std::vector<double> start(2 * f.beam_count(), std::nan(""));
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    const std::vector<double>& c = collars[catalog.placements[i].shape];
    if (c.empty()) continue;
    for (std::size_t s = 0; s < stumps[i].size(); ++s)
      start[2 * stumps[i][s].first + stumps[i][s].second] = c[s] * hubs[i].ball.radius;
  }
  for (const auto& [end, collar] : known)
    if (!(start[end] >= collar)) start[end] = collar;
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    BeamFrustum& fr = frustums[e];
    if (!fr.exists || (std::isnan(start[2 * e]) && std::isnan(start[2 * e + 1]))) continue;
    const double from = std::isnan(start[2 * e]) ? fr.exit_a : start[2 * e];
    const double to = fr.cone.length - (std::isnan(start[2 * e + 1]) ? fr.exit_b : start[2 * e + 1]);
    const double x = fr.cut_position(), moved = cut_between_collars(from, to, x);
    if (moved != x) fr.cut_fraction = (moved - fr.exit_a) / fr.length();
    no_room[e] = !(from < to);
  }
  return no_room;
}

TopoDS_Shape solids_from_faces(const std::vector<TopoDS_Face>& faces, Progress& progress) {
  const std::int64_t n = static_cast<std::int64_t>(faces.size());
  DisjointSets sets(static_cast<std::size_t>(n));
  std::unordered_map<const void*, std::int64_t> first_face;
  first_face.reserve(static_cast<std::size_t>(3 * n));
  // Units: two per face for the grouping, one per face for the shells, the rest (solids, voids) in finish().
  progress.set_total(3 * n + 1);
  constexpr std::int64_t kChunk = 1024;
  for (std::int64_t i = 0; i < n; ++i) {
    if (i % kChunk == kChunk - 1) progress.advance(2 * kChunk);
    for (TopExp_Explorer x(faces[i], TopAbs_EDGE); x.More(); x.Next()) {
      const void* key = x.Current().TShape().get();
      auto [it, inserted] = first_face.emplace(key, i);
      if (!inserted) sets.join(i, it->second);
    }
  }
  progress.advance(2 * (n % kChunk));
  std::unordered_map<std::int64_t, std::size_t> shell_of;
  std::vector<TopoDS_Shell> shells;
  const BRep_Builder b;
  for (std::int64_t i = 0; i < n; ++i) {
    if (i % kChunk == kChunk - 1) progress.advance(kChunk);
    const std::int64_t root = static_cast<std::int64_t>(sets.root(i));
    auto [it, inserted] = shell_of.emplace(root, shells.size());
    if (inserted) {
      shells.emplace_back();
      b.MakeShell(shells.back());
    }
    b.Add(shells[it->second], faces[i]);
  }
  progress.advance(n % kChunk);
  // A shell whose faces point inward bounds a void (the inside of a skin): it joins the solid around it.
  std::vector<TopoDS_Solid> solids;
  std::vector<TopoDS_Shell> voids;
  for (TopoDS_Shell& s : shells) {
    progress.check();
    s.Closed(true);
    TopoDS_Solid solid;
    b.MakeSolid(solid);
    b.Add(solid, s);
    BRepClass3d_SolidClassifier classifier(solid);
    classifier.PerformInfinitePoint(kBrepTolerance);
    if (classifier.State() == TopAbs_IN)
      voids.push_back(s);
    else
      solids.push_back(solid);
  }
  for (const TopoDS_Shell& v : voids) {
    std::size_t host = 0;
    if (solids.size() > 1) {
      TopExp_Explorer x(v, TopAbs_VERTEX);
      const gp_Pnt p = BRep_Tool::Pnt(TopoDS::Vertex(x.Current()));
      for (std::size_t k = 0; k < solids.size(); ++k) {
        BRepClass3d_SolidClassifier c(solids[k], p, kBrepTolerance);
        if (c.State() == TopAbs_IN) host = k;
      }
    }
    if (solids.empty()) throw std::runtime_error("solids_from_faces: a void shell with no solid around it");
    b.Add(solids[host], v);
  }
  progress.finish();
  if (solids.size() == 1) return solids[0];
  TopoDS_Compound compound;
  b.MakeCompound(compound);
  for (const TopoDS_Solid& s : solids) b.Add(compound, s);
  return compound;
}

LatticeBrep build_lattice_brep(const FlatLattice& lattice, SeamPreference seams, Progress& progress) {
  // Units: the clean check 5, the faces 40, the solids 55 (measured shares, roughly: grouping the faces into
  // shells and classifying them costs more than building them).
  progress.set_total(100);
  // Overlapping exit circles on a ball are the business of hub cores; elements meeting foreign ones are built in
  // groups with their neighbours (group_foreign_contacts).
  const ForeignContacts contacts = foreign_contacts(lattice);
  CutEdges cuts;
  BrepSelection selection = BrepSelection::everything(lattice);
  selection.foreign = &contacts;
  selection.seams = seams;
  progress.advance(5);
  BrepPieces pieces;
  {
    Progress part(progress, 40);
    pieces = build_brep_pieces(lattice, selection, cuts, part);
  }
  LatticeBrep out;
  {
    Progress part(progress, 55);
    out.shape = solids_from_faces(pieces.faces, part);
  }
  out.stats = pieces.stats;
  check_built_lattice(lattice, out, contacts.joined);
  progress.finish();
  return out;
}

LatticeBrep build_lattice_brep(const Lattice& lattice) { return build_lattice_brep(flatten(lattice)); }

}  // namespace steady
