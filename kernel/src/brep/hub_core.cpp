#include "brep/hub_core.hpp"

#include <AdvApprox_ApproxAFunction.hxx>
#include <AdvApprox_EvaluatorFunction.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepGProp.hxx>
#include <GProp_GProps.hxx>
#include <BRepBuilderAPI_Transform.hxx>
#include <BRepLib_MakeFace.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <ElCLib.hxx>
#include <ElSLib.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Curve.hxx>
#include <Geom2d_Circle.hxx>
#include <Geom2d_Line.hxx>
#include <Geom_Circle.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_Ellipse.hxx>
#include <Geom_Hyperbola.hxx>
#include <Geom_Line.hxx>
#include <Geom_Parabola.hxx>
#include <Geom_Plane.hxx>
#include <Geom_SphericalSurface.hxx>
#include <IntAna_QuadQuadGeo.hxx>
#include <TColStd_HArray1OfInteger.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_ListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Shell.hxx>
#include <TopoDS_Solid.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Cone.hxx>
#include <gp_Cylinder.hxx>
#include <gp_Elips.hxx>
#include <gp_Hypr.hxx>
#include <gp_Parab.hxx>
#include <gp_Pln.hxx>

#include <algorithm>
#include <cstdlib>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "brep/portable_sphere_faces.hpp"
#include "lattice/circle_frames.hpp"
#include "lattice/cone_envelope.hpp"
#include "steady/lattice/convex_distance.hpp"
#include "steady/core/errors.hpp"
#include "steady/properties/hub_properties.hpp"
#include "brep/cusp_tolerance.hpp"
#include "brep/pcurve_pieces.hpp"
#include "brep/sphere_layout.hpp"

namespace steady {

namespace {

using hull::kCollarClearance;
constexpr double kTwoPi = 2.0 * M_PI;
// Exact edges of a canonical core (unit ball): OpenCASCADE's confusion tolerance; copies scale it.
constexpr double kCoreTolerance = 1e-7;
// (u, v) accuracy of the approximated pcurves of conic and circle arcs (radians or unit-ball lengths).
constexpr double kCorePcurveTolerance = 1e-9;
// The sphere face's seam and poles must lie inside the caps by this much (cosine units), and the seam is sampled
// at half this step, so by the Lipschitz bound of the margin function it never meets the sphere face.
constexpr double kSeamMargin = 0.01;
constexpr int kSeamSamples = 360;
// Candidate poles (a Fibonacci sphere, plus the stumps' axes) and seam directions per pole for the sphere face.
constexpr int kPoleCandidates = 96;
constexpr int kSeamCandidates = 36;

gp_Pnt pnt(const Vec3& v) { return gp_Pnt(v.x, v.y, v.z); }
gp_Dir dir(const Vec3& v) { return gp_Dir(v.x, v.y, v.z); }


[[noreturn]] void unsupported(const std::string& why) { fail_input("hub", why); }

using hull::Cone;

// The cone's frame and surface in OpenCASCADE: origin on the tangent circle's center, X along e.
gp_Ax3 cone_frame(const Cone& k) { return gp_Ax3(pnt(k.s * k.d), dir(k.d), dir(k.e)); }

Handle(Geom_Surface) cone_surface(const Cone& k) {
  if (std::abs(k.s) < 1e-14) return new Geom_CylindricalSurface(cone_frame(k), k.c);
  return new Geom_ConicalSurface(cone_frame(k), -std::asin(k.s), k.c);
}


// ---------------------------------------------------------------------------------------------------------------
// pcurves of arcs on elementary surfaces, approximated with the arc's own parameter.

class ArcOnSurface : public AdvApprox_EvaluatorFunction {
 public:
  // u is unwrapped toward the straight line from (t0, u0) to (t1, u1) (monotone along the envelope).
  ArcOnSurface(const Handle(Geom_Curve)& curve, const Handle(Geom_Surface)& surface, double t0, double t1, double u0,
               double u1)
      : curve_(curve), surface_(surface), t0_(t0), t1_(t1), u0_(u0), u1_(u1) {}
  void Evaluate(Standard_Integer*, Standard_Real[2], Standard_Real* t, Standard_Integer* derivative,
                Standard_Real* result, Standard_Integer* error) override {
    gp_Pnt p;
    gp_Vec dp;
    curve_->D1(*t, p, dp);
    double u, v;
    parameters(p, u, v);
    const double guess = u0_ + (u1_ - u0_) * (*t - t0_) / (t1_ - t0_);
    u += kTwoPi * std::round((guess - u) / kTwoPi);
    if (*derivative == 0) {
      result[0] = u;
      result[1] = v;
    } else {
      gp_Pnt q;
      gp_Vec su, sv;
      surface_->D1(u, v, q, su, sv);
      const double a = su.Dot(su), b = su.Dot(sv), c = sv.Dot(sv), r1 = su.Dot(dp), r2 = sv.Dot(dp);
      const double det = a * c - b * b;
      result[0] = (c * r1 - b * r2) / det;
      result[1] = (a * r2 - b * r1) / det;
    }
    *error = 0;
  }

 private:
  void parameters(const gp_Pnt& p, double& u, double& v) const {
    const Handle(Standard_Type)& type = surface_->DynamicType();
    if (type == STANDARD_TYPE(Geom_ConicalSurface))
      ElSLib::Parameters(Handle(Geom_ConicalSurface)::DownCast(surface_)->Cone(), p, u, v);
    else if (type == STANDARD_TYPE(Geom_CylindricalSurface))
      ElSLib::Parameters(Handle(Geom_CylindricalSurface)::DownCast(surface_)->Cylinder(), p, u, v);
    else
      ElSLib::Parameters(Handle(Geom_SphericalSurface)::DownCast(surface_)->Sphere(), p, u, v);
  }
  Handle(Geom_Curve) curve_;
  Handle(Geom_Surface) surface_;
  double t0_, t1_, u0_, u1_;
};

Handle(Geom2d_BSplineCurve) approximate(AdvApprox_EvaluatorFunction& f, double t0, double t1, double& error) {
  Handle(TColStd_HArray1OfReal) tol = new TColStd_HArray1OfReal(1, 1);
  tol->SetValue(1, kCorePcurveTolerance);
  AdvApprox_ApproxAFunction approx(0, 1, 0, Handle(TColStd_HArray1OfReal)(), tol, Handle(TColStd_HArray1OfReal)(), t0,
                                   t1, GeomAbs_C1, 14, 400, f);
  if (!approx.HasResult()) throw std::runtime_error("hub core: the approximation of an arc's pcurve failed");
  TColgp_Array1OfPnt2d poles(1, approx.NbPoles());
  approx.Poles2d(1, poles);
  error = std::max(error, approx.MaxError(2, 1));
  return new Geom2d_BSplineCurve(poles, approx.Knots()->Array1(), approx.Multiplicities()->Array1(), approx.Degree());
}

// The sphere arcs use the sphere layout's longitudes (the seam avoided: branch Inner).
class SphereArc : public AdvApprox_EvaluatorFunction {
 public:
  SphereArc(const SphereLayout& layout, int circle) : layout_(layout), circle_(circle) {}
  void Evaluate(Standard_Integer*, Standard_Real[2], Standard_Real* t, Standard_Integer* derivative,
                Standard_Real* result, Standard_Integer* error) override {
    layout_.uv(circle_, ArcBranch::Inner, *t, result, *derivative);
    *error = 0;
  }

