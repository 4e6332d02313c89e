#include "brep/retraced_edges.hpp"

#include <AdvApprox_ApproxAFunction.hxx>
#include <AdvApprox_EvaluatorFunction.hxx>
#include <BRepAdaptor_Curve.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRep_Builder.hxx>
#include <BRep_TEdge.hxx>
#include <BRep_TVertex.hxx>
#include <BRep_Tool.hxx>
#include <ElSLib.hxx>
#include <Geom2dAPI_Interpolate.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <GeomAPI_Interpolate.hxx>
#include <GeomAdaptor_Curve.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Geom_Curve.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_HArray1OfInteger.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <Standard_Failure.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_HArray1OfPnt.hxx>
#include <TColgp_HArray1OfPnt2d.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Face.hxx>
#include <TopoDS_Vertex.hxx>
#include <gp_Lin.hxx>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

namespace steady {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;
// Surfaces meeting at less than this angle (its sine) leave the curve ill-conditioned: such an edge is left alone.
constexpr double kMinCrossingSine = 1e-3;
// Points within this angle (its cosine) of a sphere's pole have no stable u.
constexpr double kMinPoleCosine = 1e-3;
// How far the new curves may stray from the surfaces and from each other: a ball of radius 0.1 cut by a wall then
// has its volume to 3e-9 (RetracedEdges tests); 1e-10 would make the main job's STEP 11 % larger. The edge's
// tolerance is max(1e-7, twice what they stray).
constexpr double kTargetDeviation = 1e-8;
constexpr int kFirstSamples = 16, kMostSamples = 2048, kMostRounds = 30;

// A plane, sphere, cylinder or cone as the zero set of a function that is the signed distance near the surface,
// with its (u, v) parameters and points (in the coordinates of the shape, the face's location applied).
struct ImplicitSurface {
  GeomAbs_SurfaceType type = GeomAbs_OtherSurface;
  gp_Pln plane;
  gp_Sphere sphere;
  gp_Cylinder cylinder;
  gp_Cone cone;

  double value(const gp_XYZ& x, gp_XYZ& gradient) const {
    switch (type) {
      case GeomAbs_Plane: {
        gradient = plane.Axis().Direction().XYZ();
        return gradient.Dot(x - plane.Location().XYZ());
      }
      case GeomAbs_Sphere: {
        const gp_XYZ d = x - sphere.Location().XYZ();
        const double r = d.Modulus();
        gradient = r > 0.0 ? d / r : gp_XYZ(1.0, 0.0, 0.0);
        return r - sphere.Radius();
      }
      case GeomAbs_Cylinder: {
        const gp_XYZ a = cylinder.Axis().Direction().XYZ(), w = x - cylinder.Location().XYZ();
        const gp_XYZ radial = w - a * w.Dot(a);
        const double rho = radial.Modulus();
        gradient = rho > 0.0 ? radial / rho : gp_XYZ(cylinder.XAxis().Direction().XYZ());
        return rho - cylinder.Radius();
      }
      default: {  // the cone: its points are at distance R + h tan(alpha) from the axis, h along it from Location
        const gp_XYZ a = cone.Axis().Direction().XYZ(), w = x - cone.Location().XYZ();
        const double h = w.Dot(a), c = std::cos(cone.SemiAngle()), s = std::sin(cone.SemiAngle());
        const gp_XYZ radial = w - a * h;
        const double rho = radial.Modulus();
        const gp_XYZ out = rho > 0.0 ? radial / rho : gp_XYZ(cone.XAxis().Direction().XYZ());
        gradient = out * c - a * s;
        return (rho - cone.RefRadius()) * c - h * s;
      }
    }
  }

  gp_Pnt2d parameters(const gp_Pnt& p) const {
    double u = 0.0, v = 0.0;
    switch (type) {
      case GeomAbs_Plane: ElSLib::Parameters(plane, p, u, v); break;
      case GeomAbs_Sphere: ElSLib::Parameters(sphere, p, u, v); break;
      case GeomAbs_Cylinder: ElSLib::Parameters(cylinder, p, u, v); break;
      default: ElSLib::Parameters(cone, p, u, v); break;
    }
    return gp_Pnt2d(u, v);
  }

  gp_Pnt point(const gp_Pnt2d& uv) const {
    switch (type) {
      case GeomAbs_Plane: return ElSLib::Value(uv.X(), uv.Y(), plane);
      case GeomAbs_Sphere: return ElSLib::Value(uv.X(), uv.Y(), sphere);
      case GeomAbs_Cylinder: return ElSLib::Value(uv.X(), uv.Y(), cylinder);
      default: return ElSLib::Value(uv.X(), uv.Y(), cone);
    }
  }

