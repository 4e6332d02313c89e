#include "brep/hub_core.hpp"

#include <AdvApprox_ApproxAFunction.hxx>
#include <AdvApprox_EvaluatorFunction.hxx>
#include <BRepAlgoAPI_Fuse.hxx>
#include <BRepPrimAPI_MakeCone.hxx>
#include <BRepPrimAPI_MakeCylinder.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <ElCLib.hxx>
#include <ElSLib.hxx>
#include <Geom2d_BSplineCurve.hxx>
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

#include "lattice/circle_frames.hpp"
#include "steady/lattice/convex_distance.hpp"
#include "steady/core/errors.hpp"
#include "steady/brep/sphere_layout.hpp"

namespace steady {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// Exact edges of a canonical core (unit ball): OpenCASCADE's confusion tolerance; copies scale it.
constexpr double kCoreTolerance = 1e-7;
// (u, v) accuracy of the approximated pcurves of conic and circle arcs (radians or unit-ball lengths).
constexpr double kCorePcurveTolerance = 1e-9;
// Vertices of the arrangement closer than this (unit-ball lengths) are the same vertex.
constexpr double kVertexMerge = 1e-8;
// Two envelope values closer than this are tied (ties go to the cone with the lower index, then to cones over
// the sphere, so the faces on both sides of an edge agree).
constexpr double kTie = 1e-12;
// A collar must clear the other stumps, and the envelope must stay below it, by this much (unit-ball lengths):
// thinner bands of cone between the envelope and the collar make sliver faces that OpenCASCADE's Booleans, when
// they trim the lattice, fail to split (measured: a 4e-4 band left 52 faces unsplit in a sphere body).
constexpr double kCollarClearance = 0.02;
// Each collar's angular cone gets this fraction of half the smallest angle to a neighbour's axis.
constexpr double kCollarAngleShare = 0.9;
// The sphere face's seam and poles must lie inside the caps by this much (cosine units), and the seam is sampled
// at half this step, so by the Lipschitz bound of the margin function it never meets the sphere face.
constexpr double kSeamMargin = 0.01;
constexpr int kSeamSamples = 360;

gp_Pnt pnt(const Vec3& v) { return gp_Pnt(v.x, v.y, v.z); }
gp_Dir dir(const Vec3& v) { return gp_Dir(v.x, v.y, v.z); }
Vec3 vec(const gp_Pnt& p) { return {p.X(), p.Y(), p.Z()}; }
Vec3 vec(const gp_Vec& p) { return {p.X(), p.Y(), p.Z()}; }


[[noreturn]] void unsupported(const std::string& why) { fail_input("hub", why); }

// A hull-model cone tangent to the unit sphere: points s d + (c - v s) r(u) + v c d, r(u) = cos u e + sin u f.
struct Cone {
  Vec3 d, e, f;
  double s = 0.0, c = 1.0;
  Vec3 point(double u, double v) const {
    return s * d + (c - v * s) * (std::cos(u) * e + std::sin(u) * f) + v * c * d;
  }
  double w(const Vec3& x) const { return (glm::dot(d, x) - s) / c; }
  double u_of(const Vec3& x) const { return std::atan2(glm::dot(x, f), glm::dot(x, e)); }
  gp_Ax3 frame() const { return gp_Ax3(pnt(s * d), dir(d), dir(e)); }
  Handle(Geom_Surface) surface() const {
    if (std::abs(s) < 1e-14) return new Geom_CylindricalSurface(frame(), c);
    return new Geom_ConicalSurface(frame(), -std::asin(s), c);
  }
};

Cone make_cone(const CoreStump& st) {
  Cone k;
  k.d = glm::normalize(st.direction);
  k.e = any_perpendicular(k.d);
  k.f = glm::cross(k.d, k.e);
  k.s = st.sin_phi;
  k.c = std::sqrt((1.0 - k.s) * (1.0 + k.s));
  return k;
}

// On cone i along generator u, stump j dominates below v = t (w_i >= w_j iff v (c_j - B) >= A).
struct Bound {
  enum Kind { Lower, Upper, Always, Never } kind = Always;
  double t = 0.0;
};

Bound bound_from(const Cone& ki, const Cone& kj, double u) {
  const Vec3 r = std::cos(u) * ki.e + std::sin(u) * ki.f;
  const double dd = glm::dot(kj.d, ki.d), dr = glm::dot(kj.d, r);
  const double A = ki.s * dd + ki.c * dr - kj.s;
  const double B = ki.c * dd - ki.s * dr;
  const double D = kj.c - B;
  if (D > 1e-14) return {Bound::Lower, A / D};
  if (D < -1e-14) return {Bound::Upper, A / D};
  return {A <= 0.0 ? Bound::Always : Bound::Never, 0.0};
}

struct Active {
  int index = -1;  // -1: the sphere (v >= 0), else the cone that dominates below the envelope
  double v = 0.0;
};

Active envelope_at(const std::vector<Cone>& cones, int i, double u) {
  Active a;
  for (int j = 0; j < static_cast<int>(cones.size()); ++j) {
    if (j == i) continue;
    const Bound b = bound_from(cones[i], cones[j], u);
    if (b.kind != Bound::Lower) continue;
    if (b.t > a.v + kTie || (a.index < 0 && b.t > a.v - kTie)) a = {j, std::max(a.v, b.t)};
  }
  return a;
}

// Lowest upper bound along generator u (infinity when none).
double ceiling_at(const std::vector<Cone>& cones, int i, double u) {
  double top = std::numeric_limits<double>::infinity();
  for (int j = 0; j < static_cast<int>(cones.size()); ++j) {
    if (j == i) continue;
    const Bound b = bound_from(cones[i], cones[j], u);
    if (b.kind == Bound::Upper) top = std::min(top, b.t);
    if (b.kind == Bound::Never) top = -std::numeric_limits<double>::infinity();
  }
  return top;
}

// Solutions u of a0 + a1 cos u + a2 sin u = 0.
void trig_roots(double a0, double a1, double a2, std::vector<double>& out) {
  const double r = std::hypot(a1, a2);
  if (!(r > 1e-15) || std::abs(a0) > r) return;
  const double phi = std::atan2(a2, a1), beta = std::acos(std::clamp(-a0 / r, -1.0, 1.0));
  out.push_back(phi + beta);
  out.push_back(phi - beta);
}

struct Piece {
  int active = -1;
  double u0 = 0.0, u1 = 0.0;  // in the face's window
  int v0 = -1, v1 = -1;       // vertex ids at u0 and u1
};

struct Envelope {
  double window = 0.0;
  std::vector<Piece> pieces;
};

// Where the active stump along the envelope of cone i can change: roots of the conditions of the candidates.
std::vector<double> breakpoint_candidates(const std::vector<Cone>& cones, int i) {
  const Cone& ki = cones[i];
  std::vector<double> us;
  const int n = static_cast<int>(cones.size());
  for (int j = 0; j < n; ++j) {
    if (j == i) continue;
    const Cone& kj = cones[j];
    const double dd = glm::dot(kj.d, ki.d), de = glm::dot(kj.d, ki.e), df = glm::dot(kj.d, ki.f);
    // A_j(u) = 0: the envelope of j crosses the tangent circle.
    trig_roots(ki.s * dd - kj.s, ki.c * de, ki.c * df, us);
    // D_j(u) = 0: j switches between lower and upper bound.
    trig_roots(kj.c - ki.c * dd, ki.s * de, ki.s * df, us);
    for (int k = j + 1; k < n; ++k) {
      if (k == i) continue;
      // Points of cone i with w_i = w_j = w_k: the line of two planes meets the cone in up to two points.
      const Cone& kk = cones[k];
      const Vec3 n1 = ki.d / ki.c - kj.d / kj.c, n2 = ki.d / ki.c - kk.d / kk.c;
      const double b1 = ki.s / ki.c - kj.s / kj.c, b2 = ki.s / ki.c - kk.s / kk.c;
      const Vec3 q = glm::cross(n1, n2);
      const double qq = glm::dot(q, q);
      if (!(qq > 1e-24)) continue;
      const Vec3 p0 = (b1 * glm::cross(n2, q) + b2 * glm::cross(q, n1)) / qq;
      const double g = glm::dot(ki.d, q) / ki.c, w0 = ki.w(p0);
      const double A = qq - g * g, B = 2.0 * (glm::dot(p0, q) - w0 * g), C = glm::dot(p0, p0) - 1.0 - w0 * w0;
      std::vector<double> taus;
      if (std::abs(A) > 1e-14) {
        const double disc = B * B - 4 * A * C;
        if (disc < 0) continue;
        const double sq = std::sqrt(disc);
        taus = {(-B - sq) / (2 * A), (-B + sq) / (2 * A)};
      } else if (std::abs(B) > 1e-14) {
        taus = {-C / B};
      }
      for (double tau : taus) {
        const Vec3 x = p0 + tau * q;
        const double v = ki.w(x);
        if (v < -1e-9 || ki.c - v * ki.s <= 0.0) continue;  // behind the tangent circle, or on the other nappe
        us.push_back(ki.u_of(x));
      }
    }
  }
  for (double& u : us) u = wrap_into(u, 0.0);
  std::sort(us.begin(), us.end());
  us.erase(std::unique(us.begin(), us.end(), [](double a, double b) { return std::abs(a - b) < 1e-13; }), us.end());
  return us;
}

// Vertices shared by all faces of the core, merged by position.
struct VertexPool {
  std::vector<Vec3> points;
  int find_or_add(const Vec3& p) {
    for (std::size_t k = 0; k < points.size(); ++k)
      if (glm::length(points[k] - p) < kVertexMerge) return static_cast<int>(k);
    points.push_back(p);
    return static_cast<int>(points.size()) - 1;
  }
};

Envelope envelope_of(const std::vector<Cone>& cones, int i, double v_collar, VertexPool& pool) {
  const Cone& ki = cones[i];
  std::vector<double> us = breakpoint_candidates(cones, i);
  // Validity along the whole circle: the envelope stays below the collar, the ceilings above it.
  std::vector<double> probes = us;
  for (int k = 0; k < 256; ++k) probes.push_back(kTwoPi * k / 256);
  for (double u : probes) {
    const Active a = envelope_at(cones, i, u);
    if (!(a.v < v_collar - kCollarClearance) || !(ceiling_at(cones, i, u) > v_collar + kCollarClearance))
      unsupported("a stump is swallowed by its neighbours up to its collar");
  }
  Envelope env;
  if (us.empty()) us = {0.0};
  // Active stump on each interval between candidates; merge equal neighbours.
  struct Run {
    int active;
    double u0, u1;
  };
  std::vector<Run> runs;
  for (std::size_t k = 0; k < us.size(); ++k) {
    const double a = us[k], b = k + 1 < us.size() ? us[k + 1] : us[0] + kTwoPi;
    if (b - a < 1e-13) continue;
    const int act = envelope_at(cones, i, 0.5 * (a + b)).index;
    if (!runs.empty() && runs.back().active == act)
      runs.back().u1 = b;
    else
      runs.push_back({act, a, b});
  }
  if (runs.size() > 1 && runs.front().active == runs.back().active) {
    runs.front().u0 = runs.back().u0 - kTwoPi;
    runs.pop_back();
  }
  if (runs.size() == 1) {
    // One stump (or the sphere) all around: a closed edge, its vertex put at u = u0 by the face that makes it.
    env.window = runs[0].u0;
    env.pieces.push_back({runs[0].active, runs[0].u0, runs[0].u0 + kTwoPi, -1, -1});
    return env;
  }
  env.window = runs[0].u0;
  for (const Run& r : runs) {
    Piece p{r.active, r.u0, r.u1, -1, -1};
    p.v0 = pool.find_or_add(ki.point(r.u0, envelope_at(cones, i, r.u0).v));
    env.pieces.push_back(p);
  }
  for (std::size_t k = 0; k < env.pieces.size(); ++k) env.pieces[k].v1 = env.pieces[(k + 1) % env.pieces.size()].v0;
  // Vertex positions at breakpoints are the envelope's value there, which both neighbouring actives share.
  return env;
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
    inter.Perform(plane, gp_Cylinder(ki.frame(), ki.c), 1e-12, 1e-12);
  else
    inter.Perform(plane, gp_Cone(ki.frame(), -std::asin(ki.s), ki.c), 1e-12, 1e-12);
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

// Frame for the sphere face: poles and seam well inside the union of caps (so the face meets neither).
bool choose_sphere_frame(const std::vector<Cone>& cones, Vec3& z_out, Vec3& x_out) {
  auto inside_margin = [&](const Vec3& p) {
    double m = -1e300;
    for (const Cone& k : cones) m = std::max(m, glm::dot(k.d, p) - k.s);
    return m;
  };
  std::vector<Vec3> poles;
  const double golden = M_PI * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < 96; ++i) {
    const double zc = 1.0 - (2.0 * i + 1.0) / 96, r = std::sqrt(1.0 - zc * zc);
    poles.emplace_back(r * std::cos(golden * i), r * std::sin(golden * i), zc);
  }
  for (const Cone& k : cones) poles.push_back(k.d);
  double best = -1e300;
  for (const Vec3& z : poles) {
    const double pole_margin = std::min(inside_margin(z), inside_margin(-z));
    if (pole_margin <= best) continue;
    const Vec3 x0 = any_perpendicular(z), y0 = glm::cross(z, x0);
    for (int k = 0; k < 36; ++k) {
      const double a = kTwoPi * k / 36;
      const Vec3 x = std::cos(a) * x0 + std::sin(a) * y0;
      double m = pole_margin;
      for (int s = 1; s < kSeamSamples && m > best; ++s) {
        const double lat = -M_PI / 2 + M_PI * s / kSeamSamples;
        m = std::min(m, inside_margin(std::cos(lat) * x + std::sin(lat) * z));
      }
      if (m > best) {
        best = m;
        z_out = z;
        x_out = x;
      }
    }
  }
  return best > kSeamMargin;
}

std::shared_ptr<const HubCore> build_hull_core(const std::vector<CoreStump>& stumps, const std::vector<double>& collars) {
  const int n = static_cast<int>(stumps.size());
  std::vector<Cone> cones;
  for (const CoreStump& s : stumps) cones.push_back(make_cone(s));
  std::vector<double> v_collar(n);
  for (int i = 0; i < n; ++i) v_collar[i] = (collars[i] - cones[i].s) / cones[i].c;
  VertexPool pool;
  std::vector<Envelope> env(n);
  for (int i = 0; i < n; ++i) env[i] = envelope_of(cones, i, v_collar[i], pool);

  // Closed pieces (one active all around) get their vertex from the lower face; the partner face starts there.
  for (int i = 0; i < n; ++i) {
    Piece& p = env[i].pieces[0];
    if (env[i].pieces.size() != 1) continue;
    if (p.v0 >= 0) continue;
    const double u = p.u0;
    p.v0 = p.v1 = pool.find_or_add(cones[i].point(u, envelope_at(cones, i, u).v));
    if (p.active >= 0) {
      const int j = p.active;
      if (env[j].pieces.size() != 1 || env[j].pieces[0].active != i) unsupported("two stumps disagree on their edge");
      const Vec3 x = pool.points[p.v0];
      Piece& q = env[j].pieces[0];
      q.u0 = wrap_into(cones[j].u_of(x), 0.0);
      q.u1 = q.u0 + kTwoPi;
      env[j].window = q.u0;
      q.v0 = q.v1 = p.v0;
    }
  }

  // Edges: each cone-cone piece appears on both cones (in opposite directions), each sphere piece once.
  std::vector<CoreEdge> edges;
  std::map<std::tuple<int, int, int, int>, std::size_t> edge_index;
  std::vector<std::vector<std::size_t>> face_edges(n);
  for (int i = 0; i < n; ++i) {
    for (const Piece& p : env[i].pieces) {
      const Vec3 mid = cones[i].point(0.5 * (p.u0 + p.u1), envelope_at(cones, i, 0.5 * (p.u0 + p.u1)).v);
      if (p.active < 0) {
        CoreEdge e;
        e.face_a = i;
        e.curve = new Geom_Circle(gp_Ax2(pnt(cones[i].s * cones[i].d), dir(cones[i].d), dir(cones[i].e)), cones[i].c);
        e.t0 = p.u0;
        e.t1 = p.u1;
        e.forward_on_a = true;
        e.vertex_t0 = p.v0;
        e.vertex_t1 = p.v1;
        e.a_u0 = p.u0;
        e.a_u1 = p.u1;
        face_edges[i].push_back(edges.size());
        edges.push_back(e);
        continue;
      }
      const int j = p.active;
      // Key from the lower face's point of view: (low, high, its start vertex, its end vertex).
      const auto key = i < j ? std::make_tuple(i, j, p.v0, p.v1) : std::make_tuple(j, i, p.v1, p.v0);
      auto found = edge_index.find(key);
      if (found != edge_index.end()) {
        CoreEdge& e = edges[found->second];
        e.b_u0 = p.u0;
        e.b_u1 = p.u1;
        face_edges[i].push_back(found->second);
        continue;
      }
      CoreEdge e;
      e.face_a = i;
      e.face_b = j;
      e.curve = conic_between(cones[i], cones[j], mid);
      double ta = curve_parameter(e.curve, pool.points[p.v0]), tb = curve_parameter(e.curve, pool.points[p.v1]);
      const double tm = curve_parameter(e.curve, mid);
      if (e.curve->IsPeriodic()) {
        // The arc from the start through the middle to the end, within one period.
        const double per = e.curve->Period();
        const double mw = ta + std::fmod(std::fmod(tm - ta, per) + per, per);
        double bw = ta + std::fmod(std::fmod(tb - ta, per) + per, per);
        if (p.v0 == p.v1) bw = ta + per;
        if (mw <= bw) {
          e.t0 = ta;
          e.t1 = bw;
          e.forward_on_a = true;
        } else {
          e.t0 = bw - per;
          e.t1 = ta;
          e.forward_on_a = false;
        }
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
      edge_index.emplace(key, edges.size());
      face_edges[i].push_back(edges.size());
      edges.push_back(e);
    }
  }
  for (const auto& [key, index] : edge_index)
    if (edges[index].b_u1 == 0.0 && edges[index].b_u0 == 0.0)
      unsupported("the stumps' faces disagree about one of their edges");

  // Topology.
  auto out = std::make_shared<HubCore>();
  out->kind = CoreKind::Hull;
  const BRep_Builder b;
  b.MakeCompound(out->faces);
  std::vector<TopoDS_Vertex> vertices;
  for (const Vec3& p : pool.points) {
    TopoDS_Vertex v;
    b.MakeVertex(v, pnt(p), kCoreTolerance);
    vertices.push_back(v);
  }
  for (CoreEdge& e : edges) {
    b.MakeEdge(e.edge, e.curve, kCoreTolerance);
    b.Add(e.edge, vertices[e.vertex_t0].Oriented(TopAbs_FORWARD));
    b.Add(e.edge, vertices[e.vertex_t1].Oriented(TopAbs_REVERSED));
  }
  std::vector<Handle(Geom_Surface)> surfaces;
  std::vector<TopoDS_Face> faces(n);
  for (int i = 0; i < n; ++i) {
    surfaces.push_back(cones[i].surface());
    b.MakeFace(faces[i], surfaces[i], kCoreTolerance);
  }
  double max_error = 0.0;
  // pcurves on the cones.
  for (CoreEdge& e : edges) {
    if (e.on_sphere()) {
      // The tangent circle is the line v = 0 of its cone, with the circle's parameter as u.
      b.UpdateEdge(e.edge, new Geom2d_Line(gp_Pnt2d(0, 0), gp_Dir2d(1, 0)), faces[e.face_a], kCoreTolerance);
      continue;
    }
    for (int side = 0; side < 2; ++side) {
      const int face = side == 0 ? e.face_a : e.face_b;
      // The face runs the arc from its u0 to its u1; map the curve's ends accordingly.
      const bool forward = side == 0 ? e.forward_on_a : !e.forward_on_a;
      const double u_at_t0 = forward ? (side == 0 ? e.a_u0 : e.b_u0) : (side == 0 ? e.a_u1 : e.b_u1);
      const double u_at_t1 = forward ? (side == 0 ? e.a_u1 : e.b_u1) : (side == 0 ? e.a_u0 : e.b_u0);
      ArcOnSurface f(e.curve, surfaces[face], e.t0, e.t1, u_at_t0, u_at_t1);
      b.UpdateEdge(e.edge, approximate(f, e.t0, e.t1, max_error), faces[face], kCoreTolerance);
    }
  }
  // Cone faces: envelope, seam, collar.
  out->collar_position = collars;
  out->collars.resize(n);
  for (int i = 0; i < n; ++i) {
    const Cone& k = cones[i];
    const double u_star = env[i].pieces[0].u0, vlo = glm::length(pool.points[env[i].pieces[0].v0] - k.point(u_star, 0.0));
    (void)vlo;
    const double v_start = k.w(pool.points[env[i].pieces[0].v0]);
    // Collar circle: parameter u, its vertex at u_star.
    const Vec3 center = k.s * k.d + v_collar[i] * k.c * k.d;
    Handle(Geom_Circle) collar_curve =
        new Geom_Circle(gp_Ax2(pnt(center), dir(k.d), dir(k.e)), k.c - v_collar[i] * k.s);
    TopoDS_Vertex cv;
    b.MakeVertex(cv, collar_curve->Value(u_star), kCoreTolerance);
    TopoDS_Edge collar;
    b.MakeEdge(collar, collar_curve, kCoreTolerance);
    b.Add(collar, cv.Oriented(TopAbs_FORWARD));
    b.Add(collar, cv.Oriented(TopAbs_REVERSED));
    b.UpdateEdge(collar, new Geom2d_Line(gp_Pnt2d(0, v_collar[i]), gp_Dir2d(1, 0)), faces[i], kCoreTolerance);
    b.Range(collar, u_star, u_star + kTwoPi);
    out->collars[i] = collar;
    // Seam: the generator at u_star, parameterized by v.
    Handle(Geom_Line) line = new Geom_Line(pnt(k.point(u_star, 0.0)), dir(k.point(u_star, 1.0) - k.point(u_star, 0.0)));
    TopoDS_Edge seam;
    b.MakeEdge(seam, line, kCoreTolerance);
    b.Add(seam, vertices[env[i].pieces[0].v0].Oriented(TopAbs_FORWARD));
    b.Add(seam, cv.Oriented(TopAbs_REVERSED));
    b.UpdateEdge(seam, new Geom2d_Line(gp_Pnt2d(u_star + kTwoPi, 0), gp_Dir2d(0, 1)),
                 new Geom2d_Line(gp_Pnt2d(u_star, 0), gp_Dir2d(0, 1)), faces[i], kCoreTolerance);
    b.Range(seam, v_start, v_collar[i]);
    TopoDS_Wire wire;
    b.MakeWire(wire);
    for (std::size_t pi = 0; pi < env[i].pieces.size(); ++pi) {
      const CoreEdge& e = edges[face_edges[i][pi]];
      const bool forward = e.face_a == i ? e.forward_on_a : !e.forward_on_a;
      b.Add(wire, e.edge.Oriented(forward ? TopAbs_FORWARD : TopAbs_REVERSED));
    }
    b.Add(wire, seam.Oriented(TopAbs_FORWARD));
    b.Add(wire, collar.Oriented(TopAbs_REVERSED));
    b.Add(wire, seam.Oriented(TopAbs_REVERSED));
    wire.Closed(true);
    b.Add(faces[i], wire);
  }
  // Ranges last: they apply to every representation of the edge.
  for (CoreEdge& e : edges) b.Range(e.edge, e.t0, e.t1);

  // The sphere: the region outside all near caps, bounded by the sphere arcs.
  std::vector<std::size_t> sphere_arcs;
  for (std::size_t k = 0; k < edges.size(); ++k)
    if (edges[k].on_sphere()) sphere_arcs.push_back(k);
  std::vector<TopoDS_Face> sphere_faces;
  if (!sphere_arcs.empty()) {
    Vec3 z, x;
    if (!choose_sphere_frame(cones, z, x))
      unsupported("the part of the ball between the stumps leaves no room for the sphere's seam");
    SphereLayout layout;
    layout.z = z;
    layout.x = x;
    for (const Cone& k : cones) {
      CircleLayout c;
      c.cap = {k.d, k.s};
      c.e1 = k.e;
      c.e2 = k.f;
      c.rho = k.c;
      layout.circles.push_back(c);
    }
    Handle(Geom_SphericalSurface) sphere = new Geom_SphericalSurface(gp_Ax3(gp::Origin(), dir(z), dir(x)), 1.0);
    // Loops: the face runs each arc backwards (its caps on the right); the next arc ends where this one starts.
    std::map<int, std::size_t> by_end;
    for (std::size_t k : sphere_arcs) by_end[edges[k].vertex_t1] = k;
    std::vector<char> used(edges.size(), 0);
    struct Loop {
      std::vector<std::size_t> arcs;
      double area = 0.0;
      gp_Pnt2d sample;
    };
    std::vector<Loop> loops;
    std::map<std::size_t, Handle(Geom2d_Curve)> pcurve;
    for (std::size_t k : sphere_arcs) {
      SphereArc f(layout, edges[k].face_a);
      pcurve[k] = approximate(f, edges[k].t0, edges[k].t1, max_error);
    }
    for (std::size_t start : sphere_arcs) {
      if (used[start]) continue;
      Loop loop;
      std::size_t k = start;
      for (;;) {
        used[k] = 1;
        loop.arcs.push_back(k);
        if (edges[k].vertex_t0 == edges[start].vertex_t1) break;
        auto next = by_end.find(edges[k].vertex_t0);
        if (next == by_end.end() || used[next->second]) unsupported("the part of the ball between the stumps is not closed");
        k = next->second;
      }
      // Shoelace area of the loop in (u, v), run backwards along each arc.
      for (std::size_t a : loop.arcs) {
        const Handle(Geom2d_Curve)& c = pcurve[a];
        for (int s = 0; s < 32; ++s) {
          const double t = edges[a].t1 - (edges[a].t1 - edges[a].t0) * s / 32.0;
          const double t2 = edges[a].t1 - (edges[a].t1 - edges[a].t0) * (s + 1) / 32.0;
          const gp_Pnt2d p = c->Value(t), q = c->Value(t2);
          loop.area += 0.5 * (p.X() * q.Y() - q.X() * p.Y());
        }
      }
      loop.sample = pcurve[loop.arcs[0]]->Value(0.5 * (edges[loop.arcs[0]].t0 + edges[loop.arcs[0]].t1));
      loops.push_back(loop);
    }
    auto make_wire = [&](const Loop& loop) {
      TopoDS_Wire w;
      b.MakeWire(w);
      for (std::size_t a : loop.arcs) b.Add(w, edges[a].edge.Oriented(TopAbs_REVERSED));
      w.Closed(true);
      return w;
    };
    // Outer loops (counterclockwise) become faces; holes (clockwise) join the outer loop that surrounds them.
    std::vector<std::size_t> outers;
    for (std::size_t l = 0; l < loops.size(); ++l)
      if (loops[l].area > 0) outers.push_back(l);
    for (std::size_t o : outers) {
      TopoDS_Face face;
      b.MakeFace(face, sphere, kCoreTolerance);
      for (std::size_t a : loops[o].arcs) b.UpdateEdge(edges[a].edge, pcurve[a], face, kCoreTolerance);
      b.Add(face, make_wire(loops[o]));
      sphere_faces.push_back(face);
    }
    for (std::size_t l = 0; l < loops.size(); ++l) {
      if (loops[l].area > 0) continue;
      if (outers.size() != 1)
        unsupported("the part of the ball between the stumps has holes and several pieces");
      TopoDS_Face& face = sphere_faces[0];
      for (std::size_t a : loops[l].arcs) b.UpdateEdge(edges[a].edge, pcurve[a], face, kCoreTolerance);
      b.Add(face, make_wire(loops[l]));
    }
    if (outers.empty()) unsupported("the part of the ball between the stumps has no outer boundary");
    for (std::size_t k : sphere_arcs) b.Range(edges[k].edge, edges[k].t0, edges[k].t1);
  }
  // Tolerances from the approximations.
  const double tol = std::max(kCoreTolerance, 2.0 * max_error);
  for (CoreEdge& e : edges) b.UpdateEdge(e.edge, tol);
  for (TopoDS_Vertex& v : vertices) b.UpdateVertex(v, tol);
  for (TopoDS_Face& f : faces) b.Add(out->faces, f);
  for (TopoDS_Face& f : sphere_faces) b.Add(out->faces, f);
  out->face_count = static_cast<std::int64_t>(faces.size() + sphere_faces.size());
  return out;
}

// A frame for the ball whose poles and seam keep away from the stumps' axes: OpenCASCADE's Fuse lost an untouched
// collar disk when a stump ran along the sphere's seam plane (OCC 7.6, crowded octet hub, stump along -X).
gp_Ax2 generic_sphere_frame(const std::vector<CoreStump>& stumps) {
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
  Handle(Geom_Plane) plane = Handle(Geom_Plane)::DownCast(BRep_Tool::Surface(face));
  if (plane.IsNull()) return -1;
  TopoDS_Edge only;
  int edges = 0;
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next()) {
    if (BRep_Tool::Degenerated(TopoDS::Edge(x.Current()))) continue;
    only = TopoDS::Edge(x.Current());
    ++edges;
  }
  if (edges != 1) return -1;
  Standard_Real first, last;
  Handle(Geom_Circle) circle = Handle(Geom_Circle)::DownCast(BRep_Tool::Curve(only, first, last));
  if (circle.IsNull()) return -1;
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

std::shared_ptr<const HubCore> build_transversal_core(const std::vector<CoreStump>& stumps,
                                                      const std::vector<double>& collars) {
  auto out = std::make_shared<HubCore>();
  out->kind = CoreKind::Transversal;
  out->collar_position = collars;
  TopTools_ListOfShape args, tools;
  args.Append(BRepPrimAPI_MakeSphere(generic_sphere_frame(stumps), 1.0).Shape());
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
  return out;
}

// How far the ray from the center along unit w stays in stump i: the stump is the beam's cone region between the
// plane where the cone touches its end ball (axial r0 sin_phi) and the collar; the ray meets it in an interval,
// and the far end counts when the interval starts inside the ball (it always does: the cone lies outside the
// ball, so a ray leaving the ball before that plane cannot come back into the cone).
double stump_reach(const CoreStump& s, double collar, const Vec3& w) {
  const double k = glm::dot(glm::normalize(s.direction), w);
  const double c = std::sqrt((1.0 - s.sin_phi) * (1.0 + s.sin_phi));
  const double start = s.end_radius * s.sin_phi;  // axial position of the end ball's tangent plane
  double lo = 0.0, hi = std::numeric_limits<double>::infinity();
  // axial = rho k >= start
  if (k > 0.0) lo = std::max(lo, start / k);
  else if (k < 0.0) hi = std::min(hi, start / k);
  else if (start > 0.0) return 0.0;
  // axial <= collar
  if (k > 0.0) hi = std::min(hi, collar / k);
  // radial <= radius(axial): rho (c sqrt(1 - k^2) + k sin_phi) <= r0
  const double denom = c * std::sqrt(std::max(0.0, 1.0 - k * k)) + k * s.sin_phi;
  if (denom > 0.0) hi = std::min(hi, s.end_radius / denom);
  else if (s.end_radius < 0.0) return 0.0;
  if (!(hi >= lo) || lo > 1.0) return 0.0;
  return hi;
}

}  // namespace

double CoreStump::radius_at(double x) const {
  const double c = std::sqrt((1.0 - sin_phi) * (1.0 + sin_phi));
  return (end_radius - x * sin_phi) / c;
}

std::vector<double> place_collars(const std::vector<CoreStump>& stumps, CoreKind kind, double max_position) {
  const int n = static_cast<int>(stumps.size());
  std::vector<double> collar(n);
  // Angular radius of the collar circle seen from the center decreases with its position: give each stump half of
  // its smallest angle to a neighbour (less a margin), then push collars out until they clear the other stumps.
  for (int i = 0; i < n; ++i) {
    double min_angle = M_PI;
    for (int j = 0; j < n; ++j)
      if (j != i)
        min_angle = std::min(min_angle, std::acos(std::clamp(glm::dot(glm::normalize(stumps[i].direction),
                                                                     glm::normalize(stumps[j].direction)), -1.0, 1.0)));
    const double target = 0.5 * min_angle * kCollarAngleShare;
    if (target <= 0.0) unsupported("two stumps leave the ball in the same direction");
    // A narrowing stump must keep a radius: stay well short of its cone's apex.
    double reach = max_position;
    if (stumps[i].sin_phi > 0.0) reach = std::min(reach, 0.9 * stumps[i].end_radius / stumps[i].sin_phi);
    double lo = std::max(stumps[i].exit, 1e-6), hi = reach;
    auto angle = [&](double x) { return std::atan2(stumps[i].radius_at(x), x); };
    if (angle(hi) > target) unsupported("the stumps stay too close to each other to place their collars");
    // A stump whose exit circle already lies inside its share needs no push: its collar starts at the exit.
    if (angle(lo) <= target) hi = lo;
    for (int it = 0; it < 80 && angle(lo) > target; ++it) {
      const double mid = 0.5 * (lo + hi);
      (angle(mid) > target ? lo : hi) = mid;
    }
    // Beyond the ball too: a collar disk never cuts into the ball (for the Boolean cores, it stays untouched).
    collar[i] = std::max({hi, stumps[i].exit + kCollarClearance, 1.0 + kCollarClearance});
  }
  // Clearance of each collar disk from the other stumps' parts before their collars (GJK on the disk and the
  // frustum), and on the hull model the collar circle where its own stump dominates (a linear function on a
  // circle peaks at its center plus its amplitude). Collars grow until all hold; growing one may need another
  // to grow, so repeat until nothing changes.
  std::vector<Cone> cones;
  if (kind == CoreKind::Hull)
    for (const CoreStump& s : stumps) cones.push_back(make_cone(s));
  auto disk = [&](int i, double x) {
    const Vec3 d = glm::normalize(stumps[i].direction);
    return Circle{x * d, d, stumps[i].radius_at(x)};
  };
  auto clear_of = [&](int i, int j) {
    const Vec3 d = glm::normalize(stumps[i].direction);
    if (kind == CoreKind::Hull) {
      const Cone& kj = cones[j];
      const Vec3 center = collar[i] * d;
      const Vec3 g = kj.d / kj.c - d / cones[i].c;
      const double at_center = kj.w(center) - cones[i].w(center);
      const double amplitude = stumps[i].radius_at(collar[i]) * glm::length(g - glm::dot(g, d) * d);
      if (!(at_center + amplitude < -kCollarClearance)) return false;
    }
    const Circle mine = disk(i, collar[i]);
    const Circle j0 = disk(j, stumps[j].end_radius * stumps[j].sin_phi), j1 = disk(j, collar[j]);
    const DistanceBounds dist = convex_distance([&](const Vec3& v) { return disk_support(mine, v); },
                                                [&](const Vec3& v) { return disk_hull_support(j0, j1, v); },
                                                kCollarClearance, kCollarClearance);
    return dist.lower > kCollarClearance;
  };
  for (int round = 0;; ++round) {
    bool grew = false;
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) {
        if (j == i) continue;
        while (!clear_of(i, j)) {
          collar[i] *= 1.1;
          grew = true;
          if (collar[i] > max_position || stumps[i].radius_at(collar[i]) <= 0.1 * stumps[i].end_radius)
            unsupported("a stump's collar cannot clear its neighbours before its cut");
        }
      }
    if (!grew) break;
    if (round > 50) unsupported("the collars of a crowded hub do not settle");
  }
  return collar;
}