 private:
  const SphereLayout& layout_;
  int circle_;
};

// The conic where cone i meets the plane w_i = w_j, as the OpenCASCADE curve nearest to `near`.
Handle(Geom_Curve) conic_between(const Cone& ki, const Cone& kj, const Vec3& near) {
  const Vec3 n = ki.d / ki.c - kj.d / kj.c;
  const double b = ki.s / ki.c - kj.s / kj.c;
  const double nn = glm::length(n);
  const gp_Pln plane(pnt(n * (b / (nn * nn))), dir(n / nn));
  IntAna_QuadQuadGeo inter;
  if (std::abs(ki.s) < 1e-14)
    inter.Perform(plane, gp_Cylinder(cone_frame(ki), ki.c), 1e-12, 1e-12);
  else
    inter.Perform(plane, gp_Cone(cone_frame(ki), -std::asin(ki.s), ki.c), 1e-12, 1e-12);
  if (!inter.IsDone()) unsupported("the intersection of two stumps could not be computed");
  Handle(Geom_Curve) best;
  double best_d = std::numeric_limits<double>::infinity();
  const gp_Pnt p = pnt(near);
  for (int k = 1; k <= inter.NbSolutions(); ++k) {
    Handle(Geom_Curve) c;
    double d = 0;
    switch (inter.TypeInter()) {
      case IntAna_Circle: {
        const gp_Circ g = inter.Circle(k);
        c = new Geom_Circle(g);
        d = ElCLib::Value(ElCLib::Parameter(g, p), g).Distance(p);
        break;
      }
      case IntAna_Ellipse: {
        const gp_Elips g = inter.Ellipse(k);
        c = new Geom_Ellipse(g);
        d = ElCLib::Value(ElCLib::Parameter(g, p), g).Distance(p);
        break;
      }
      case IntAna_Hyperbola: {
        const gp_Hypr g = inter.Hyperbola(k);
        c = new Geom_Hyperbola(g);
        d = ElCLib::Value(ElCLib::Parameter(g, p), g).Distance(p);
        break;
      }
      case IntAna_Parabola: {
        const gp_Parab g = inter.Parabola(k);
        c = new Geom_Parabola(g);
        d = ElCLib::Value(ElCLib::Parameter(g, p), g).Distance(p);
        break;
      }
      default:
        unsupported("two stumps meet in a degenerate conic (a plane through a cone's apex)");
    }
    if (d < best_d) {
      best_d = d;
      best = c;
    }
  }
  if (best.IsNull() || best_d > 1e-6) unsupported("the intersection of two stumps is not where expected");
  return best;
}

double curve_parameter(const Handle(Geom_Curve)& c, const Vec3& x) {
  const gp_Pnt p = pnt(x);
  if (auto e = Handle(Geom_Ellipse)::DownCast(c)) return ElCLib::Parameter(e->Elips(), p);
  if (auto h = Handle(Geom_Hyperbola)::DownCast(c)) return ElCLib::Parameter(h->Hypr(), p);
  if (auto q = Handle(Geom_Parabola)::DownCast(c)) return ElCLib::Parameter(q->Parab(), p);
  if (auto ci = Handle(Geom_Circle)::DownCast(c)) return ElCLib::Parameter(ci->Circ(), p);
  throw std::runtime_error("hub core: unexpected conic type");
}

// An arrangement edge shared by two faces (two cones, or a cone and the sphere).
struct CoreEdge {
  int face_a = -1, face_b = -1;  // face_b = -1: the sphere
  Handle(Geom_Curve) curve;
  double t0 = 0.0, t1 = 0.0;     // parameter range, t0 < t1
  bool forward_on_a = true;      // face a runs it from t0 to t1
  int vertex_t0 = -1, vertex_t1 = -1;
  TopoDS_Edge edge;
  // Pieces on each face (their u range), to unwrap the pcurves.
  double a_u0 = 0, a_u1 = 0, b_u0 = 0, b_u1 = 0;
  bool on_sphere() const { return face_b < 0; }
};

// The ball's radius R where the cones (tangent to the unit sphere) leave it at exit_v: |x|^2 = 1 + v^2.
double ball_radius(const Cone& k) { return std::sqrt(1.0 + k.exit_v * k.exit_v); }

// Cone k's exit cap on the ball, as a cap of the unit sphere of directions: d.x >= height.
double exit_cap_height(const Cone& k) { return (k.s + k.exit_v * k.c) / ball_radius(k); }

// Frame for the sphere face: its poles and seam either well inside the union of the exit caps (crowded caps: the
// face is bounded by its loops alone) or well outside every cap (the face keeps the sphere's natural boundary,
// the seam and the poles, and every loop around caps is a hole), whichever leaves the wider margin.
struct SphereFrame {
  Vec3 z, x;
  bool seam_inside_caps = true;
  double margin = -1e300;
  bool crossing = false;  // the seam crosses the face's loops (crossing_frame)
};

// Where the seam crosses the boundary of the sphere face: its latitude, the cone whose exit circle it crosses,
// and (once the arrangement is split there) the vertex.
struct SeamCrossing {
  double latitude = 0.0;
  int cone = -1;
  int vertex = -1;
};

// The exit cap nearest to containing p: its index, its margin d.p - height (> 0 inside) and the runner-up's.
struct CapMargin {
  int cap = -1;
  double margin = -1e300, second = -1e300;
};
CapMargin cap_margin(const std::vector<Cone>& cones, const Vec3& p) {
  CapMargin m;
  for (int k = 0; k < static_cast<int>(cones.size()); ++k) {
    const double x = glm::dot(cones[k].d, p) - exit_cap_height(cones[k]);
    if (x > m.margin) {
      m.second = m.margin;
      m.margin = x;
      m.cap = k;
    } else {
      m.second = std::max(m.second, x);
    }
  }
  return m;
}

// Candidate poles of the sphere face's frame: a Fibonacci sphere and the stumps' axes.
std::vector<Vec3> pole_candidates(const std::vector<Cone>& cones) {
  std::vector<Vec3> poles;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kPoleCandidates; ++i) {
    const double zc = 1.0 - (2.0 * i + 1.0) / kPoleCandidates, r = std::sqrt(1.0 - zc * zc);
    poles.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), zc);
  }
  for (const Cone& k : cones) poles.push_back(k.d);
  return poles;
}

SphereFrame choose_sphere_frame(const std::vector<Cone>& cones) {
  auto inside_margin = [&](const Vec3& p) { return cap_margin(cones, p).margin; };
  const std::vector<Vec3> poles = pole_candidates(cones);
  SphereFrame best;
  for (const Vec3& z : poles) {
    const double north = inside_margin(z), south = inside_margin(-z);
    // Margins for the seam inside the caps (m_in) and outside all of them (m_out).
    const double pole_in = std::min(north, south), pole_out = std::min(-north, -south);
    if (std::max(pole_in, pole_out) <= best.margin) continue;
    const Vec3 x0 = any_perpendicular(z), y0 = glm::cross(z, x0);
    for (int k = 0; k < kSeamCandidates; ++k) {
      const double a = kTwoPi * k / kSeamCandidates;
      const Vec3 x = std::cos(a) * x0 + std::sin(a) * y0;
      double m_in = pole_in, m_out = pole_out;
      for (int s = 1; s < kSeamSamples && std::max(m_in, m_out) > best.margin; ++s) {
        const double lat = -M_PI / 2 + M_PI * s / kSeamSamples;
        const double m = inside_margin(std::cos(lat) * x + std::sin(lat) * z);
        m_in = std::min(m_in, m);
        m_out = std::min(m_out, -m);
      }
      if (std::max(m_in, m_out) > best.margin) best = {z, x, m_in >= m_out, std::max(m_in, m_out)};
    }
  }
  return best;
}

// A frame whose seam crosses the sphere face's loops (when neither inside nor outside every cap leaves room):
// poles well inside a cap or well outside all, and every crossing clear of the other caps (so not near a vertex
// of the loops) and transversal. The seam may leave the caps only around its poles: a stretch of it inside
// the caps between two crossings would lay a hole across the periodic boundary, which OpenCASCADE accepts but
// STEP readers rebuild as intersecting wires (section 5 of docs/brep.md). The margin is the worst of those
// clearances (cosine units) and a fifth of the worst crossing's sine of angle.
SphereFrame crossing_frame(const std::vector<Cone>& cones, std::vector<SeamCrossing>& crossings) {
  const std::vector<Vec3> poles = pole_candidates(cones);
  SphereFrame best;
  best.crossing = true;
  std::vector<SeamCrossing> found;
  for (const Vec3& z : poles) {
    const double pole = std::min(std::abs(cap_margin(cones, z).margin), std::abs(cap_margin(cones, -z).margin));
    if (pole <= best.margin) continue;
    const Vec3 x0 = any_perpendicular(z), y0 = glm::cross(z, x0);
    for (int k = 0; k < kSeamCandidates; ++k) {
      const double a = kTwoPi * k / kSeamCandidates;
      const Vec3 x = std::cos(a) * x0 + std::sin(a) * y0;
      auto at = [&](double lat) { return std::cos(lat) * x + std::sin(lat) * z; };
      double score = pole;
      bool entered = false;
      found.clear();
      double previous = cap_margin(cones, at(-M_PI / 2)).margin;
      for (int s = 1; s <= kSeamSamples && score > best.margin; ++s) {
        double lo = -M_PI / 2 + M_PI * (s - 1) / kSeamSamples, hi = -M_PI / 2 + M_PI * s / kSeamSamples;
        const double here = cap_margin(cones, at(hi)).margin;
        if ((previous > 0) != (here > 0)) {
          const bool rising = here > 0;
          // Out of the caps only at the first crossing, into them only at the last.
          if (entered || (!rising && !found.empty())) score = -1e300;
          entered = entered || rising;
          for (int it = 0; it < 50; ++it) {
            const double mid = 0.5 * (lo + hi);
            ((cap_margin(cones, at(mid)).margin > 0) == rising ? hi : lo) = mid;
          }
          const double lat = 0.5 * (lo + hi);
          const Vec3 p = at(lat), tangent = -std::sin(lat) * x + std::cos(lat) * z;
          const CapMargin m = cap_margin(cones, p);
          const Vec3 d = cones[m.cap].d, g = d - glm::dot(d, p) * p;
          const double sine = std::abs(glm::dot(d, tangent)) / std::max(glm::length(g), 1e-300);
          score = std::min({score, -m.second, 0.2 * sine});
          found.push_back({lat, m.cap, -1});
        }
        previous = here;
      }
      if (score > best.margin) {
        best.z = z;
        best.x = x;
        best.margin = score;
        crossings = found;
      }
    }
  }
  return best;
}