  bool u_periodic() const { return type != GeomAbs_Plane; }
};

std::optional<ImplicitSurface> implicit_surface(const TopoDS_Face& face) {
  const BRepAdaptor_Surface adaptor(face, Standard_False);
  ImplicitSurface s;
  s.type = adaptor.GetType();
  switch (s.type) {
    case GeomAbs_Plane: s.plane = adaptor.Plane(); break;
    case GeomAbs_Sphere: s.sphere = adaptor.Sphere(); break;
    case GeomAbs_Cylinder: s.cylinder = adaptor.Cylinder(); break;
    case GeomAbs_Cone: s.cone = adaptor.Cone(); break;
    default: return std::nullopt;
  }
  return s;
}

// Newton steps of least length onto both surfaces (each step solves the two linearised equations with the
// smallest move, which is across the curve); false where the surfaces meet nearly tangentially or it does not
// converge.
bool pull_onto_both(const ImplicitSurface& a, const ImplicitSurface& b, gp_XYZ& x) {
  const double scale = std::max(1.0, x.Modulus());
  for (int step = 0; step < 40; ++step) {
    gp_XYZ ga, gb;
    const double fa = a.value(x, ga), fb = b.value(x, gb);
    if (std::abs(fa) < 1e-14 * scale && std::abs(fb) < 1e-14 * scale) return true;
    const double aa = ga.Dot(ga), ab = ga.Dot(gb), bb = gb.Dot(gb), det = aa * bb - ab * ab;
    if (det < kMinCrossingSine * kMinCrossingSine * aa * bb) return false;
    const double la = (bb * fa - ab * fb) / det, lb = (aa * fb - ab * fa) / det;
    const gp_XYZ move = ga * la + gb * lb;
    x -= move;
    if (move.Modulus() < 1e-15 * scale) break;
  }
  gp_XYZ g;
  return std::abs(a.value(x, g)) < 1e-11 * scale && std::abs(b.value(x, g)) < 1e-11 * scale;
}

// One of the edge's faces: its surface and the edge's current (u, v) curve on it (which picks the period).
struct Side {
  TopoDS_Face face;
  ImplicitSurface surface;
  Handle(Geom2d_Curve) old_pcurve;
};

// All faces along the edge (two in a solid; more where parts share faces), on two distinct surfaces: `a` and `b`
// index one face on each, the surfaces the points are pulled onto.
struct Sides {
  std::vector<Side> faces;
  std::size_t a = 0, b = 1;
};

struct Trace {
  Handle(Geom_Curve) curve;  // null where the edge's own curve (a conic) is kept
  std::vector<Handle(Geom2d_BSplineCurve)> pcurves;  // one per face
  double deviation = 0.0;
};

// (u, v) of a point on the side's surface, u in the period nearest `u_near`; false near a sphere's pole.
bool side_parameters(const Side& side, const gp_Pnt& p, double u_near, gp_Pnt2d& uv) {
  uv = side.surface.parameters(p);
  if (side.surface.type == GeomAbs_Sphere && std::cos(uv.Y()) < kMinPoleCosine) return false;
  if (side.surface.u_periodic()) uv.SetX(uv.X() + kTwoPi * std::round((u_near - uv.X()) / kTwoPi));
  return true;
}

// The samples' (u, v) on a face: the period of u taken from the old (u, v) curve's start, then followed from
// sample to sample (near a seam the old curve, 1e-4 off, could pick the other side); false when the end does not
// come back to the old curve's end (in the other period, the face's loop would not close).
bool face_parameters(const Side& side, const TColgp_HArray1OfPnt& points, const std::vector<double>& old_t,
                     TColgp_HArray1OfPnt2d& uvs) {
  const int n = points.Length();
  const bool old = !side.old_pcurve.IsNull();
  double u_near = old ? side.old_pcurve->Value(old_t.front()).X() : side.surface.parameters(points(1)).X();
  for (int i = 1; i <= n; ++i) {
    gp_Pnt2d uv;
    if (!side_parameters(side, points(i), u_near, uv)) return false;
    uvs(i) = uv;
    u_near = uv.X();
  }
  return !old || std::abs(uvs(n).X() - side.old_pcurve->Value(old_t.back()).X()) < 0.5;
}

// How far the new curves stray, in each interval between samples: from each surface, and the (u, v) curves'
// points from the 3D curve's, at the samples and three points between.
std::vector<double> interval_deviations(const Trace& trace, const Adaptor3d_Curve& curve, const Sides& sides,
                                        const TColStd_Array1OfReal& params) {
  std::vector<double> worst(params.Length() - 1, 0.0);
  for (int i = params.Lower(); i < params.Upper(); ++i)
    for (int q = 0; q <= 4; ++q) {
      const double t = params(i) + (params(i + 1) - params(i)) * q / 4.0;
      const gp_Pnt p = curve.Value(t);
      double& w = worst[i - params.Lower()];
      for (std::size_t k = 0; k < sides.faces.size(); ++k) {
        gp_XYZ g;
        w = std::max(w, std::abs(sides.faces[k].surface.value(p.XYZ(), g)));
        w = std::max(w, sides.faces[k].surface.point(trace.pcurves[k]->Value(t)).Distance(p));
      }
    }
  return worst;
}

// Parameters of the old curve at n + 1 points evenly spaced along it (by the chords of a dense sampling): a
// walking line's parameter can run very unevenly.
std::vector<double> even_parameters(const Adaptor3d_Curve& curve, double first, double last, int n) {
  const int m = std::max(256, 4 * n);
  std::vector<double> length(m + 1, 0.0);
  gp_Pnt previous = curve.Value(first);
  for (int j = 1; j <= m; ++j) {
    const gp_Pnt p = curve.Value(first + (last - first) * j / m);
    length[j] = length[j - 1] + p.Distance(previous);
    previous = p;
  }
  std::vector<double> t(n + 1);
  int j = 0;
  for (int i = 0; i <= n; ++i) {
    const double target = length[m] * i / n;
    while (j < m - 1 && length[j + 1] < target) ++j;
    const double piece = length[j + 1] - length[j];
    const double f = piece > 0.0 ? std::clamp((target - length[j]) / piece, 0.0, 1.0) : 0.0;
    t[i] = first + (last - first) * (j + f) / m;
  }
  t.front() = first;
  t.back() = last;
  return t;
}

// The (u, v) velocity on the side's surface that moves its point at `uv` with the 3D velocity `v` (tangent to it).
gp_Vec2d surface_velocity(const ImplicitSurface& surface, const gp_Pnt2d& uv, const gp_Vec& v) {
  gp_Pnt p;
  gp_Vec su, sv;
  switch (surface.type) {
    case GeomAbs_Plane: ElSLib::D1(uv.X(), uv.Y(), surface.plane, p, su, sv); break;
    case GeomAbs_Sphere: ElSLib::D1(uv.X(), uv.Y(), surface.sphere, p, su, sv); break;
    case GeomAbs_Cylinder: ElSLib::D1(uv.X(), uv.Y(), surface.cylinder, p, su, sv); break;
    default: ElSLib::D1(uv.X(), uv.Y(), surface.cone, p, su, sv); break;
  }
  const double uu = su.Dot(su), uv_ = su.Dot(sv), vv = sv.Dot(sv), det = uu * vv - uv_ * uv_;
  const double bu = su.Dot(v), bv = sv.Dot(v);
  return gp_Vec2d((vv * bu - uv_ * bv) / det, (uu * bv - uv_ * bu) / det);
}

// Points of the exact curve, their parameters on the new curves, the curve's velocity at both ends, and their
// (u, v) on each face.
struct Samples {
  Handle(TColgp_HArray1OfPnt) points;
  Handle(TColStd_HArray1OfReal) params;
  gp_Vec start_velocity, end_velocity;
  std::vector<Handle(TColgp_HArray1OfPnt2d)> uvs;
};

// The exact curve's unit tangent at a point: the normals' cross product, turned to point along `sense`.
gp_Vec exact_direction(const Sides& sides, const gp_Pnt& p, const gp_Vec& sense) {
  gp_XYZ ga, gb;
  sides.faces[sides.a].surface.value(p.XYZ(), ga);
  sides.faces[sides.b].surface.value(p.XYZ(), gb);
  gp_Vec along = gp_Vec(ga.Crossed(gb)).Normalized();
  if (along.Dot(sense) < 0.0) along.Reverse();
  return along;
}

// Drops samples that the pull left behind the one before: the old curve strays along the exact one too (up to
// its tolerance), so near a vertex, or where the old parameter runs fast, a pulled point can land behind its
// predecessor, and the spline through them would turn back (a loop a checker finds self-intersecting). Each kept
// point lies ahead of the one kept before it along the curve (in the old curve's sense); the last, the
// vertex, is always kept, and points before it are dropped until it is ahead.
void keep_samples_in_order(const Sides& sides, const Adaptor3d_Curve& old_curve, std::vector<gp_Pnt>& points,
                           std::vector<double>& old_t) {
  std::vector<gp_Vec> along(points.size());
  for (std::size_t i = 0; i < points.size(); ++i)
    along[i] = exact_direction(sides, points[i], old_curve.DN(old_t[i], 1));
  // Ahead along the mean of the two directions: a sharp bend between far samples is no reason to drop one.
  const auto ahead = [&](std::size_t i, std::size_t k) {
    return gp_Vec(points[i], points[k]).Dot(along[i] + along[k]) > 0.0;
  };
  std::vector<std::size_t> kept = {0};
  for (std::size_t j = 1; j < points.size(); ++j) {
    if (j + 1 < points.size()) {
      if (ahead(kept.back(), j)) kept.push_back(j);
      continue;
    }
    while (kept.size() > 1 && !ahead(kept.back(), j)) kept.pop_back();
    kept.push_back(j);
  }
  std::vector<gp_Pnt> kept_points;
  std::vector<double> kept_t;
  for (std::size_t i : kept) {
    kept_points.push_back(points[i]);
    kept_t.push_back(old_t[i]);
  }
  points = std::move(kept_points);
  old_t = std::move(kept_t);
}

// The first samples of the exact curve, at the old curve's parameters `old_t`: a conic (a circle where a plane or
// a cone meets a sphere, an ellipse where a plane meets a cylinder) is exact already, its own points; otherwise the
// old curve's points (at its ends, its vertices) pulled onto the curve, those left out of order dropped (with
// their parameters).
std::optional<std::vector<gp_Pnt>> first_samples(const TopoDS_Edge& edge, const BRepAdaptor_Curve& old_curve,
                                                 const Sides& sides, bool conic, std::vector<double>& old_t) {
  TopoDS_Vertex v_first, v_last;
  TopExp::Vertices(edge, v_first, v_last);
  std::vector<gp_Pnt> pulled;
  for (std::size_t i = 0; i < old_t.size(); ++i) {
    gp_XYZ x = conic                                       ? old_curve.Value(old_t[i]).XYZ()
               : i == 0 && !v_first.IsNull()               ? BRep_Tool::Pnt(v_first).XYZ()
               : i + 1 == old_t.size() && !v_last.IsNull() ? BRep_Tool::Pnt(v_last).XYZ()
                                                           : old_curve.Value(old_t[i]).XYZ();
    if (!conic && !pull_onto_both(sides.faces[sides.a].surface, sides.faces[sides.b].surface, x))
      return std::nullopt;
    pulled.emplace_back(x);
  }
  if (!conic) keep_samples_in_order(sides, old_curve, pulled, old_t);
  if (pulled.size() < 2) return std::nullopt;
  return pulled;
}

// Samples between two of the exact curve: a conic's own point at the middle parameter; otherwise the middle of
// their chord pulled onto the curve, which lands between them (the pull moves across the curve), where the old
// curve's point at the middle parameter, off along the curve too, could land behind one of them.
std::optional<gp_Pnt> middle_sample(const Sides& sides, const Adaptor3d_Curve& old_curve, bool conic, double t0,
                                    double t1, const gp_Pnt& p0, const gp_Pnt& p1) {
  if (conic) return old_curve.Value(0.5 * (t0 + t1));
  gp_XYZ x = 0.5 * (p0.XYZ() + p1.XYZ());
  if (!pull_onto_both(sides.faces[sides.a].surface, sides.faces[sides.b].surface, x)) return std::nullopt;
  return gp_Pnt(x);
}

// The samples `points` of the exact curve (from the old curve's parameters `old_t`) as spline data: for a conic
// its parameters and derivatives; otherwise the chord length as parameter (scaled to the edge's range) and the
// velocities along the curve at that speed at both ends; and their (u, v) on each face.
std::optional<Samples> sample_exact_curve(const BRepAdaptor_Curve& old_curve, const Sides& sides, bool conic,
                                          const std::vector<double>& old_t, const std::vector<gp_Pnt>& pulled) {
  const double first = old_curve.FirstParameter(), last = old_curve.LastParameter();
  const int n = static_cast<int>(old_t.size()) - 1;
  if (n < 1) return std::nullopt;
  Samples out{new TColgp_HArray1OfPnt(1, n + 1), new TColStd_HArray1OfReal(1, n + 1), {}, {}, {}};
  std::vector<double> chord(n + 1, 0.0);
  for (int i = 0; i <= n; ++i) {
    out.points->SetValue(i + 1, pulled[i]);
    if (i > 0) chord[i] = chord[i - 1] + pulled[i].Distance(pulled[i - 1]);
  }
  if (!(chord[n] > 0.0)) return std::nullopt;
  for (int i = 0; i <= n; ++i)
    out.params->SetValue(i + 1, conic ? old_t[i] : i == n ? last : first + (last - first) * chord[i] / chord[n]);
  if (conic) {
    out.start_velocity = old_curve.DN(first, 1);
    out.end_velocity = old_curve.DN(last, 1);
  } else {
    const double speed = chord[n] / (last - first);
    out.start_velocity = exact_direction(sides, pulled[0], gp_Vec(pulled[0], pulled[1])) * speed;
    out.end_velocity = exact_direction(sides, pulled[n], gp_Vec(pulled[n - 1], pulled[n])) * speed;
  }
  for (std::size_t k = 0; k < sides.faces.size(); ++k) {
    out.uvs.push_back(new TColgp_HArray1OfPnt2d(1, n + 1));
    if (!face_parameters(sides.faces[k], *out.points, old_t, *out.uvs[k])) return std::nullopt;
  }
  return out;
}

// Cubic splines through the samples of the exact curve, with the curve's velocity at both ends (a conic keeps its
// own 3D curve), and how far they stray between each two samples.
std::optional<Trace> trace_through(const BRepAdaptor_Curve& old_curve, const Sides& sides, bool conic,
                                   const std::vector<double>& old_t, const std::vector<gp_Pnt>& points,
                                   std::vector<double>& deviations) {
  const std::optional<Samples> samples = sample_exact_curve(old_curve, sides, conic, old_t, points);
  if (!samples) return std::nullopt;
  const int count = samples->points->Length();
  Trace trace;
  if (!conic) {
    double spacing = samples->points->Value(1).Distance(samples->points->Value(2));
    for (int i = 2; i < count; ++i)
      spacing = std::min(spacing, samples->points->Value(i).Distance(samples->points->Value(i + 1)));
    GeomAPI_Interpolate curve(samples->points, samples->params, Standard_False, std::min(1e-12, 0.01 * spacing));
    curve.Load(samples->start_velocity, samples->end_velocity, Standard_False);
    curve.Perform();
    if (!curve.IsDone()) return std::nullopt;
    trace.curve = curve.Curve();
  }
  for (std::size_t k = 0; k < sides.faces.size(); ++k) {
    const Handle(TColgp_HArray1OfPnt2d)& uvs = samples->uvs[k];
    Geom2dAPI_Interpolate pcurve(uvs, samples->params, Standard_False, 1e-14);
    pcurve.Load(surface_velocity(sides.faces[k].surface, uvs->Value(1), samples->start_velocity),
                surface_velocity(sides.faces[k].surface, uvs->Value(count), samples->end_velocity), Standard_False);
    pcurve.Perform();
    if (!pcurve.IsDone()) return std::nullopt;
    trace.pcurves.push_back(pcurve.Curve());
  }
  deviations = conic ? interval_deviations(trace, old_curve, sides, samples->params->Array1())
                     : interval_deviations(trace,
                                           GeomAdaptor_Curve(trace.curve, old_curve.FirstParameter(),
                                                             old_curve.LastParameter()),
                                           sides, samples->params->Array1());
  trace.deviation = *std::max_element(deviations.begin(), deviations.end());
  return trace;
}

// The edge's faces as sides it can be retraced between, or nothing: a seam, a face of another kind, an edge that
// is not same-parameter, or faces that are not on exactly two surfaces crossing each other.
std::optional<Sides> retraceable_sides(const TopoDS_Edge& edge, const TopTools_ListOfShape& faces) {
  if (BRep_Tool::Degenerated(edge) || !BRep_Tool::SameParameter(edge) || !BRep_Tool::SameRange(edge) ||
      faces.Extent() < 2)
    return std::nullopt;
  Sides sides;
  for (const TopoDS_Shape& f : faces) {
    const TopoDS_Face face = TopoDS::Face(f);
    if (BRep_Tool::IsClosed(edge, face)) return std::nullopt;
    const std::optional<ImplicitSurface> surface = implicit_surface(face);
    if (!surface) return std::nullopt;
    double a = 0.0, b = 0.0;
    sides.faces.push_back({face, *surface, BRep_Tool::CurveOnSurface(edge, face, a, b)});
  }
  // The pair of faces whose normals cross most at the edge's middle; the others must lie on one of their surfaces.
  double first = 0.0, last = 0.0;
  BRep_Tool::Range(edge, first, last);
  const gp_XYZ middle = BRepAdaptor_Curve(edge).Value(0.5 * (first + last)).XYZ();
  std::vector<gp_XYZ> normals(sides.faces.size());
  for (std::size_t k = 0; k < sides.faces.size(); ++k) sides.faces[k].surface.value(middle, normals[k]);
  double crossing = 0.0;
  for (std::size_t i = 0; i < normals.size(); ++i)
    for (std::size_t k = i + 1; k < normals.size(); ++k) {
      const double sine = normals[i].Crossed(normals[k]).Modulus();
      if (sine > crossing) {
        crossing = sine;
        sides.a = i;
        sides.b = k;
      }
    }
  if (crossing < kMinCrossingSine) return std::nullopt;
  return sides;
}

// The tolerance a vertex needs: the distance from its point to the ends of every curve of its edges, and at least
// their tolerances.
double vertex_tolerance_needed(const TopoDS_Vertex& vertex, const TopTools_ListOfShape& edges,
                               const TopTools_IndexedDataMapOfShapeListOfShape& edge_faces) {
  const gp_Pnt p = BRep_Tool::Pnt(vertex);
  double needed = 1e-7;
  for (const TopoDS_Shape& e : edges) {
    const TopoDS_Edge& edge = TopoDS::Edge(e);
    needed = std::max(needed, BRep_Tool::Tolerance(edge));
    if (BRep_Tool::Degenerated(edge)) continue;
    const double t = BRep_Tool::Parameter(vertex, edge);
    needed = std::max(needed, 1.1 * BRepAdaptor_Curve(edge).Value(t).Distance(p));
    const int index = edge_faces.FindIndex(edge);
    if (index == 0) continue;
    for (const TopoDS_Shape& f : edge_faces(index)) {
      const BRepAdaptor_Curve on_face(edge, TopoDS::Face(f));
      needed = std::max(needed, 1.1 * on_face.Value(t).Distance(p));
    }
  }
  return needed;
}

// Replaces the edge's curves by the trace's and sets its tolerance.
void apply_trace(const TopoDS_Edge& edge, const Sides& sides, const Trace& trace, double tolerance) {
  BRep_Builder builder;
  if (!trace.curve.IsNull()) builder.UpdateEdge(edge, trace.curve, TopLoc_Location(), tolerance);
  for (std::size_t k = 0; k < sides.faces.size(); ++k)
    builder.UpdateEdge(edge, trace.pcurves[k], sides.faces[k].face, tolerance);
  Handle(BRep_TEdge)::DownCast(edge.TShape())->Tolerance(tolerance);
  edge.TShape()->Modified(Standard_True);
}

// An edge's curves and tolerances and those of its vertices, to put back when its faces come out invalid.
struct SavedEdge {
  Handle(Geom_Curve) curve;
  TopLoc_Location location;
  std::vector<Handle(Geom2d_Curve)> pcurves;
  double tolerance = 0.0;
  std::vector<std::pair<TopoDS_Vertex, double>> vertices;
};

SavedEdge save_edge(const TopoDS_Edge& edge, const Sides& sides) {
  SavedEdge saved;
  double first = 0.0, last = 0.0;
  saved.curve = BRep_Tool::Curve(edge, saved.location, first, last);
  for (const Side& side : sides.faces) saved.pcurves.push_back(BRep_Tool::CurveOnSurface(edge, side.face, first, last));
  saved.tolerance = BRep_Tool::Tolerance(edge);
  for (TopExp_Explorer v(edge, TopAbs_VERTEX); v.More(); v.Next())
    saved.vertices.emplace_back(TopoDS::Vertex(v.Current()), BRep_Tool::Tolerance(TopoDS::Vertex(v.Current())));
  return saved;
}

void restore_edge(const TopoDS_Edge& edge, const Sides& sides, const SavedEdge& saved) {
  BRep_Builder builder;
  builder.UpdateEdge(edge, saved.curve, saved.location, saved.tolerance);
  for (std::size_t k = 0; k < sides.faces.size(); ++k)
    builder.UpdateEdge(edge, saved.pcurves[k], sides.faces[k].face, saved.tolerance);
  Handle(BRep_TEdge)::DownCast(edge.TShape())->Tolerance(saved.tolerance);
  for (const auto& [vertex, tolerance] : saved.vertices)
    Handle(BRep_TVertex)::DownCast(vertex.TShape())->Tolerance(tolerance);
  edge.TShape()->Modified(Standard_True);
}

// The edge's vertices given at least the tolerance their edges need now. Never less than they had: a vertex's
// tolerance also covers the other edges that meet there, and where two of them meet at a small angle on a face
// that no retraced edge bounds (so no check below sees it), a smaller one made their (u, v) curves cross outside it
// and the face read back self-intersecting (the octet at node 0.45, beams 1.0 of the node, a taper).
void cover_vertices(const TopoDS_Edge& edge, const TopTools_IndexedDataMapOfShapeListOfShape& vertex_edges,
                    const TopTools_IndexedDataMapOfShapeListOfShape& edge_faces) {
  for (TopExp_Explorer v(edge, TopAbs_VERTEX); v.More(); v.Next()) {
    const TopoDS_Vertex& vertex = TopoDS::Vertex(v.Current());
    const double needed = vertex_tolerance_needed(vertex, vertex_edges.FindFromKey(vertex), edge_faces);
    if (needed > BRep_Tool::Tolerance(vertex)) Handle(BRep_TVertex)::DownCast(vertex.TShape())->Tolerance(needed);
  }
}

// The best trace of an edge: from samples evenly spaced along it, each interval whose curves stray more than the
// target split in two, until all come within it or the samples or rounds run out.
std::optional<Trace> best_trace(const TopoDS_Edge& edge, const Sides& sides) {
  const BRepAdaptor_Curve old_curve(edge);
  const GeomAbs_CurveType kind = old_curve.GetType();
  const bool conic = kind == GeomAbs_Line || kind == GeomAbs_Circle || kind == GeomAbs_Ellipse;
  double first = 0.0, last = 0.0;
  BRep_Tool::Range(edge, first, last);
  std::vector<double> old_t = even_parameters(old_curve, first, last, kFirstSamples);
  if (conic)
    for (int i = 0; i <= kFirstSamples; ++i) old_t[i] = first + (last - first) * i / kFirstSamples;
  std::optional<std::vector<gp_Pnt>> first_points = first_samples(edge, old_curve, sides, conic, old_t);
  if (!first_points) return std::nullopt;
  std::vector<gp_Pnt> points = std::move(*first_points);
  std::optional<Trace> best;
  for (int round = 0; round < kMostRounds; ++round) {
    std::vector<double> deviations;
    std::optional<Trace> trace = trace_through(old_curve, sides, conic, old_t, points, deviations);
    if (!trace) return best;
    if (!best || trace->deviation < best->deviation) best = trace;
    if (best->deviation <= kTargetDeviation) break;
    std::vector<double> refined_t = {old_t.front()};
    std::vector<gp_Pnt> refined = {points.front()};
    for (std::size_t i = 0; i + 1 < old_t.size(); ++i) {
      if (deviations[i] > kTargetDeviation) {
        const std::optional<gp_Pnt> middle =
            middle_sample(sides, old_curve, conic, old_t[i], old_t[i + 1], points[i], points[i + 1]);
        if (middle) {
          refined_t.push_back(0.5 * (old_t[i] + old_t[i + 1]));
          refined.push_back(*middle);
        }
      }
      refined_t.push_back(old_t[i + 1]);
      refined.push_back(points[i + 1]);
    }
    if (refined.size() > static_cast<std::size_t>(kMostSamples) || refined.size() == points.size()) break;
    old_t = std::move(refined_t);
    points = std::move(refined);
  }
  return best;
}

// ---- Edges winding around a beam, refitted with the beam's angle as parameter (issue 14: compact files) ----
//
// Where an edge winds around a cylinder or a cone (its u there runs one way along it), the exact curve is a
// function of that angle: the point where the surface's ruling at angle u meets the other surface (a ball cut by a
// wall: the meridian of a sphere framed around the wall's normal). With u as the parameter the 3D curve and every
// (u, v) curve are smooth functions of one variable, which B-splines of degree up to 14 follow to 1e-8 with one to
// a few spans: about 35 poles a curve for a whole loop, where OpenCASCADE's walking lines keep 20 to 160 (the main
// job's STEP: 48 % of it was such curves).

constexpr int kAxisSamples = 64;  // samples of the old curves: monotony of u, and starting points for Newton
constexpr int kAxisMaxDegree = 14, kAxisMaxSegments = 64;

// The exact curve of an edge around the axis of `axis` (a face's cylinder or cone, or a framed sphere), as a
// function of the edge's own parameter t: u = u0 + (u1 - u0) (t - first) / (last - first) on that surface, v where
// its ruling meets the other surface. (u, v) on every face follow, each face's u in the period of its old curve.
class AxisCurve : public AdvApprox_EvaluatorFunction {
 public:
  AxisCurve(const Sides& sides, const ImplicitSurface& axis, std::size_t other, double first, double last)
      : sides_(sides), axis_(axis), other_(other), first_(first), last_(last) {}

