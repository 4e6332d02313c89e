#include "steady/brep_builder.hpp"

#include <BRepClass3d_SolidClassifier.hxx>
#include <BRep_Builder.hxx>
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
#include <chrono>
#include <cmath>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "sphere_pcurve.hpp"
#include "steady/beam_frustum.hpp"
#include "steady/clean_check.hpp"
#include "steady/errors.hpp"
#include "steady/hub_catalog.hpp"

namespace steady {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// A beam's seam meets an existing vertex of a circle when their parameters agree to this (radians); otherwise the
// circle gets one more vertex.
constexpr double kSameVertexAngle = 1e-9;
// Below this |sin(half-angle)| a beam is a cylinder: OpenCASCADE refuses cones of (near) zero angle.
constexpr double kCylinderSine = 1e-12;

gp_Pnt pnt(const Vec3& v) { return gp_Pnt(v.x, v.y, v.z); }
gp_Dir dir(const Vec3& v) { return gp_Dir(v.x, v.y, v.z); }

double seconds_since(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

double wrap_into(double t, double start) {
  double r = std::fmod(t - start, kTwoPi);
  if (r < 0.0) r += kTwoPi;
  return start + r;
}

// A beam's exit circle at one of its nodes, as built on that node's sphere.
struct EndCircle {
  std::int64_t hub = -1;
  int slot = -1;
  Circle circle;
  Vec3 e1{0.0}, e2{0.0};          // world directions of parameters 0 and pi/2
  std::vector<double> params;     // vertex parameters, sorted, in the circle's window
  double seam_param = 0.0;        // where the beam's seam leaves the circle
  double tolerance = kBrepTolerance;
  Handle(Geom_Circle) curve;
  std::vector<TopoDS_Vertex> vertices;  // one per parameter
  std::vector<TopoDS_Edge> edges;       // edges[k] from params[k] to params[k+1] (the last wraps by 2 pi)
  double edge_end(std::size_t k) const { return k + 1 < params.size() ? params[k + 1] : params[0] + kTwoPi; }
};

enum class BeamKind { None, Whole, HalfA, HalfB, Split };

struct BeamWork {
  BeamKind kind = BeamKind::None;
  EndCircle end[2];
  Vec3 seam_dir{0.0};
  TopoDS_Edge cut_edge;
  bool new_cut = false;
  TopoDS_Face cone[2];  // whole beam or the a-side half: cone[0]; the b-side half: cone[1]
  TopoDS_Face cap[2];   // disks closing the a-side / b-side piece at the cut
};

struct HubWork {
  std::int64_t ball = -1;
  std::vector<std::pair<std::int64_t, int>> stumps;  // (beam, end)
  TopoDS_Face face;
};

struct ShapeWork {
  SphereLayout layout;
  std::vector<std::vector<ArcPcurve>> pcurves;  // per circle, per arc
  double max_error = 0.0;
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
      b.UpdateEdge(e, shape.pcurves[s][arc].curve, face, tol);
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
  Handle(Geom_Circle) meridian = new Geom_Circle(gp_Ax2(pnt(ball.center), dir(-yw), dir(xw)), R);
  Handle(Geom2d_Line) seam_right = line2d(kTwoPi, 0.0, 0.0, 1.0), seam_left = line2d(0.0, 0.0, 0.0, 1.0);
  std::vector<TopoDS_Edge> seam;  // piece k joins stops[2k] and stops[2k+1]
  for (std::size_t k = 0; k + 1 < stops.size(); k += 2) {
    TopoDS_Edge e;
    b.MakeEdge(e, meridian, tol);
    b.Add(e, stops[k].second.Oriented(TopAbs_FORWARD));
    b.Add(e, stops[k + 1].second.Oriented(TopAbs_REVERSED));
    b.UpdateEdge(e, seam_right, seam_left, face, tol);
    b.Range(e, stops[k].first, stops[k + 1].first);
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
  hub.face = face;
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

BrepPieces build_brep_pieces(const FlatLattice& f, const BrepSelection& selection, CutEdges& cut_edges) {
  if (static_cast<std::int64_t>(selection.balls.size()) != f.ball_count() ||
      static_cast<std::int64_t>(selection.beams.size()) != f.beam_count() ||
      (!selection.open_cuts.empty() && static_cast<std::int64_t>(selection.open_cuts.size()) != f.beam_count()) ||
      (!selection.split.empty() && static_cast<std::int64_t>(selection.split.size()) != f.beam_count()))
    fail_input("selection", "needs one flag per ball and per beam");
  const auto start = std::chrono::steady_clock::now();
  BrepPieces out;
  const std::vector<BeamFrustum> frustums = beam_frustums(f);
  const std::vector<char> absorbed = absorbed_balls(f, frustums);
  std::vector<char> ball_built(f.ball_count());
  for (std::int64_t i = 0; i < f.ball_count(); ++i) ball_built[i] = selection.balls[i] && !absorbed[i];

  std::vector<BeamWork> beams(f.beam_count());
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    if (!selection.beams[e] || !frustums[e].exists) continue;
    const bool a = ball_built[f.beams[e].a], b = ball_built[f.beams[e].b];
    const bool split = !selection.split.empty() && selection.split[e];
    beams[e].kind = a && b ? (split ? BeamKind::Split : BeamKind::Whole)
                           : a ? BeamKind::HalfA : b ? BeamKind::HalfB : BeamKind::None;
  }
  // Hubs and their geometry.
  std::vector<HubWork> hubs;
  std::vector<HubGeometry> geometry;
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    if (!ball_built[i]) continue;
    HubWork h;
    h.ball = i;
    HubGeometry g;
    g.ball = f.balls[i];
    for (const std::int64_t* e = f.incident_begin(i); e != f.incident_end(i); ++e) {
      if (beams[*e].kind == BeamKind::None) continue;
      const int end = f.beams[*e].a == i ? 0 : 1;
      h.stumps.emplace_back(*e, end);
      g.exits.push_back(end == 0 ? frustums[*e].circle_a : frustums[*e].circle_b);
      EndCircle& ec = beams[*e].end[end];
      ec.hub = static_cast<std::int64_t>(hubs.size());
      ec.slot = static_cast<int>(h.stumps.size()) - 1;
      ec.circle = g.exits.back();
    }
    hubs.push_back(std::move(h));
    geometry.push_back(std::move(g));
  }
  const HubCatalog catalog = catalog_hubs(geometry);
  std::vector<ShapeWork> shapes(catalog.shapes.size());
  tbb::parallel_for(std::size_t(0), shapes.size(), [&](std::size_t s) {
    ShapeWork& w = shapes[s];
    w.layout = layout_sphere(catalog.shapes[s], selection.seams);
    w.pcurves.resize(w.layout.circles.size());
    for (std::size_t c = 0; c < w.layout.circles.size(); ++c)
      for (const CircleArc& arc : w.layout.circles[c].arcs) {
        w.pcurves[c].push_back(approximate_arc_pcurve(w.layout, static_cast<int>(c), arc));
        w.max_error = std::max(w.max_error, w.pcurves[c].back().max_error);
      }
  });
  out.stats.layout_seconds = seconds_since(start);
  const auto topology_start = std::chrono::steady_clock::now();

  // World frames of the circles, and each beam's seam.
  tbb::parallel_for(std::int64_t(0), f.beam_count(), [&](std::int64_t e) {
    BeamWork& w = beams[e];
    if (w.kind == BeamKind::None) return;
    for (EndCircle& ec : w.end) {
      if (ec.hub < 0) continue;
      const HubPlacement& place = catalog.placements[ec.hub];
      const CircleLayout& cl = shapes[place.shape].layout.circles[ec.slot];
      const Vec3 n = ec.circle.normal, e1 = place.rotation * cl.e1;
      ec.e1 = glm::normalize(e1 - glm::dot(e1, n) * n);
      ec.e2 = glm::cross(n, ec.e1);
      ec.params = cl.own_vertices;
    }
    const bool cut = w.kind != BeamKind::Whole;
    auto found = cut ? cut_edges.find(e) : cut_edges.end();
    if (found != cut_edges.end()) {
      Standard_Real first, last;
      Handle(Geom_Circle) c = Handle(Geom_Circle)::DownCast(BRep_Tool::Curve(found->second, first, last));
      const gp_Dir x = c->Position().XDirection();
      w.seam_dir = Vec3(x.X(), x.Y(), x.Z());
    } else {
      const EndCircle& ec = w.end[w.end[0].hub >= 0 ? 0 : 1];
      const double t = ec.params[0];
      w.seam_dir = std::cos(t) * ec.e1 + std::sin(t) * ec.e2;
    }
    const Vec3 axis = frustums[e].cone.axis;
    w.seam_dir = glm::normalize(w.seam_dir - glm::dot(w.seam_dir, axis) * axis);
    for (EndCircle& ec : w.end) {
      if (ec.hub < 0) continue;
      const double window = ec.params[0];
      const double t = wrap_into(std::atan2(glm::dot(w.seam_dir, ec.e2), glm::dot(w.seam_dir, ec.e1)), window);
      ec.seam_param = t;
      bool matched = false;
      for (double p : ec.params) {
        const double d = std::abs(wrap_into(t - p + M_PI, 0.0) - M_PI);
        if (d < kSameVertexAngle) {
          ec.seam_param = p;
          matched = true;
        }
      }
      if (!matched) {
        ec.params.push_back(t);
        std::sort(ec.params.begin(), ec.params.end());
      }
    }
  });

  // Spherical faces.
  const BRep_Builder builder;
  tbb::parallel_for(std::size_t(0), hubs.size(), [&](std::size_t h) {
    const HubPlacement& place = catalog.placements[h];
    build_sphere_face(builder, f.balls[hubs[h].ball], place, shapes[place.shape], hubs[h], beams);
  });
  // Conical faces, cut circles and their caps.
  tbb::parallel_for(std::int64_t(0), f.beam_count(), [&](std::int64_t e) {
    BeamWork& w = beams[e];
    if (w.kind == BeamKind::None) return;
    const BeamFrustum& fr = frustums[e];
    const double to_v = 1.0 / fr.cone.cos_phi;
    auto node_station = [&](int end) {
      const EndCircle& ec = w.end[end];
      Station st;
      st.edges = &ec.edges;
      st.params = &ec.params;
      const std::size_t k = std::find(ec.params.begin(), ec.params.end(), ec.seam_param) - ec.params.begin();
      st.seam_vertex = ec.vertices[k];
      st.seam_param = ec.seam_param;
      st.sign = end == 0 ? 1.0 : -1.0;
      st.v = end == 0 ? 0.0 : (fr.cone.length - fr.exit_b - fr.exit_a) * to_v;
      st.tolerance = ec.tolerance;
      return st;
    };
    if (w.kind == BeamKind::Whole) {
      build_cone_face(builder, fr, w.seam_dir, node_station(0), node_station(1), w.cone[0]);
      return;
    }
    auto found = cut_edges.find(e);
    if (found != cut_edges.end()) {
      w.cut_edge = found->second;
    } else {
      const Circle cc = fr.cut_circle();
      Handle(Geom_Circle) curve = new Geom_Circle(gp_Ax2(pnt(cc.center), dir(cc.normal), dir(w.seam_dir)), cc.radius);
      const TopoDS_Vertex v = make_vertex(builder, curve->Value(0.0), kBrepTolerance);
      builder.MakeEdge(w.cut_edge, curve, kBrepTolerance);
      builder.Add(w.cut_edge, v.Oriented(TopAbs_FORWARD));
      builder.Add(w.cut_edge, v.Oriented(TopAbs_REVERSED));
      builder.Range(w.cut_edge, 0.0, kTwoPi);
      w.new_cut = true;
    }
    static const std::vector<double> kCutParams = {0.0};
    const std::vector<TopoDS_Edge> cut_edges_list = {w.cut_edge};
    Station cut;
    cut.edges = &cut_edges_list;
    cut.params = &kCutParams;
    for (TopExp_Explorer x(w.cut_edge, TopAbs_VERTEX); x.More(); x.Next()) cut.seam_vertex = TopoDS::Vertex(x.Current());
    cut.seam_param = 0.0;
    cut.sign = 1.0;
    cut.v = (fr.cut_position() - fr.exit_a) * to_v;
    const bool side_a = w.kind == BeamKind::HalfA || w.kind == BeamKind::Split;
    const bool side_b = w.kind == BeamKind::HalfB || w.kind == BeamKind::Split;
    if (side_a) build_cone_face(builder, fr, w.seam_dir, node_station(0), cut, w.cone[0]);
    if (side_b) build_cone_face(builder, fr, w.seam_dir, cut, node_station(1), w.cone[1]);
    if (selection.open_cuts.empty() || !selection.open_cuts[e]) {
      const Circle cc = fr.cut_circle();
      Handle(Geom_Plane) plane = new Geom_Plane(gp_Ax3(pnt(cc.center), dir(cc.normal), dir(w.seam_dir)));
      Handle(Geom2d_Circle) pcurve = new Geom2d_Circle(gp_Ax2d(gp_Pnt2d(0, 0), gp_Dir2d(1, 0)), cc.radius);
      for (int side = 0; side < 2; ++side) {
        if (!(side == 0 ? side_a : side_b)) continue;
        TopoDS_Face& cap = w.cap[side];
        builder.MakeFace(cap, plane, kBrepTolerance);
        builder.UpdateEdge(w.cut_edge, pcurve, cap, kBrepTolerance);
        builder.Range(w.cut_edge, 0.0, kTwoPi);
        TopoDS_Wire wire;
        builder.MakeWire(wire);
        builder.Add(wire, w.cut_edge.Oriented(TopAbs_FORWARD));
        wire.Closed(true);
        builder.Add(cap, wire);
        // The disk faces away from the half it closes.
        if (side == 1) cap.Orientation(TopAbs_REVERSED);
      }
    }
  });

  for (const HubWork& h : hubs) {
    out.faces.push_back(h.face);
    out.face_owner.push_back(h.ball);
  }
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    BeamWork& w = beams[e];
    if (w.kind == BeamKind::None) continue;
    ++out.stats.beams;
    for (int side = 0; side < 2; ++side) {
      const std::int64_t owner = side == 0 ? f.beams[e].a : f.beams[e].b;
      if (!w.cone[side].IsNull()) {
        out.faces.push_back(w.cone[side]);
        out.face_owner.push_back(owner);
      }
      if (!w.cap[side].IsNull()) {
        out.faces.push_back(w.cap[side]);
        out.face_owner.push_back(owner);
        out.caps.push_back({e, side, w.cap[side]});
        ++out.stats.cut_caps;
      }
    }
    if (w.new_cut) cut_edges.emplace(e, w.cut_edge);
  }
  out.stats.balls = static_cast<std::int64_t>(hubs.size());
  out.stats.faces = static_cast<std::int64_t>(out.faces.size());
  out.stats.distinct_hubs = static_cast<std::int64_t>(shapes.size());
  for (const ShapeWork& w : shapes)
    for (const CircleLayout& c : w.layout.circles) out.stats.seam_crossing_circles += c.role != CircleRole::Inner;
  out.stats.topology_seconds = seconds_since(topology_start);
  return out;
}

TopoDS_Shape solids_from_faces(const std::vector<TopoDS_Face>& faces) {
  const std::int64_t n = static_cast<std::int64_t>(faces.size());
  std::vector<std::int64_t> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](std::int64_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  std::unordered_map<const void*, std::int64_t> first_face;
  first_face.reserve(static_cast<std::size_t>(3 * n));
  for (std::int64_t i = 0; i < n; ++i)
    for (TopExp_Explorer x(faces[i], TopAbs_EDGE); x.More(); x.Next()) {
      const void* key = x.Current().TShape().get();
      auto [it, inserted] = first_face.emplace(key, i);
      if (!inserted) parent[find(i)] = find(it->second);
    }
  std::unordered_map<std::int64_t, std::size_t> shell_of;
  std::vector<TopoDS_Shell> shells;
  const BRep_Builder b;
  for (std::int64_t i = 0; i < n; ++i) {
    const std::int64_t root = find(i);
    auto [it, inserted] = shell_of.emplace(root, shells.size());
    if (inserted) {
      shells.emplace_back();
      b.MakeShell(shells.back());
    }
    b.Add(shells[it->second], faces[i]);
  }
  // A shell whose faces point inward bounds a void (the inside of a skin): it joins the solid around it.
  std::vector<TopoDS_Solid> solids;
  std::vector<TopoDS_Shell> voids;
  for (TopoDS_Shell& s : shells) {
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
  if (solids.size() == 1) return solids[0];
  TopoDS_Compound compound;
  b.MakeCompound(compound);
  for (const TopoDS_Solid& s : solids) b.Add(compound, s);
  return compound;
}

LatticeBrep build_lattice_brep(const FlatLattice& lattice, SeamPreference seams) {
  const CleanReport report = check_clean(lattice);
  if (!report.clean()) {
    std::ostringstream os;
    os << "is not clean (" << report.issue_count << " issue" << (report.issue_count == 1 ? "" : "s") << "): ";
    for (std::size_t i = 0; i < std::min<std::size_t>(3, report.issues.size()); ++i)
      os << (i ? "; " : "") << report.issues[i].describe();
    if (report.issue_count > 3) os << "; ...";
    fail_input("lattice", os.str());
  }
  CutEdges cuts;
  BrepSelection selection = BrepSelection::everything(lattice);
  selection.seams = seams;
  BrepPieces pieces = build_brep_pieces(lattice, selection, cuts);
  LatticeBrep out;
  out.shape = solids_from_faces(pieces.faces);
  out.stats = pieces.stats;
  return out;
}

LatticeBrep build_lattice_brep(const Lattice& lattice) { return build_lattice_brep(flatten(lattice)); }

}  // namespace steady