// What the steps of a hull-model core share: the cones and their arrangement, the edges between faces, and the
// OpenCASCADE topology as it is made.
struct HullCoreBuild {
  std::vector<Cone> cones;
  std::vector<double> v_collar;  // each collar's v on its cone
  hull::Arrangement arrangement;
  SphereFrame frame;                    // of the sphere face, chosen before the edges are made
  std::vector<SeamCrossing> crossings;  // where its seam crosses the face's loops (a crossing frame only)
  std::vector<CoreEdge> edges;
  std::vector<std::vector<std::size_t>> face_edges;  // per cone, its edges in the order of its envelope's pieces
  BRep_Builder builder;
  std::vector<TopoDS_Vertex> vertices;
  std::vector<Handle(Geom_Surface)> surfaces;
  std::vector<TopoDS_Face> cone_faces;
  std::vector<TopoDS_Face> sphere_faces;
  double max_error = 0.0;  // of the approximated pcurves
};

// The exit circle arc shared by cone i and the sphere (its tangent circle in the hull model), with the circle's
// parameter as the cone's u.
CoreEdge sphere_edge(const Cone& k, int i, const hull::Piece& p) {
  CoreEdge e;
  e.face_a = i;
  e.curve = new Geom_Circle(gp_Ax2(pnt((k.s + k.exit_v * k.c) * k.d), dir(k.d), dir(k.e)), k.c - k.exit_v * k.s);
  e.t0 = e.a_u0 = p.u0;
  e.t1 = e.a_u1 = p.u1;
  e.forward_on_a = true;
  e.vertex_t0 = p.v0;
  e.vertex_t1 = p.v1;
  return e;
}

// The conic arc where cone i meets cone p.active, from vertex p.v0 through `mid` to p.v1 as cone i runs it.
CoreEdge conic_edge(const HullCoreBuild& h, int i, const hull::Piece& p, const Vec3& mid) {
  const std::vector<Vec3>& points = h.arrangement.vertices.points;
  CoreEdge e;
  e.face_a = i;
  e.face_b = p.active;
  e.curve = conic_between(h.cones[i], h.cones[p.active], mid);
  const double ta = curve_parameter(e.curve, points[p.v0]), tb = curve_parameter(e.curve, points[p.v1]);
  const double tm = curve_parameter(e.curve, mid);
  if (e.curve->IsPeriodic()) {
    // The arc from the start through the middle to the end, within one period.
    const double per = e.curve->Period();
    const double mw = ta + std::fmod(std::fmod(tm - ta, per) + per, per);
    double bw = ta + std::fmod(std::fmod(tb - ta, per) + per, per);
    if (p.v0 == p.v1) bw = ta + per;
    e.forward_on_a = mw <= bw;
    e.t0 = e.forward_on_a ? ta : bw - per;
    e.t1 = e.forward_on_a ? bw : ta;
  } else {
    e.forward_on_a = ta < tb;
    e.t0 = std::min(ta, tb);
    e.t1 = std::max(ta, tb);
    if (!(tm > e.t0 && tm < e.t1)) unsupported("an open conic arc does not hold its middle point");
  }
  e.vertex_t0 = e.forward_on_a ? p.v0 : p.v1;
  e.vertex_t1 = e.forward_on_a ? p.v1 : p.v0;
  e.a_u0 = p.u0;
  e.a_u1 = p.u1;
  return e;
}

// Edges: each cone-cone piece appears on both cones (in opposite directions) and becomes one edge; each sphere
// piece appears once.
void collect_core_edges(HullCoreBuild& h) {
  const int n = static_cast<int>(h.cones.size());
  std::map<std::tuple<int, int, int, int>, std::size_t> edge_index;
  h.face_edges.assign(n, {});
  for (int i = 0; i < n; ++i) {
    for (const hull::Piece& p : h.arrangement.envelopes[i].pieces) {
      if (p.active < 0) {
        h.face_edges[i].push_back(h.edges.size());
        h.edges.push_back(sphere_edge(h.cones[i], i, p));
        continue;
      }
      const int j = p.active;
      // Key from the lower face's point of view: (low, high, its start vertex, its end vertex).
      const auto key = i < j ? std::make_tuple(i, j, p.v0, p.v1) : std::make_tuple(j, i, p.v1, p.v0);
      auto found = edge_index.find(key);
      if (found != edge_index.end()) {
        CoreEdge& e = h.edges[found->second];
        e.b_u0 = p.u0;
        e.b_u1 = p.u1;
        h.face_edges[i].push_back(found->second);
        continue;
      }
      const double u_mid = 0.5 * (p.u0 + p.u1);
      const Vec3 mid = h.cones[i].point(u_mid, hull::envelope_at(h.cones, i, u_mid).v);
      edge_index.emplace(key, h.edges.size());
      h.face_edges[i].push_back(h.edges.size());
      h.edges.push_back(conic_edge(h, i, p, mid));
    }
  }
  for (const auto& [key, index] : edge_index)
    if (h.edges[index].b_u1 == 0.0 && h.edges[index].b_u0 == 0.0)
      unsupported("the stumps' faces disagree about one of their edges");
}

// Vertices, edges on their curves, and one face per cone on its surface (bounded later).
void make_core_topology(HullCoreBuild& h) {
  for (const Vec3& p : h.arrangement.vertices.points) {
    TopoDS_Vertex v;
    h.builder.MakeVertex(v, pnt(p), kCoreTolerance);
    h.vertices.push_back(v);
  }
  for (CoreEdge& e : h.edges) {
    h.builder.MakeEdge(e.edge, e.curve, kCoreTolerance);
    h.builder.Add(e.edge, h.vertices[e.vertex_t0].Oriented(TopAbs_FORWARD));
    h.builder.Add(e.edge, h.vertices[e.vertex_t1].Oriented(TopAbs_REVERSED));
  }
  h.cone_faces.resize(h.cones.size());
  for (std::size_t i = 0; i < h.cones.size(); ++i) {
    h.surfaces.push_back(cone_surface(h.cones[i]));
    h.builder.MakeFace(h.cone_faces[i], h.surfaces[i], kCoreTolerance);
  }
}

// Each edge's pcurves on its cones: the exit circle is the line v = exit_v; conic arcs are approximated with the
// arc's own parameter, u unwrapped along the piece each face runs.
void add_cone_pcurves(HullCoreBuild& h) {
  for (CoreEdge& e : h.edges) {
    if (e.on_sphere()) {
      const double v = h.cones[e.face_a].exit_v;
      h.builder.UpdateEdge(e.edge, new Geom2d_Line(gp_Pnt2d(0, v), gp_Dir2d(1, 0)), h.cone_faces[e.face_a],
                           kCoreTolerance);
      continue;
    }
    for (int side = 0; side < 2; ++side) {
      const int face = side == 0 ? e.face_a : e.face_b;
      // The face runs the arc from its u0 to its u1; map the curve's ends accordingly.
      const bool forward = side == 0 ? e.forward_on_a : !e.forward_on_a;
      const double u0 = side == 0 ? e.a_u0 : e.b_u0, u1 = side == 0 ? e.a_u1 : e.b_u1;
      ArcOnSurface f(e.curve, h.surfaces[face], e.t0, e.t1, forward ? u0 : u1, forward ? u1 : u0);
      h.builder.UpdateEdge(e.edge, approximate(f, e.t0, e.t1, h.max_error), h.cone_faces[face], kCoreTolerance);
    }
  }
}