  // Reads the old curve at kAxisSamples + 1 parameters; false unless u around the axis runs strictly one way.
  bool sample_old_curves(const Adaptor3d_Curve& old_curve) {
    for (int i = 0; i <= kAxisSamples; ++i) {
      const double t = first_ + (last_ - first_) * i / kAxisSamples;
      const gp_Pnt p = old_curve.Value(t);
      gp_Pnt2d uv = axis_.parameters(p);
      if (i > 0) uv.SetX(uv.X() + kTwoPi * std::round((axis_u_.back() - uv.X()) / kTwoPi));
      axis_u_.push_back(uv.X());
      axis_v_.push_back(uv.Y());
      std::vector<double> us;
      for (std::size_t k = 0; k < sides_.faces.size(); ++k) {
        const Handle(Geom2d_Curve)& old = sides_.faces[k].old_pcurve;
        const double near = i > 0 ? face_u_[i - 1][k] : old.IsNull() ? sides_.faces[k].surface.parameters(p).X()
                                                                      : old->Value(t).X();
        gp_Pnt2d face_uv;
        if (!side_parameters(sides_.faces[k], p, near, face_uv)) return false;
        us.push_back(face_uv.X());
      }
      face_u_.push_back(std::move(us));
    }
    // u must run strictly one way: where it turns back the ruling meets the curve twice
    const double sense = axis_u_.back() - axis_u_.front();
    for (int i = 1; i <= kAxisSamples; ++i)
      if ((axis_u_[i] - axis_u_[i - 1]) * sense <= 0.0) return false;
    return std::abs(sense) > 1e-6;
  }