std::shared_ptr<const HubCore> build_hub_core(const std::vector<CoreStump>& stumps, CoreKind kind,
                                              const std::vector<double>& collars) {
  if (stumps.empty()) unsupported("a hub core needs stumps");
  return kind == CoreKind::Hull ? build_hull_core(stumps, collars) : build_transversal_core(stumps, collars);
}

double core_volume_by_quadrature(const std::vector<CoreStump>& stumps, const std::vector<double>& collars,
                                 int resolution) {
  // Gauss-Legendre in cos(theta) on [-1, 1] (nodes by Newton on the Legendre polynomial), uniform in phi.
  const int m = resolution;
  std::vector<double> nodes(m), weights(m);
  for (int i = 0; i < m; ++i) {
    double x = std::cos(M_PI * (i + 0.75) / (m + 0.5));
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = x;
      for (int k = 2; k <= m; ++k) {
        const double p2 = ((2.0 * k - 1.0) * x * p1 - (k - 1.0) * p0) / k;
        p0 = p1;
        p1 = p2;
      }
      const double dp = m * (x * p1 - p0) / (x * x - 1.0);
      const double dx = p1 / dp;
      x -= dx;
      if (std::abs(dx) < 1e-16) {
        nodes[i] = x;
        weights[i] = 2.0 / ((1.0 - x * x) * dp * dp);
        break;
      }
    }
  }
  const int nphi = 2 * m;
  double volume = 0.0;
  for (int i = 0; i < m; ++i) {
    const double z = nodes[i], r = std::sqrt(std::max(0.0, 1.0 - z * z));
    for (int k = 0; k < nphi; ++k) {
      const double phi = kTwoPi * (k + 0.5) / nphi;
      const Vec3 w(r * std::cos(phi), r * std::sin(phi), z);
      double reach = 1.0;
      for (std::size_t s = 0; s < stumps.size(); ++s) reach = std::max(reach, stump_reach(stumps[s], collars[s], w));
      volume += weights[i] * (kTwoPi / nphi) * reach * reach * reach / 3.0;
    }
  }
  return volume;
}

}  // namespace steady