// Cone i's face: bounded by its envelope's edges, the seam (the generator where its first piece starts) up to
// the collar circle, the collar backwards, and the seam back down. Returns the collar edge.
TopoDS_Edge close_cone_face(HullCoreBuild& h, int i) {
  const Cone& k = h.cones[i];
  const BRep_Builder& b = h.builder;
  const hull::Piece& first = h.arrangement.envelopes[i].pieces[0];
  const double u_star = first.u0, v_collar = h.v_collar[i];
  const double v_start = k.w(h.arrangement.vertices.points[first.v0]);
  // Collar circle: parameter u, its vertex at u_star.
  Handle(Geom_Circle) collar_curve =
      new Geom_Circle(gp_Ax2(pnt(k.s * k.d + v_collar * k.c * k.d), dir(k.d), dir(k.e)), k.c - v_collar * k.s);
  TopoDS_Vertex cv;
  b.MakeVertex(cv, collar_curve->Value(u_star), kCoreTolerance);
  TopoDS_Edge collar;
  b.MakeEdge(collar, collar_curve, kCoreTolerance);
  b.Add(collar, cv.Oriented(TopAbs_FORWARD));
  b.Add(collar, cv.Oriented(TopAbs_REVERSED));
  b.UpdateEdge(collar, new Geom2d_Line(gp_Pnt2d(0, v_collar), gp_Dir2d(1, 0)), h.cone_faces[i], kCoreTolerance);
  b.Range(collar, u_star, u_star + kTwoPi);
  // Seam: the generator at u_star, parameterized by v.
  Handle(Geom_Line) line = new Geom_Line(pnt(k.point(u_star, 0.0)), dir(k.point(u_star, 1.0) - k.point(u_star, 0.0)));
  TopoDS_Edge seam;
  b.MakeEdge(seam, line, kCoreTolerance);
  b.Add(seam, h.vertices[first.v0].Oriented(TopAbs_FORWARD));
  b.Add(seam, cv.Oriented(TopAbs_REVERSED));
  b.UpdateEdge(seam, new Geom2d_Line(gp_Pnt2d(u_star + kTwoPi, 0), gp_Dir2d(0, 1)),
               new Geom2d_Line(gp_Pnt2d(u_star, 0), gp_Dir2d(0, 1)), h.cone_faces[i], kCoreTolerance);
  b.Range(seam, v_start, v_collar);
  TopoDS_Wire wire;
  b.MakeWire(wire);
  for (std::size_t edge : h.face_edges[i]) {
    const CoreEdge& e = h.edges[edge];
    const bool forward = e.face_a == i ? e.forward_on_a : !e.forward_on_a;
    b.Add(wire, e.edge.Oriented(forward ? TopAbs_FORWARD : TopAbs_REVERSED));
  }
  b.Add(wire, seam.Oriented(TopAbs_FORWARD));
  b.Add(wire, collar.Oriented(TopAbs_REVERSED));
  b.Add(wire, seam.Oriented(TopAbs_REVERSED));
  wire.Closed(true);
  b.Add(h.cone_faces[i], wire);
  return collar;
}

// A closed loop of sphere arcs, run backwards (the caps on its right), as a polygon in the sphere's (u, v) with
// its signed area: positive for an outer boundary, negative for a hole.
struct SphereLoop {
  std::vector<std::size_t> arcs;
  std::vector<gp_Pnt2d> polygon;
  double area = 0.0;
  bool contains(const gp_Pnt2d& p) const;
  void measure();  // the area of the polygon (shoelace)
};

void SphereLoop::measure() {
  area = 0.0;
  for (std::size_t k = 0; k < polygon.size(); ++k) {
    const gp_Pnt2d &p = polygon[k], &q = polygon[(k + 1) % polygon.size()];
    area += 0.5 * (p.X() * q.Y() - q.X() * p.Y());
  }
}

bool SphereLoop::contains(const gp_Pnt2d& p) const {
  bool in = false;
  for (std::size_t k = 0, j = polygon.size() - 1; k < polygon.size(); j = k++) {
    const gp_Pnt2d &a = polygon[k], &b = polygon[j];
    if ((a.Y() > p.Y()) != (b.Y() > p.Y()) &&
        p.X() < a.X() + (b.X() - a.X()) * (p.Y() - a.Y()) / (b.Y() - a.Y()))
      in = !in;
  }
  return in;
}

std::vector<SphereLoop> sphere_loops(const HullCoreBuild& h, const std::vector<std::size_t>& sphere_arcs,
                                     std::map<std::size_t, Handle(Geom2d_Curve)>& pcurve) {
  // The next arc of a loop ends where this one starts.
  std::map<int, std::size_t> by_end;
  for (std::size_t k : sphere_arcs) by_end[h.edges[k].vertex_t1] = k;
  std::vector<char> used(h.edges.size(), 0);
  std::vector<SphereLoop> loops;
  for (std::size_t start : sphere_arcs) {
    if (used[start]) continue;
    SphereLoop loop;
    for (std::size_t k = start;;) {
      used[k] = 1;
      loop.arcs.push_back(k);
      if (h.edges[k].vertex_t0 == h.edges[start].vertex_t1) break;
      auto next = by_end.find(h.edges[k].vertex_t0);
      if (next == by_end.end() || used[next->second]) unsupported("the part of the ball between the stumps is not closed");
      k = next->second;
    }
    // Polygon and shoelace area, run backwards along each arc.
    for (std::size_t a : loop.arcs) {
      const CoreEdge& e = h.edges[a];
      for (int s = 0; s < 32; ++s) loop.polygon.push_back(pcurve[a]->Value(e.t1 - (e.t1 - e.t0) * s / 32.0));
    }
    loop.measure();
    loops.push_back(loop);
  }
  return loops;
}

// The frame of the sphere face, before the edges are made: its seam inside the caps or outside all of them if
// either leaves room; else a seam crossing the face's loops, each crossed arc split there by a new vertex (an
// arc never runs across the seam, so each keeps one (u, v) curve).
void choose_frame_and_split(HullCoreBuild& h) {
  bool sphere = false;
  for (const hull::Envelope& env : h.arrangement.envelopes)
    for (const hull::Piece& p : env.pieces) sphere = sphere || p.active < 0;
  if (!sphere) return;
  h.frame = choose_sphere_frame(h.cones);
  if (h.frame.margin > kSeamMargin) return;
  std::vector<SeamCrossing> crossings;
  h.frame = crossing_frame(h.cones, crossings);
  if (!(h.frame.margin > kSeamMargin))
    unsupported("the part of the ball between the stumps leaves no room for the sphere's seam");
  for (SeamCrossing& x : crossings) {
    const Cone& k = h.cones[x.cone];
    const double u = k.u_of(std::cos(x.latitude) * h.frame.x + std::sin(x.latitude) * h.frame.z);
    std::vector<hull::Piece>& pieces = h.arrangement.envelopes[x.cone].pieces;
    std::size_t at = pieces.size();
    double uu = 0.0;
    for (std::size_t q = 0; q < pieces.size() && at == pieces.size(); ++q) {
      if (pieces[q].active >= 0) continue;
      uu = pieces[q].u0 + std::fmod(std::fmod(u - pieces[q].u0, kTwoPi) + kTwoPi, kTwoPi);
      if (uu > pieces[q].u0 + 1e-9 && uu < pieces[q].u1 - 1e-9) at = q;
    }
    if (at == pieces.size()) unsupported("the sphere's seam crosses a loop away from its arcs");
    x.vertex = h.arrangement.vertices.find_or_add(k.point(uu, k.exit_v));
    hull::Piece second = pieces[at];
    second.u0 = uu;
    second.v0 = x.vertex;
    pieces[at].u1 = uu;
    pieces[at].v1 = x.vertex;
    pieces.insert(pieces.begin() + static_cast<std::ptrdiff_t>(at) + 1, second);
  }
  std::sort(crossings.begin(), crossings.end(),
            [](const SeamCrossing& a, const SeamCrossing& b) { return a.latitude < b.latitude; });
  h.crossings = crossings;
}

// One piece of a sphere face's boundary, run with the face on its left in (u, v).
struct FaceRun {
  TopoDS_Edge edge;
  TopAbs_Orientation orientation = TopAbs_FORWARD;
  Handle(Geom2d_Curve) pcurve, pcurve_reversed;  // the second only for seam pieces
  double t_start = 0.0, t_end = 0.0;             // the run's parameters on pcurve, in running order
  bool pole = false;
  gp_Pnt2d start() const { return pcurve->Value(t_start); }
  gp_Pnt2d end() const { return pcurve->Value(t_end); }
};