  // The exact point at t, its velocity (d/dt), and (u, v) and their velocities on every face; false where the ruling
  // meets the other surface too obliquely, Newton does not converge, or a face's (u, v) is not defined (a pole).
  bool evaluate(double t, gp_Pnt& p, gp_Vec& dp, std::vector<gp_Pnt2d>& uv, std::vector<gp_Vec2d>& duv) const {
    const double at = std::clamp((t - first_) / (last_ - first_), 0.0, 1.0) * kAxisSamples;
    const int k = std::min(static_cast<int>(at), kAxisSamples - 1);
    const double f = at - k, du_dt = (axis_u_.back() - axis_u_.front()) / (last_ - first_);
    const double u = axis_u_.front() + du_dt * (t - first_);
    double v = axis_v_[k] + (axis_v_[k + 1] - axis_v_[k]) * f;
    const ImplicitSurface& s = axis_;
    const ImplicitSurface& o = sides_.faces[other_].surface;
    gp_Vec su, sv;
    gp_XYZ g;
    bool converged = false;
    for (int step = 0; step < 30 && !converged; ++step) {
      ruling_point(s, u, v, p, su, sv);
      const double value = o.value(p.XYZ(), g), slope = g.Dot(sv.XYZ());
      if (std::abs(slope) < kMinCrossingSine * sv.Magnitude()) return false;
      v -= value / slope;
      converged = std::abs(value / slope) < 1e-15 * std::max(1.0, std::abs(v));
    }
    ruling_point(s, u, v, p, su, sv);
    if (std::abs(o.value(p.XYZ(), g)) > 1e-12 * std::max(1.0, p.XYZ().Modulus())) return false;
    dp = (su + sv * (-g.Dot(su.XYZ()) / g.Dot(sv.XYZ()))) * du_dt;
    uv.resize(sides_.faces.size());
    duv.resize(sides_.faces.size());
    for (std::size_t j = 0; j < sides_.faces.size(); ++j) {
      const double near = face_u_[k][j] + (face_u_[k + 1][j] - face_u_[k][j]) * f;
      if (!side_parameters(sides_.faces[j], p, near, uv[j])) return false;
      duv[j] = surface_velocity(sides_.faces[j].surface, uv[j], dp);
    }
    return true;
  }

  // AdvApprox's layout: the (u, v) curves of the faces one after another, then the 3D curve.
  void Evaluate(Standard_Integer* /*dimension*/, Standard_Real /*range*/[2], Standard_Real* parameter,
                Standard_Integer* derivative, Standard_Real* result, Standard_Integer* error) override {
    gp_Pnt p;
    gp_Vec dp;
    std::vector<gp_Pnt2d> uv;
    std::vector<gp_Vec2d> duv;
    *error = *derivative > 1 || !evaluate(*parameter, p, dp, uv, duv) ? 1 : 0;
    if (*error) return;
    const std::size_t n = sides_.faces.size();
    for (std::size_t j = 0; j < n; ++j) {
      result[2 * j] = *derivative == 0 ? uv[j].X() : duv[j].X();
      result[2 * j + 1] = *derivative == 0 ? uv[j].Y() : duv[j].Y();
    }
    const gp_XYZ x = *derivative == 0 ? p.XYZ() : dp.XYZ();
    result[2 * n] = x.X();
    result[2 * n + 1] = x.Y();
    result[2 * n + 2] = x.Z();
  }

 private:
  // The point at (u, v) on the axis surface: v runs along a ruling of a cylinder or cone, along a meridian of a
  // sphere.
  static void ruling_point(const ImplicitSurface& s, double u, double v, gp_Pnt& p, gp_Vec& su, gp_Vec& sv) {
    if (s.type == GeomAbs_Cylinder)
      ElSLib::D1(u, v, s.cylinder, p, su, sv);
    else if (s.type == GeomAbs_Cone)
      ElSLib::D1(u, v, s.cone, p, su, sv);
    else
      ElSLib::D1(u, v, s.sphere, p, su, sv);
  }