// The seam's pieces outside every cap (up the side u = 2 pi, down u = 0) and the poles outside every cap
// (degenerate edges along v = -pi/2 and pi/2) as runs of the sphere face's wires.
void add_seam_runs(HullCoreBuild& h, const Handle(Geom_SphericalSurface)& sphere, std::vector<FaceRun>& runs) {
  const SphereFrame& fr = h.frame;
  const double radius = sphere->Radius();
  const BRep_Builder& b = h.builder;
  // Seam stops from the south pole up.
  auto outside_caps = [&](double lat) {
    return cap_margin(h.cones, std::cos(lat) * fr.x + std::sin(lat) * fr.z).margin < 0.0;
  };
  const Vec3 y = glm::cross(fr.z, fr.x);
  // From the south pole (t = latitude + pi/2): ranges in [0, pi], as the builder's seams (see build_sphere_face).
  Handle(Geom_Circle) meridian = new Geom_Circle(gp_Ax2(gp::Origin(), dir(-y), dir(-fr.z)), radius);
  std::vector<std::pair<double, TopoDS_Vertex>> stops;
  auto pole_vertex = [&](double lat) {
    TopoDS_Vertex v;
    b.MakeVertex(v, meridian->Value(lat + M_PI / 2), kCoreTolerance);
    return v;
  };
  stops.emplace_back(-M_PI / 2, pole_vertex(-M_PI / 2));
  for (const SeamCrossing& x : h.crossings) stops.emplace_back(x.latitude, h.vertices[x.vertex]);
  stops.emplace_back(M_PI / 2, pole_vertex(M_PI / 2));
  for (std::size_t k = 0; k + 1 < stops.size(); ++k) {
    const double lo = stops[k].first, hi = stops[k + 1].first;
    if (!outside_caps(0.5 * (lo + hi))) continue;
    TopoDS_Edge e;
    b.MakeEdge(e, meridian, kCoreTolerance);
    b.Add(e, stops[k].second.Oriented(TopAbs_FORWARD));
    b.Add(e, stops[k + 1].second.Oriented(TopAbs_REVERSED));
    b.Range(e, lo + M_PI / 2, hi + M_PI / 2);
    FaceRun up;
    up.edge = e;
    up.pcurve = new Geom2d_Line(gp_Pnt2d(kTwoPi, -M_PI / 2), gp_Dir2d(0, 1));
    up.pcurve_reversed = new Geom2d_Line(gp_Pnt2d(0.0, -M_PI / 2), gp_Dir2d(0, 1));
    up.t_start = lo + M_PI / 2;
    up.t_end = hi + M_PI / 2;
    FaceRun down = up;
    down.orientation = TopAbs_REVERSED;
    std::swap(down.pcurve, down.pcurve_reversed);
    std::swap(down.t_start, down.t_end);
    runs.push_back(up);
    runs.push_back(down);
  }
  for (int side = 0; side < 2; ++side) {  // poles outside every cap: degenerate edges
    const double lat = side == 0 ? -M_PI / 2 : M_PI / 2;
    if (!outside_caps(lat)) continue;
    const TopoDS_Vertex& v = side == 0 ? stops.front().second : stops.back().second;
    TopoDS_Edge e;
    b.MakeEdge(e);
    b.Add(e, v.Oriented(TopAbs_FORWARD));
    b.Add(e, v.Oriented(TopAbs_REVERSED));
    b.Degenerated(e, true);
    FaceRun r;
    r.edge = e;
    r.pole = true;
    r.pcurve = new Geom2d_Line(gp_Pnt2d(0.0, lat), gp_Dir2d(1, 0));
    r.orientation = side == 0 ? TopAbs_FORWARD : TopAbs_REVERSED;
    r.t_start = side == 0 ? 0.0 : kTwoPi;
    r.t_end = side == 0 ? kTwoPi : 0.0;
    runs.push_back(r);
  }
}

// The sphere face when its seam crosses the loops: in the (u, v) rectangle the face is bounded by the arcs (run
// with the caps on their right), the pieces of the seam that lie outside every cap (up the side u = 2 pi, down
// the side u = 0) and the poles outside every cap (degenerate edges along v = -pi/2 and pi/2). The runs are
// chained end to start into wires; counterclockwise wires are faces, clockwise ones holes of the face around them.
void build_crossing_sphere_faces(HullCoreBuild& h, const std::vector<std::size_t>& sphere_arcs) {
  const SphereFrame& fr = h.frame;
  const double radius = ball_radius(h.cones[0]);
  Handle(Geom_SphericalSurface) sphere =
      new Geom_SphericalSurface(gp_Ax3(gp::Origin(), dir(fr.z), dir(fr.x)), radius);
  const BRep_Builder& b = h.builder;

  std::vector<FaceRun> runs;
  for (std::size_t k : sphere_arcs) {
    CoreEdge& e = h.edges[k];
    double um, vm, ua, va, ub, vb;
    ElSLib::Parameters(sphere->Sphere(), e.curve->Value(0.5 * (e.t0 + e.t1)), um, vm);
    ElSLib::Parameters(sphere->Sphere(), e.curve->Value(e.t0), ua, va);
    ElSLib::Parameters(sphere->Sphere(), e.curve->Value(e.t1), ub, vb);
    ua += kTwoPi * std::round((um - ua) / kTwoPi);
    ub += kTwoPi * std::round((um - ub) / kTwoPi);
    ArcOnSurface f(e.curve, sphere, e.t0, e.t1, ua, ub);
    FaceRun r;
    r.edge = e.edge;
    r.orientation = TopAbs_REVERSED;
    r.pcurve = approximate(f, e.t0, e.t1, h.max_error);
    r.t_start = e.t1;
    r.t_end = e.t0;
    runs.push_back(r);
  }
  add_seam_runs(h, sphere, runs);
  // Chain runs end to start into wires, each with its polygon and signed area in (u, v).
  struct Loop {
    std::vector<std::size_t> runs;
    SphereLoop shape;
  };
  std::vector<Loop> loops;
  std::vector<char> used(runs.size(), 0);
  for (std::size_t first = 0; first < runs.size(); ++first) {
    if (used[first]) continue;
    Loop loop;
    for (std::size_t r = first;;) {
      used[r] = 1;
      loop.runs.push_back(r);
      const gp_Pnt2d end = runs[r].end();
      if (end.Distance(runs[first].start()) < 1e-6) break;
      std::size_t next = runs.size();
      for (std::size_t q = 0; q < runs.size(); ++q)
        if (!used[q] && runs[q].start().Distance(end) < 1e-6) next = q;
      if (next == runs.size()) unsupported("the part of the ball between the stumps is not closed across the seam");
      r = next;
    }
    for (std::size_t r : loop.runs)
      for (int s = 0; s < 32; ++s)
        loop.shape.polygon.push_back(
            runs[r].pcurve->Value(runs[r].t_start + (runs[r].t_end - runs[r].t_start) * s / 32.0));
    loop.shape.measure();
    loops.push_back(loop);
  }
  auto add_loop = [&](const Loop& loop, TopoDS_Face& face) {
    TopoDS_Wire w;
    b.MakeWire(w);
    for (std::size_t r : loop.runs) {
      const FaceRun& run = runs[r];
      if (!run.pcurve_reversed.IsNull()) {
        // The seam's two (u, v) curves: the first for the edge as it runs forward (up the side u = 2 pi).
        const bool forward = run.orientation == TopAbs_FORWARD;
        b.UpdateEdge(run.edge, forward ? run.pcurve : run.pcurve_reversed, forward ? run.pcurve_reversed : run.pcurve,
                     face, kCoreTolerance);
      } else {
        b.UpdateEdge(run.edge, run.pcurve, face, kCoreTolerance);
      }
      if (run.pole) b.Range(run.edge, 0.0, kTwoPi);
      b.Add(w, run.edge.Oriented(run.orientation));
    }
    w.Closed(true);
    b.Add(face, w);
  };
  std::vector<const Loop*> outer;
  for (const Loop& loop : loops) {
    if (loop.shape.area <= 0) continue;
    TopoDS_Face face;
    b.MakeFace(face, sphere, kCoreTolerance);
    add_loop(loop, face);
    h.sphere_faces.push_back(face);
    outer.push_back(&loop);
  }
  for (const Loop& loop : loops) {
    if (loop.shape.area > 0) continue;
    std::size_t face = outer.size();
    for (std::size_t k = 0; k < outer.size(); ++k)
      if (outer[k]->shape.contains(loop.shape.polygon.front())) face = k;
    if (face == outer.size()) unsupported("a hole in the part of the ball between the stumps lies in no face");
    add_loop(loop, h.sphere_faces[face]);
  }
  for (std::size_t k : sphere_arcs) b.Range(h.edges[k].edge, h.edges[k].t0, h.edges[k].t1);
}