  const Sides& sides_;
  ImplicitSurface axis_;
  std::size_t other_;
  double first_, last_;
  std::vector<double> axis_u_, axis_v_;
  std::vector<std::vector<double>> face_u_;  // per sample, per face
};

bool has_spline_curve(const TopoDS_Edge& edge) {
  double a = 0.0, b = 0.0;
  const Handle(Geom_Curve) c = BRep_Tool::Curve(edge, a, b);
  return !c.IsNull() && c->DynamicType() == STANDARD_TYPE(Geom_BSplineCurve);
}

// Poles of the edge's curves: its 3D curve's and its (u, v) curves' (a line or conic counts 1).
int curve_poles(const Handle(Geom_Curve)& c) {
  const Handle(Geom_BSplineCurve) b = Handle(Geom_BSplineCurve)::DownCast(c);
  return b.IsNull() ? 1 : b->NbPoles();
}
int edge_poles(const TopoDS_Edge& edge, const Sides& sides) {
  double a = 0.0, b = 0.0;
  int n = curve_poles(BRep_Tool::Curve(edge, a, b));
  for (const Side& side : sides.faces) {
    const Handle(Geom2d_BSplineCurve) pc = Handle(Geom2d_BSplineCurve)::DownCast(side.old_pcurve);
    n += pc.IsNull() ? 1 : pc->NbPoles();
  }
  return n;
}

int trace_poles(const Trace& trace) {
  int n = curve_poles(trace.curve);
  for (const Handle(Geom2d_BSplineCurve)& pc : trace.pcurves) n += pc->NbPoles();
  return n;
}

// How far a unit step of u and of v moves the face's point at most, near `p` (a plane's: 1 and 1; a cone's u: twice
// the distance from its axis there, for the way along the edge): (u, v) curves are approximated as (su u, sv v), in
// which the 3D tolerance holds for both (on the skin's wall, radius 18.8, v needs no more than a beam's v).
gp_XY uv_scales(const Side& side, const gp_Pnt& p) {
  switch (side.surface.type) {
    case GeomAbs_Sphere: return gp_XY(side.surface.sphere.Radius(), side.surface.sphere.Radius());
    case GeomAbs_Cylinder: return gp_XY(side.surface.cylinder.Radius(), 1.0);
    case GeomAbs_Cone: return gp_XY(2.0 * gp_Lin(side.surface.cone.Axis()).Distance(p), 1.0);
    default: return gp_XY(1.0, 1.0);
  }
}

// One coordinate space of the exact curve: the (u, v) curve on face `space` scaled by `scales`, or the 3D curve
// (space = faces).
class OneSpace : public AdvApprox_EvaluatorFunction {
 public:
  OneSpace(AxisCurve& exact, int faces, int space, const gp_XY& scales)
      : exact_(exact), faces_(faces), space_(space), scales_(scales), all_(2 * faces + 3) {}
  void Evaluate(Standard_Integer* dimension, Standard_Real range[2], Standard_Real* parameter,
                Standard_Integer* derivative, Standard_Real* result, Standard_Integer* error) override {
    exact_.Evaluate(dimension, range, parameter, derivative, all_.data(), error);
    if (space_ == faces_) {
      std::copy_n(all_.begin() + 2 * space_, 3, result);
      return;
    }
    result[0] = all_[2 * space_] * scales_.X();
    result[1] = all_[2 * space_ + 1] * scales_.Y();
  }

 private:
  AxisCurve& exact_;
  int faces_, space_;
  gp_XY scales_;
  std::vector<double> all_;
};

// AdvApprox's tolerances: an array of one value.
Handle(TColStd_HArray1OfReal) one_value(double v) {
  Handle(TColStd_HArray1OfReal) a = new TColStd_HArray1OfReal(1, 1);
  a->SetValue(1, v);
  return a;
}

// The 3D curve and every (u, v) curve approximated each on its own knots (they share the parameter, so the edge
// stays same-parameter), all to half the target deviation (the (u, v) ones scaled by uv_scales); how far they
// stray measured as for a trace, and from the exact point. (Least-squares splines of the greatest smoothness through
// samples of the exact curve were tried: the main job 0.1 % smaller, 11 s slower.)
std::optional<Trace> approximate_axis_curve(AxisCurve& exact, const Sides& sides, const gp_Pnt& middle, double first,
                                            double last) {
  const int n = static_cast<int>(sides.faces.size());
  const Handle(TColStd_HArray1OfReal) none;
  Trace trace;
  const double tolerance = 0.5 * kTargetDeviation;
  for (int space = 0; space <= n; ++space) {
    const bool is_3d = space == n;
    const gp_XY scales = is_3d ? gp_XY(1.0, 1.0) : uv_scales(sides.faces[space], middle);
    if (scales.X() <= 0.0 || scales.Y() <= 0.0) return std::nullopt;
    OneSpace f(exact, n, space, scales);
    AdvApprox_ApproxAFunction approx(0, is_3d ? 0 : 1, is_3d ? 1 : 0, none, is_3d ? none : one_value(tolerance),
                                     is_3d ? one_value(tolerance) : none, first, last, GeomAbs_C1, kAxisMaxDegree,
                                     kAxisMaxSegments, f);
    if (!approx.IsDone() || !approx.HasResult()) return std::nullopt;
    const TColStd_Array1OfReal& knots = approx.Knots()->Array1();
    const TColStd_Array1OfInteger& mults = approx.Multiplicities()->Array1();
    if (is_3d) {
      TColgp_Array1OfPnt poles(1, approx.NbPoles());
      approx.Poles(1, poles);
      trace.curve = new Geom_BSplineCurve(poles, knots, mults, approx.Degree());
    } else {
      TColgp_Array1OfPnt2d poles(1, approx.NbPoles());
      approx.Poles2d(1, poles);
      for (gp_Pnt2d& p : poles) p.SetCoord(p.X() / scales.X(), p.Y() / scales.Y());
      trace.pcurves.push_back(new Geom2d_BSplineCurve(poles, knots, mults, approx.Degree()));
    }
  }
  constexpr int kChecks = 256;
  TColStd_Array1OfReal checks(1, kChecks + 1);
  for (int i = 0; i <= kChecks; ++i) checks(i + 1) = first + (last - first) * i / kChecks;
  const GeomAdaptor_Curve curve(trace.curve);
  const std::vector<double> deviations = interval_deviations(trace, curve, sides, checks);
  trace.deviation = *std::max_element(deviations.begin(), deviations.end());
  for (int i = checks.Lower(); i <= checks.Upper(); ++i) {
    gp_Pnt p;
    gp_Vec dp;
    std::vector<gp_Pnt2d> uv;
    std::vector<gp_Vec2d> duv;
    if (!exact.evaluate(checks(i), p, dp, uv, duv)) return std::nullopt;
    trace.deviation = std::max(trace.deviation, p.Distance(curve.Value(checks(i))));
  }
  return trace;
}

// The surface whose u the edge may wind around: a cylinder or cone as it is; a sphere in a frame whose pole is the
// other surface's normal at the sphere's centre (a ball cut by a wall: the loop goes round that direction, and so
// do its arcs between other edges); nothing for a plane.
std::optional<ImplicitSurface> axis_surface(const ImplicitSurface& s, const ImplicitSurface& other) {
  if (s.type == GeomAbs_Cylinder || s.type == GeomAbs_Cone) return s;
  if (s.type != GeomAbs_Sphere) return std::nullopt;
  gp_XYZ normal;
  other.value(s.sphere.Location().XYZ(), normal);
  if (normal.Modulus() < 0.5) return std::nullopt;  // a gradient of unit length wherever it is defined
  ImplicitSurface framed = s;
  framed.sphere = gp_Sphere(gp_Ax3(s.sphere.Location(), gp_Dir(normal)), s.sphere.Radius());
  return framed;
}

// The edge's curves refitted around the axis of a cylinder, cone or sphere it winds around, when that takes fewer
// poles than it has; nothing otherwise.
std::optional<Trace> fit_around_axis(const TopoDS_Edge& edge, const Sides& sides) {
  double first = 0.0, last = 0.0;
  BRep_Tool::Range(edge, first, last);
  const BRepAdaptor_Curve old_curve(edge);
  const std::size_t pair[2] = {sides.a, sides.b};
  for (int q = 0; q < 2; ++q) {
    const std::optional<ImplicitSurface> axis =
        axis_surface(sides.faces[pair[q]].surface, sides.faces[pair[1 - q]].surface);
    if (!axis) continue;
    AxisCurve exact(sides, *axis, pair[1 - q], first, last);
    if (!exact.sample_old_curves(old_curve)) continue;
    const std::optional<Trace> trace =
        approximate_axis_curve(exact, sides, old_curve.Value(0.5 * (first + last)), first, last);
    if (trace && trace->deviation <= kTargetDeviation && trace_poles(*trace) < edge_poles(edge, sides)) return trace;
  }
  return std::nullopt;
}

}  // namespace