// The sphere: the region outside all exit caps, bounded by the sphere arcs. Outer loops (counterclockwise in
// (u, v)) become faces; where the seam and poles lie outside the caps, one more face keeps the sphere's natural
// boundary. Each hole (clockwise) joins the outer loop around it, or the natural face.
void build_sphere_faces(HullCoreBuild& h) {
  std::vector<std::size_t> sphere_arcs;
  for (std::size_t k = 0; k < h.edges.size(); ++k)
    if (h.edges[k].on_sphere()) sphere_arcs.push_back(k);
  if (sphere_arcs.empty()) return;
  const SphereFrame& frame = h.frame;
  if (frame.crossing) {
    build_crossing_sphere_faces(h, sphere_arcs);
    return;
  }
  SphereLayout layout;
  layout.z = frame.z;
  layout.x = frame.x;
  for (const Cone& k : h.cones) {
    CircleLayout c;
    c.cap = {k.d, exit_cap_height(k)};
    c.e1 = k.e;
    c.e2 = k.f;
    c.rho = (k.c - k.exit_v * k.s) / ball_radius(k);
    layout.circles.push_back(c);
  }
  Handle(Geom_SphericalSurface) sphere =
      new Geom_SphericalSurface(gp_Ax3(gp::Origin(), dir(frame.z), dir(frame.x)), ball_radius(h.cones[0]));
  std::map<std::size_t, Handle(Geom2d_Curve)> pcurve;
  for (std::size_t k : sphere_arcs) {
    SphereArc f(layout, h.edges[k].face_a);
    pcurve[k] = approximate(f, h.edges[k].t0, h.edges[k].t1, h.max_error);
  }
  const std::vector<SphereLoop> loops = sphere_loops(h, sphere_arcs, pcurve);
  auto add_loop = [&](const SphereLoop& loop, TopoDS_Face& face) {
    TopoDS_Wire w;
    h.builder.MakeWire(w);
    for (std::size_t a : loop.arcs) {
      h.builder.UpdateEdge(h.edges[a].edge, pcurve[a], face, kCoreTolerance);
      h.builder.Add(w, h.edges[a].edge.Oriented(TopAbs_REVERSED));
    }
    w.Closed(true);
    h.builder.Add(face, w);
  };
  std::vector<const SphereLoop*> outer;
  for (const SphereLoop& loop : loops) {
    if (loop.area <= 0) continue;
    TopoDS_Face face;
    h.builder.MakeFace(face, sphere, kCoreTolerance);
    add_loop(loop, face);
    h.sphere_faces.push_back(face);
    outer.push_back(&loop);
  }
  if (!frame.seam_inside_caps) {
    // The sphere's own seam and degenerate pole edges bound this face.
    h.sphere_faces.push_back(BRepLib_MakeFace(sphere, 0.0, kTwoPi, -M_PI / 2, M_PI / 2, kCoreTolerance).Face());
  } else if (h.sphere_faces.empty()) {
    unsupported("the part of the ball between the stumps has no outer boundary");
  }
  for (const SphereLoop& loop : loops) {
    if (loop.area > 0) continue;
    std::size_t face = outer.size();  // the natural face, if no outer loop holds the hole
    for (std::size_t k = 0; k < outer.size(); ++k)
      if (outer[k]->contains(loop.polygon.front())) face = k;
    if (face == h.sphere_faces.size()) unsupported("a hole in the part of the ball between the stumps lies in no face");
    add_loop(loop, h.sphere_faces[face]);
  }
  for (std::size_t k : sphere_arcs) h.builder.Range(h.edges[k].edge, h.edges[k].t0, h.edges[k].t1);
}

// The core without Booleans when all stumps share their end radius rho (the hull model: rho = 1): each cone's
// face between its envelope and its collar, the sphere outside all caps (docs/brep.md, section 6). Built with the
// cones tangent to the unit sphere (the ball's radius is then 1 / rho) and scaled by rho into the canonical frame.
std::shared_ptr<const HubCore> build_envelope_core(const std::vector<CoreStump>& stumps, CoreKind kind,
                                                   const std::vector<double>& collars, CollarFit fit) {
  const int n = static_cast<int>(stumps.size());
  const double rho = shared_end_radius(stumps), ball = 1.0 / rho;
  HullCoreBuild h;
  h.cones = envelope_cones(stumps);
  for (int i = 0; i < n; ++i) h.v_collar.push_back((collars[i] * ball - h.cones[i].s) / h.cones[i].c);
  h.arrangement = hull::arrange_envelopes(h.cones, h.v_collar, envelope_clearance(fit));
  choose_frame_and_split(h);
  collect_core_edges(h);
  make_core_topology(h);
  add_cone_pcurves(h);
  auto out = std::make_shared<HubCore>();
  out->kind = kind;
  out->collar_position = collars;
  for (int i = 0; i < n; ++i) out->collars.push_back(close_cone_face(h, i));
  // Ranges last: they apply to every representation of the edge.
  for (CoreEdge& e : h.edges) h.builder.Range(e.edge, e.t0, e.t1);
  build_sphere_faces(h);
  // Tolerances from the approximations.
  const double tol = std::max(kCoreTolerance, 2.0 * h.max_error);
  for (CoreEdge& e : h.edges) h.builder.UpdateEdge(e.edge, tol);
  for (TopoDS_Vertex& v : h.vertices) h.builder.UpdateVertex(v, tol);
  h.builder.MakeCompound(out->faces);
  for (TopoDS_Face& f : h.cone_faces) h.builder.Add(out->faces, f);
  for (TopoDS_Face& f : h.sphere_faces) h.builder.Add(out->faces, f);
  out->face_count = static_cast<std::int64_t>(h.cone_faces.size() + h.sphere_faces.size());
  widen_cusp_vertices(out->faces);  // tangent exit caps: see cusp_tolerance.hpp
  if (rho == 1.0) return out;  // the hull model: built in place
  gp_Trsf scale;
  scale.SetScale(gp::Origin(), rho);
  BRepBuilderAPI_Transform placed(out->faces, scale, true);
  for (TopoDS_Edge& collar : out->collars) collar = TopoDS::Edge(placed.ModifiedShape(collar));
  out->faces = TopoDS::Compound(placed.Shape());
  return out;
}

// Angle from the unit vector d to the half great circle from pole z through seam direction x to -z.
double angle_to_seam(const Vec3& d, const Vec3& z, const Vec3& x) {
  if (glm::dot(d, x) >= 0.0) return std::asin(std::min(1.0, std::abs(glm::dot(d, glm::cross(z, x)))));
  const double to_pole = std::acos(std::clamp(glm::dot(d, z), -1.0, 1.0));
  return std::min(to_pole, M_PI - to_pole);
}

// Frames for the ball whose seam crosses no exit cap and whose poles are clear of the caps' circles (outside
// every cap, or inside one: a cap holding a pole is crossed by the seam once, which readers keep). Where a cap
// straddles the seam, the Fuse's sphere face carries a hole across the periodic boundary, which OpenCASCADE
// accepts but STEP readers rebuild as intersecting wires (docs/brep.md, section 5). Poles: 97 Fibonacci points
// on the upper half sphere and the stumps' axes; 72 seam directions each. The `count` best poles, each with its
// best seam, by the smallest clearance (radians) between a circle and a pole or the seam.
std::vector<gp_Ax2> portable_sphere_frames(const std::vector<CoreStump>& stumps, std::size_t count) {
  constexpr int kFibonacci = 97, kSeams = 72;
  std::vector<Vec3> poles;
  for (int k = 0; k < kFibonacci; ++k) {
    const double z = 1.0 - (k + 0.5) / kFibonacci, r = std::sqrt(1.0 - z * z), a = k * 2.399963229728653;
    poles.emplace_back(r * std::cos(a), r * std::sin(a), z);
  }
  // Each cap's axis and angular radius, once.
  std::vector<Vec3> axes;
  std::vector<double> thetas;
  for (const CoreStump& s : stumps) {
    axes.push_back(glm::normalize(s.direction));
    thetas.push_back(std::acos(s.exit));
  }
  poles.insert(poles.end(), axes.begin(), axes.end());
  std::vector<std::pair<double, gp_Ax2>> ranked;
  for (const Vec3& pole : poles) {
    double pole_clearance = 10.0;
    std::vector<bool> holds_pole(stumps.size(), false);
    for (std::size_t i = 0; i < stumps.size(); ++i) {
      const double to_pole = std::acos(std::clamp(glm::dot(axes[i], pole), -1.0, 1.0));
      const double nearest = std::min(to_pole, M_PI - to_pole);
      holds_pole[i] = nearest < thetas[i];
      pole_clearance = std::min(pole_clearance, std::abs(nearest - thetas[i]));
    }
    const Vec3 e0 = any_perpendicular(pole), e1 = glm::cross(pole, e0);
    double best = -10.0;
    Vec3 best_seam = e0;
    for (int j = 0; j < kSeams; ++j) {
      const double b = j * (2.0 * M_PI / kSeams);
      const Vec3 seam = std::cos(b) * e0 + std::sin(b) * e1;
      double clearance = pole_clearance;
      for (std::size_t i = 0; i < stumps.size(); ++i)
        if (!holds_pole[i])
          clearance = std::min(clearance, angle_to_seam(axes[i], pole, seam) - thetas[i]);
      if (clearance > best) best = clearance, best_seam = seam;
    }
    ranked.emplace_back(best, gp_Ax2(gp_Pnt(0, 0, 0), dir(pole), dir(best_seam)));
  }
  std::stable_sort(ranked.begin(), ranked.end(), [](const auto& x, const auto& y) { return x.first > y.first; });
  std::vector<gp_Ax2> out;
  for (std::size_t i = 0; i < ranked.size() && out.size() < count; ++i) out.push_back(ranked[i].second);
  return out;
}

// The fallback frame: poles farthest from the stumps' axes, the seam farthest from their directions (exit caps may
// cross the seam: the face is valid, but does not survive a STEP round trip).
gp_Ax2 spread_sphere_frame(const std::vector<CoreStump>& stumps) {
  constexpr int kCandidates = 97;
  Vec3 best_pole(0.0, 0.0, 1.0);
  double best = -1.0;
  for (int k = 0; k < kCandidates; ++k) {  // Fibonacci points on the upper half sphere
    const double z = 1.0 - (k + 0.5) / kCandidates, r = std::sqrt(1.0 - z * z), a = k * 2.399963229728653;
    const Vec3 pole(r * std::cos(a), r * std::sin(a), z);
    double nearest = 1.0;  // smallest |sin| of the angle to a stump's axis
    for (const CoreStump& s : stumps) {
      const double c = glm::dot(pole, glm::normalize(s.direction));
      nearest = std::min(nearest, std::sqrt(std::max(0.0, 1.0 - c * c)));
    }
    if (nearest > best) best = nearest, best_pole = pole;
  }
  // The seam's half plane: the perpendicular farthest from the stumps' axes projected on the equator.
  const Vec3 e0 = any_perpendicular(best_pole), e1 = glm::cross(best_pole, e0);
  Vec3 best_seam = e0;
  double best_seam_gap = -1.0;
  for (int k = 0; k < 72; ++k) {
    const double a = k * (2.0 * M_PI / 72);
    const Vec3 seam = std::cos(a) * e0 + std::sin(a) * e1;
    double gap = 2.0;
    for (const CoreStump& s : stumps) {
      const Vec3 d = glm::normalize(s.direction);
      const Vec3 flat = d - glm::dot(d, best_pole) * best_pole;
      if (glm::length(flat) < 1e-9) continue;
      gap = std::min(gap, glm::length(glm::normalize(flat) - seam));
    }
    if (gap > best_seam_gap) best_seam_gap = gap, best_seam = seam;
  }
  return gp_Ax2(gp_Pnt(0, 0, 0), dir(best_pole), dir(best_seam));
}

// Which stump's collar disk `face` is (or -1): a plane through the collar's center, orthogonal to the stump, bounded
// by a single circle of the collar's radius around that center.
int collar_disk_index(const TopoDS_Face& face, const std::vector<CoreStump>& stumps, const std::vector<double>& collars) {
  const Handle(Geom_Circle) circle = disk_circle(face);
  if (circle.IsNull()) return -1;
  Handle(Geom_Plane) plane = Handle(Geom_Plane)::DownCast(BRep_Tool::Surface(face));
  const gp_Pnt c = circle->Location();
  for (std::size_t i = 0; i < stumps.size(); ++i) {
    const Vec3 d = glm::normalize(stumps[i].direction);
    const gp_Pnt expected = pnt(collars[i] * d);
    if (c.Distance(expected) < 1e-9 && std::abs(circle->Radius() - stumps[i].radius_at(collars[i])) < 1e-9 &&
        std::abs(std::abs(plane->Axis().Direction().Dot(dir(d))) - 1.0) < 1e-12)
      return static_cast<int>(i);
  }
  return -1;
}

std::shared_ptr<const HubCore> fuse_core(const std::vector<CoreStump>& stumps, const std::vector<double>& collars,
                                         const gp_Ax2& ball_frame) {
  auto out = std::make_shared<HubCore>();
  out->kind = CoreKind::Transversal;
  out->fused = true;
  out->collar_position = collars;
  TopTools_ListOfShape args, tools;
  args.Append(BRepPrimAPI_MakeSphere(ball_frame, 1.0).Shape());
  for (std::size_t i = 0; i < stumps.size(); ++i) {
    const CoreStump& s = stumps[i];
    const Vec3 d = glm::normalize(s.direction), e = any_perpendicular(d);
    // Start where the cone's circle is well inside the ball: halfway between the plane where the cone touches its
    // end ball and its exit. (Not at the end ball's plane: for cylinders that is the center, where opposite
    // stumps would meet face to face, nearly coaxial, and the Fuse then lost a collar disk.)
    const double x0 = 0.5 * (s.end_radius * s.sin_phi + s.exit);
    const double r0 = s.radius_at(x0), r1 = s.radius_at(collars[i]);
    const gp_Ax2 ax(pnt(x0 * d), dir(d), dir(e));
    if (std::abs(r0 - r1) < 1e-12)
      tools.Append(BRepPrimAPI_MakeCylinder(ax, r0, collars[i] - x0).Shape());
    else
      tools.Append(BRepPrimAPI_MakeCone(ax, r0, r1, collars[i] - x0).Shape());
  }
  BRepAlgoAPI_Fuse fuse;
  fuse.SetArguments(args);
  fuse.SetTools(tools);
  fuse.SetNonDestructive(Standard_False);
  fuse.Build();
  if (!fuse.IsDone() || fuse.HasErrors()) unsupported("the Fuse of a hub's ball and stumps failed");
  // Find each collar disk in the result by its geometry (a planar face bounded by one circle: the collar's), not
  // by the Fuse's history, which has reported disks it left untouched as deleted (OCC 7.6, crowded octet hubs).
  const BRep_Builder b;
  b.MakeCompound(out->faces);
  std::vector<TopoDS_Face> found(stumps.size());
  for (TopExp_Explorer x(fuse.Shape(), TopAbs_FACE); x.More(); x.Next()) {
    const TopoDS_Face face = TopoDS::Face(x.Current());
    const int collar = collar_disk_index(face, stumps, collars);
    if (collar >= 0) {
      if (!found[collar].IsNull()) unsupported("a stump's collar was split by the Fuse of its hub");
      found[collar] = face;
      continue;
    }
    b.Add(out->faces, face);
    ++out->face_count;
  }
  for (std::size_t i = 0; i < found.size(); ++i) {
    const TopoDS_Face& t = found[i];
    if (t.IsNull()) {
      std::ostringstream os;
      os << "the collar of stump " << i << " (of " << stumps.size() << ") was touched by the Fuse of its hub (stumps:";
      for (std::size_t k = 0; k < stumps.size(); ++k)  // the hub, for a bug report
        os << " [" << stumps[k].direction.x << " " << stumps[k].direction.y << " " << stumps[k].direction.z
           << ", sin_phi " << stumps[k].sin_phi << ", end " << stumps[k].end_radius << ", collar " << collars[k] << "]";
      os << ")";
      unsupported(os.str());
    }
    TopExp_Explorer x(t, TopAbs_EDGE);
    out->collars.push_back(TopoDS::Edge(x.Current()));
  }
  // The Fuse kept the parents' pcurves on split edges (see pcurve_pieces.hpp), once per distinct core.
  give_edges_their_own_pcurves(out->faces);
  // Tangent exit caps (an octet at beam/node 0.5) leave the sphere's loop touching itself in cusps, valid or not
  // by luck once written as text: see cusp_tolerance.hpp.
  widen_cusp_vertices(out->faces);
  return out;
}

// Whether a sphere face of the core holds a chain of edges across the seam (portable_sphere_faces.hpp): valid in
// OpenCASCADE, invalid once a STEP reader rebuilds the face from its loops (docs/brep.md, section 5).
bool has_straddling_arc(const HubCore& core) {
  for (TopExp_Explorer f(core.faces, TopAbs_FACE); f.More(); f.Next())
    if (has_chain_across_seam(TopoDS::Face(f.Current()))) return true;
  return false;
}

}  // namespace

// The Fuse depends on the ball's frame (OpenCASCADE's sphere has a seam and poles). The spread frame first (the
// one every trim was measured with); where it leaves a hole across the seam or its Fuse fails (a collar touched),
// up to kPortableFrameTries portable frames, the first whose Fuse succeeds without such a hole kept; else the
// first core built (valid, but a STEP reader will find that face invalid); else the spread frame's error.
constexpr std::size_t kPortableFrameTries = 4;
std::shared_ptr<const HubCore> build_transversal_core(const std::vector<CoreStump>& stumps,
                                                      const std::vector<double>& collars) {
  std::shared_ptr<const HubCore> spread;
  std::string spread_error;
  try {
    spread = fuse_core(stumps, collars, spread_sphere_frame(stumps));
    if (!has_straddling_arc(*spread)) return spread;
  } catch (const InvalidInput& e) {
    spread_error = e.what();
  }
  for (const gp_Ax2& frame : portable_sphere_frames(stumps, kPortableFrameTries)) {
    try {
      std::shared_ptr<const HubCore> portable = fuse_core(stumps, collars, frame);
      if (!has_straddling_arc(*portable)) return portable;
      if (!spread) spread = portable;  // valid in OpenCASCADE, though not portable: better than no part
    } catch (const InvalidInput&) {  // this frame's Fuse failed: the next one
    }
  }
  if (!spread) throw InvalidInput(spread_error);
  return spread;
}