RetracedEdges retrace_intersection_edges(const std::vector<TopoDS_Shape>& shapes) {
  RetracedEdges out;
  // One map over all shapes: an edge shared by two parts gets (u, v) curves on the faces of both.
  TopoDS_Compound all;
  BRep_Builder builder;
  builder.MakeCompound(all);
  for (const TopoDS_Shape& shape : shapes)
    if (!shape.IsNull()) builder.Add(all, shape);
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces, vertex_edges;
  TopExp::MapShapesAndUniqueAncestors(all, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  TopExp::MapShapesAndUniqueAncestors(all, TopAbs_VERTEX, TopAbs_EDGE, vertex_edges);
  struct Applied {
    TopoDS_Edge edge;
    Sides sides;
    SavedEdge saved;
    bool loose = false, around_axis = false;
  };
  std::vector<Applied> applied;
  std::vector<TopoDS_Edge> loose;
  // Every face along a retraced edge, and whether BRepCheck found it valid before any of its edges changed (a
  // face's check costs as much as its edges: the skin's inner wall holds thousands).
  TopTools_IndexedMapOfShape faces;
  std::vector<bool> valid_before;
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge& edge = TopoDS::Edge(edge_faces.FindKey(i));
    const double tolerance = BRep_Tool::Tolerance(edge);
    const bool is_loose = tolerance > kLooseEdgeTolerance, is_spline = has_spline_curve(edge);
    if (!is_loose && !is_spline) continue;
    const std::optional<Sides> sides = retraceable_sides(edge, edge_faces(i));
    if (!sides) continue;
    if (is_loose) {
      loose.push_back(edge);
      out.loosest_before = std::max(out.loosest_before, tolerance);
    }
    std::optional<Trace> trace;
    bool around_axis = false;
    try {
      if (is_spline) trace = fit_around_axis(edge, *sides);
      around_axis = trace.has_value();
      if (!trace && is_loose) trace = best_trace(edge, *sides);
    } catch (const Standard_Failure&) {
      trace.reset();
    }
    const double new_tolerance = trace ? std::max(1e-7, 2.0 * trace->deviation) : tolerance;
    if (!trace || (is_loose ? new_tolerance >= 0.5 * tolerance : new_tolerance > std::max(1e-7, tolerance))) continue;
    for (const Side& side : sides->faces)
      if (faces.Add(side.face) > static_cast<int>(valid_before.size()))
        valid_before.push_back(BRepCheck_Analyzer(side.face).IsValid());
    applied.push_back({edge, *sides, save_edge(edge, *sides), is_loose, around_axis});
    apply_trace(edge, *sides, *trace, new_tolerance);
    cover_vertices(edge, vertex_edges, edge_faces);
  }
  // The new curves stay only where every face along them that was valid still is (a face whose loop ends at a
  // sphere's pole can come out self-intersecting); otherwise all edges of such a face get their old curves back.
  std::vector<bool> revert(applied.size(), false);
  for (int f = 1; f <= faces.Extent(); ++f) {
    if (!valid_before[f - 1] || BRepCheck_Analyzer(faces(f)).IsValid()) continue;
    for (std::size_t k = 0; k < applied.size(); ++k)
      for (const Side& side : applied[k].sides.faces) revert[k] = revert[k] || side.face.IsSame(faces(f));
  }
  for (std::size_t k = applied.size(); k-- > 0;)
    if (revert[k]) restore_edge(applied[k].edge, applied[k].sides, applied[k].saved);
  out.loose = static_cast<std::int64_t>(loose.size());
  for (std::size_t k = 0; k < applied.size(); ++k) {
    out.retraced += !revert[k] && applied[k].loose;
    out.refitted += !revert[k] && applied[k].around_axis;
  }
  for (const TopoDS_Edge& edge : loose) out.loosest_after = std::max(out.loosest_after, BRep_Tool::Tolerance(edge));
  return out;
}

}  // namespace steady