Handle(Geom_Circle) disk_circle(const TopoDS_Face& face) {
  if (Handle(Geom_Plane)::DownCast(BRep_Tool::Surface(face)).IsNull()) return nullptr;
  TopoDS_Edge only;
  int edges = 0;
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next()) {
    if (BRep_Tool::Degenerated(TopoDS::Edge(x.Current()))) continue;
    only = TopoDS::Edge(x.Current());
    ++edges;
  }
  if (edges != 1) return nullptr;
  Standard_Real first, last;
  return Handle(Geom_Circle)::DownCast(BRep_Tool::Curve(only, first, last));
}

TopoDS_Solid closed_core(const HubCore& core) {
  BRep_Builder b;
  TopoDS_Shell shell;
  b.MakeShell(shell);
  for (TopExp_Explorer x(core.faces, TopAbs_FACE); x.More(); x.Next()) b.Add(shell, x.Current());
  for (const TopoDS_Edge& collar : core.collars) {
    Standard_Real first, last;
    Handle(Geom_Circle) c = Handle(Geom_Circle)::DownCast(BRep_Tool::Curve(collar, first, last));
    const gp_Ax2& ax = c->Position();
    TopoDS_Face disk;
    b.MakeFace(disk, new Geom_Plane(gp_Ax3(ax.Location(), ax.Direction(), ax.XDirection())), 1e-7);
    b.UpdateEdge(collar, new Geom2d_Circle(gp_Ax2d(gp_Pnt2d(0, 0), gp_Dir2d(1, 0)), c->Radius()), disk, 1e-7);
    b.Range(collar, first, last);
    TopoDS_Wire w;
    b.MakeWire(w);
    b.Add(w, collar.Oriented(TopAbs_FORWARD));
    b.Add(disk, w);
    b.Add(shell, disk);
  }
  shell.Closed(true);
  TopoDS_Solid solid;
  b.MakeSolid(solid);
  b.Add(solid, shell);
  return solid;
}

namespace {

// The hub up to the core's collars as a HubShape of hub_properties (unit ball at the origin, each cut at its
// collar). hub_properties wants each stump's far node: any beam with the stump's cone whose far ball stays beyond
// the collar gives the same stump, and the one chosen lies between those bounds.
HubShape core_hub_shape(const std::vector<CoreStump>& stumps, const std::vector<double>& collars) {
  HubShape shape;
  shape.radius = 1.0;
  for (std::size_t i = 0; i < stumps.size(); ++i) {
    const CoreStump& c = stumps[i];
    const double s = c.sin_phi, r = c.end_radius, x = collars[i];
    const double shortest = (x - r * s) / ((1.0 - s) * (1.0 + s));  // the far ball's tangent circle at the collar
    const double longest = s > 0.0 ? r / s : 4.0 * std::max(shortest, x);  // the far ball shrinks to the apex
    HubStump h;
    h.axis = c.direction;
    h.radius = r;
    h.length = 0.5 * (std::max(shortest, x) + longest);
    h.other_radius = r - h.length * s;
    h.cut = x;
    shape.stumps.push_back(h);
  }
  return shape;
}

// The volume the core encloses with its collar disks (OpenCASCADE's integral over the closed solid; an open shell's
// faces alone do not give it), and the exact volume of its hub (hub_properties). Tight collars (core_collars) may
// lie inside the ball, where another stump can reach through a collar disk's interior (the closed core ends at the
// disk, hub_properties would keep what that stump holds): both sides are then taken to place_collars' collars, the
// built one by adding each stump's frustum between the two collars (beyond its tight collar no stump meets
// another, so the frustums add exactly).
std::pair<double, double> core_volumes(const HubCore& core, const std::vector<CoreStump>& stumps) {
  GProp_GProps closed;
  BRepGProp::VolumeProperties(closed_core(core), closed, 1e-8, Standard_True);
  double built = closed.Mass();
  std::vector<double> cuts = core.collar_position;
  std::vector<double> apart = cuts;
  try {
    apart = place_collars(stumps, core.kind, kMaxCollarPosition);
  } catch (const InvalidInput&) {  // no collars apart: the tight ones are measured as they are
  }
  for (std::size_t i = 0; i < stumps.size(); ++i) {
    const double x0 = cuts[i], x1 = apart[i];
    if (!(x1 > x0)) continue;
    const double r0 = stumps[i].radius_at(x0), r1 = stumps[i].radius_at(x1);
    built += M_PI * (x1 - x0) * (r0 * r0 + r0 * r1 + r1 * r1) / 3.0;
    cuts[i] = x1;
  }
  return {built, hub_properties(core_hub_shape(stumps, cuts)).moments.volume};
}

constexpr double kCoreVolumeTolerance = 1e-6;  // relative; OpenCASCADE integrates the faces to 1e-9

bool core_volume_matches(const HubCore& core, const std::vector<CoreStump>& stumps) {
  const auto [built, exact] = core_volumes(core, stumps);
  return std::abs(built - exact) <= kCoreVolumeTolerance * exact;
}

void check_core_volume(const HubCore& core, const std::vector<CoreStump>& stumps) {
  const auto [built, exact] = core_volumes(core, stumps);
  if (std::abs(built - exact) <= kCoreVolumeTolerance * exact) return;
  std::ostringstream os;
  os << "the core built for a crowded hub of " << stumps.size() << " beams (" << (core.fused ? "Fuse" : "envelope")
     << ") encloses volume " << built << " where the hub's exact volume is " << exact;
  fail_input("hub", os.str());
}

// The core, once check_core_volume passed it.
std::shared_ptr<const HubCore> checked(std::shared_ptr<const HubCore> core, const std::vector<CoreStump>& stumps) {
  check_core_volume(*core, stumps);
  return core;
}

}  // namespace

std::shared_ptr<const HubCore> build_hub_core(const std::vector<CoreStump>& stumps, CoreKind kind,
                                              const std::vector<double>& collars, CollarFit fit) {
  if (stumps.empty()) unsupported("a hub core needs stumps");
  if (kind == CoreKind::Hull) return checked(build_envelope_core(stumps, kind, collars, fit), stumps);
  // Transversal stumps of one end radius: the same exact construction, no Boolean; else (or where a stump is
  // swallowed up to its collar, or the seam finds no room) the Fuse.
  // Tangent exit caps (beams exactly as far apart as their caps are wide) give cusps the arrangement builds but
  // OpenCASCADE refuses as self-intersecting wires: such a core, or one off its exact volume, goes to the Fuse.
  if (share_end_radius(stumps)) {
    try {
      std::shared_ptr<const HubCore> core = build_envelope_core(stumps, kind, collars, fit);
      if (BRepCheck_Analyzer(core->faces).IsValid() && core_volume_matches(*core, stumps)) return core;
    } catch (const InvalidInput&) {
    }
  }
  // The Fuse with the collars asked for (the beams may not fit the others), else with collars whose angular
  // cones stay apart (its collar disks then surely come out untouched); the core reports the ones it used in
  // collar_position.
  // Last, those collars pushed a little farther out: where the caps are exactly tangent (an octet at beam/node 0.5)
  // and the end radii differ, OpenCASCADE's Fuse has split a collar disk 0.02 beyond the ball that it leaves
  // whole 0.06 farther out (the long sweep's octet, node 0.45, twisted taper). The geometry is the same exact union
  // wherever the collars are; whether they still fit on their beams is the builder's check.
  try {
    return checked(build_transversal_core(stumps, collars), stumps);
  } catch (const InvalidInput&) {
  }
  const std::vector<double> apart = place_collars(stumps, kind, kMaxCollarPosition);
  for (double push : {1.0, 1.06, 1.12}) {
    std::vector<double> farther = apart;
    for (double& c : farther) c *= push;
    if (farther == collars) continue;  // tried above
    try {
      return checked(build_transversal_core(stumps, farther), stumps);
    } catch (const InvalidInput&) {
      if (push == 1.12) throw;
    }
  }
  unsupported("the Fuse of a crowded hub failed with every set of collars tried");
}

}  // namespace steady
