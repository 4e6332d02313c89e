#include "brep/portable_sphere_faces.hpp"

#include <AdvApprox_ApproxAFunction.hxx>
#include <AdvApprox_EvaluatorFunction.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepClass_FaceClassifier.hxx>
#include <BRepTools.hxx>
#include <BRepTools_WireExplorer.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <ElSLib.hxx>
#include <Geom2d_BSplineCurve.hxx>
#include <Geom2d_Line.hxx>
#include <Geom_Curve.hxx>
#include <Geom_SphericalSurface.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Edge.hxx>
#include <TopoDS_Vertex.hxx>
#include <TopoDS_Wire.hxx>
#include <gp_Ax3.hxx>
#include <gp_Pnt2d.hxx>

#include <algorithm>
#include <cmath>
#include <unordered_set>
#include <vector>

#include "brep/sphere_pcurve.hpp"
#include "brep/sphere_seam_frames.hpp"

namespace steady {

namespace {

constexpr double kTwoPi = 2.0 * M_PI;

Handle(Geom_SphericalSurface) sphere_of(const TopoDS_Face& face) {
  return Handle(Geom_SphericalSurface)::DownCast(BRep_Tool::Surface(face));
}

// The face's edges that it uses twice: its seam (an edge that is closed on the sphere but bounds the face once,
// the face's side of a cut along the seam, is not one of them).
std::unordered_set<const void*> seam_edges(const TopoDS_Face& face) {
  std::unordered_set<const void*> once, twice;
  for (TopExp_Explorer x(face, TopAbs_EDGE); x.More(); x.Next())
    if (!once.insert(x.Current().TShape().get()).second) twice.insert(x.Current().TShape().get());
  return twice;
}

// A run of a wire's edges off the seam (in the wire's order, oriented as in the face), and whether the wire comes
// to it along the seam and goes on along the seam after it.
struct Run {
  std::vector<TopoDS_Edge> edges;
  bool from_seam = false, to_seam = false;
};

// The maximal runs of the face's wires (each followed in its own order, which says where loops touching at a
// vertex go), or false when a wire is reversed in the face.
bool wire_runs(const TopoDS_Face& face, std::vector<Run>& runs) {
  enum Kind { kOff, kSeam, kPole };
  const std::unordered_set<const void*> seam = seam_edges(face);
  for (TopExp_Explorer w(face, TopAbs_WIRE); w.More(); w.Next()) {
    if (w.Current().Orientation() != TopAbs_FORWARD) return false;
    std::vector<TopoDS_Edge> edges;
    std::vector<Kind> kinds;
    for (BRepTools_WireExplorer e(TopoDS::Wire(w.Current()), face); e.More(); e.Next()) {
      edges.push_back(e.Current());
      kinds.push_back(BRep_Tool::Degenerated(e.Current())           ? kPole
                      : seam.count(e.Current().TShape().get()) != 0 ? kSeam
                                                                     : kOff);
    }
    // Start after the last edge on the seam or a pole, so that no run wraps around the wire's end.
    const std::size_t n = edges.size();
    std::size_t start = 0;
    for (std::size_t i = 0; i < n; ++i)
      if (kinds[i] != kOff) start = i + 1;
    Kind previous = start == 0 ? kOff : kinds[start - 1];
    Run run;
    for (std::size_t k = 0; k < n; ++k) {
      const std::size_t i = (start + k) % n;
      if (kinds[i] == kOff) {
        if (run.edges.empty()) run.from_seam = previous == kSeam;
        run.edges.push_back(edges[i]);
      } else if (!run.edges.empty()) {
        run.to_seam = kinds[i] == kSeam;
        runs.push_back(std::move(run));
        run = Run();
      }
      previous = kinds[i];
    }
    if (!run.edges.empty()) runs.push_back(std::move(run));  // a wire that never meets the seam: one closed run
  }
  return true;
}

// The loops of a face as chains of its edges (seams and degenerate edges left out), or empty when they cannot be
// followed: where a wire runs along the seam, the chain goes on with the run that leaves the seam at the vertex
// where it met it.
std::vector<std::vector<TopoDS_Edge>> loops_of(const TopoDS_Face& face) {
  std::vector<Run> run_list;
  if (!wire_runs(face, run_list)) return {};
  std::vector<std::vector<TopoDS_Edge>> runs;
  for (Run& r : run_list) runs.push_back(std::move(r.edges));
  auto first = [](const std::vector<TopoDS_Edge>& r) { return TopExp::FirstVertex(r.front(), Standard_True); };
  auto last = [](const std::vector<TopoDS_Edge>& r) { return TopExp::LastVertex(r.back(), Standard_True); };
  std::vector<char> used(runs.size(), 0);
  std::vector<std::vector<TopoDS_Edge>> loops;
  for (std::size_t r = 0; r < runs.size(); ++r) {
    if (used[r]) continue;
    used[r] = 1;
    std::vector<TopoDS_Edge> loop = runs[r];
    while (!first(runs[r]).IsSame(last(loop))) {
      std::size_t next = runs.size();
      for (std::size_t q = 0; q < runs.size(); ++q)
        if (!used[q] && first(runs[q]).IsSame(last(loop))) {
          if (next != runs.size()) return {};  // two runs leave the seam at one vertex
          next = q;
        }
      if (next == runs.size()) return {};  // an open chain
      used[next] = 1;
      loop.insert(loop.end(), runs[next].begin(), runs[next].end());
    }
    loops.push_back(std::move(loop));
  }
  return loops;
}

// Samples along every loop, about one every 0.01 rad of the sphere (at least 16 an edge), each edge's ends
// included; empty when an edge has no 3D curve.
std::vector<SampledLoop> sample_loops(const std::vector<std::vector<TopoDS_Edge>>& loops, const gp_Pnt& centre,
                                      double radius) {
  std::vector<SampledLoop> out;
  for (const auto& loop : loops) {
    SampledLoop sampled;
    for (int i = 0; i < static_cast<int>(loop.size()); ++i) {
      Standard_Real t0, t1;
      const Handle(Geom_Curve) c = BRep_Tool::Curve(loop[i], t0, t1);
      if (c.IsNull()) return {};
      const bool reversed = loop[i].Orientation() == TopAbs_REVERSED;
      const gp_Pnt middle = c->Value(0.5 * (t0 + t1));
      const double chord = c->Value(t0).Distance(middle) + c->Value(t1).Distance(middle);
      const int n = std::clamp(static_cast<int>(std::ceil(chord / radius / 0.01)), 16, 4096);
      for (int k = 0; k <= n; ++k) {
        const double t = reversed ? t1 + (t0 - t1) * k / n : t0 + (t1 - t0) * k / n;
        const gp_Vec v(centre, c->Value(t));
        if (v.Magnitude() < 0.5 * radius) return {};
        sampled.push_back({gp_Dir(v), i, t});
      }
    }
    out.push_back(std::move(sampled));
  }
  return out;
}

// (u, v) of a 3D curve on the sphere of `frame`, with the curve's own parameter, and their first two derivatives.
// u is continuous along the curve, which never crosses the seam (it may end on it): it is taken nearest to a table
// unwrapped from the curve's middle, where it lies in (0, 2 pi).
class CurveOnSphere : public AdvApprox_EvaluatorFunction {
 public:
  CurveOnSphere(const Handle(Geom_Curve)& curve, double t0, double t1, const gp_Ax3& frame, double radius)
      : curve_(curve), frame_(frame), radius_(radius), t0_(t0), t1_(t1) {
    constexpr int kTable = 256;
    us_.resize(kTable + 1);
    const int mid = kTable / 2;
    us_[mid] = std::fmod(raw_u(t_at(mid)) + kTwoPi, kTwoPi);
    for (int k = mid + 1; k <= kTable; ++k) us_[k] = nearest(raw_u(t_at(k)), us_[k - 1]);
    for (int k = mid - 1; k >= 0; --k) us_[k] = nearest(raw_u(t_at(k)), us_[k + 1]);
  }
  void Evaluate(Standard_Integer* /*dimension*/, Standard_Real /*range*/[2], Standard_Real* parameter,
                Standard_Integer* derivative, Standard_Real* result, Standard_Integer* error) override {
    gp_Pnt p;
    gp_Vec d1, d2;
    curve_->D2(*parameter, p, d1, d2);
    const gp_Vec r(frame_.Location(), p);
    const gp_Vec X(frame_.XDirection()), Y(frame_.YDirection()), Z(frame_.Direction());
    const double x = r.Dot(X), y = r.Dot(Y), z = std::clamp(r.Dot(Z), -radius_, radius_);
    const double x1 = d1.Dot(X), y1 = d1.Dot(Y), z1 = d1.Dot(Z), x2 = d2.Dot(X), y2 = d2.Dot(Y), z2 = d2.Dot(Z);
    const double rho2 = x * x + y * y, s = std::sqrt(std::max(radius_ * radius_ - z * z, 1e-300));
    *error = 0;
    switch (*derivative) {
      case 0:
        result[0] = nearest(std::atan2(y, x), table_u(*parameter));
        result[1] = std::asin(z / radius_);
        break;
      case 1:
        result[0] = (x * y1 - y * x1) / rho2;
        result[1] = z1 / s;
        break;
      case 2: {
        const double w = x * y1 - y * x1, w1 = x * y2 - y * x2, rho2_1 = 2.0 * (x * x1 + y * y1);
        result[0] = (w1 * rho2 - w * rho2_1) / (rho2 * rho2);
        result[1] = z2 / s + z * z1 * z1 / (s * s * s);
        break;
      }
      default:
        *error = 1;
    }
  }

 private:
  double t_at(int k) const { return t0_ + (t1_ - t0_) * k / (static_cast<int>(us_.size()) - 1); }
  double raw_u(double t) const {
    const gp_Vec r(frame_.Location(), curve_->Value(t));
    return std::atan2(r.Dot(gp_Vec(frame_.YDirection())), r.Dot(gp_Vec(frame_.XDirection())));
  }
  static double nearest(double u, double reference) {
    return u + kTwoPi * std::round((reference - u) / kTwoPi);
  }
  double table_u(double t) const {
    const double at = std::clamp((t - t0_) / (t1_ - t0_), 0.0, 1.0) * (static_cast<int>(us_.size()) - 1);
    const int k = std::min(static_cast<int>(at), static_cast<int>(us_.size()) - 2);
    return us_[k] + (us_[k + 1] - us_[k]) * (at - k);
  }

  Handle(Geom_Curve) curve_;
  gp_Ax3 frame_;
  double radius_, t0_, t1_;
  std::vector<double> us_;
};

// The edge's (u, v) curve on the sphere of `frame`, to sphere_pcurve_tolerance(radius), or null.
Handle(Geom2d_BSplineCurve) pcurve_on(const TopoDS_Edge& edge, const gp_Ax3& frame, double radius,
                                      double& max_error) {
  Standard_Real t0, t1;
  const Handle(Geom_Curve) c = BRep_Tool::Curve(edge, t0, t1);
  if (c.IsNull()) return nullptr;
  CurveOnSphere f(c, t0, t1, frame, radius);
  Handle(TColStd_HArray1OfReal) tolerance = new TColStd_HArray1OfReal(1, 1);
  tolerance->SetValue(1, sphere_pcurve_tolerance(radius));
  AdvApprox_ApproxAFunction approx(0, 1, 0, Handle(TColStd_HArray1OfReal)(), tolerance,
                                   Handle(TColStd_HArray1OfReal)(), t0, t1, GeomAbs_C2, 14, 400, f);
  if (!approx.HasResult()) return nullptr;
  TColgp_Array1OfPnt2d poles(1, approx.NbPoles());
  approx.Poles2d(1, poles);
  max_error = approx.MaxError(2, 1);
  return new Geom2d_BSplineCurve(poles, approx.Knots()->Array1(), approx.Multiplicities()->Array1(),
                                 approx.Degree());
}

// Where the point of the sphere in direction `d` lies with respect to a face: its (u, v), taken into the face's
// own u range (a Boolean's face may run from -2 to 4), classified against the face's (u, v) curves. The range is
// found once per face.
class SphereClassifier {
 public:
  explicit SphereClassifier(const TopoDS_Face& face) : face_(face), sphere_(sphere_of(face)) {
    double umax, vmin, vmax;
    BRepTools::UVBounds(face, umin_, umax, vmin, vmax);
  }
  TopAbs_State at(const gp_Dir& d) const {
    const gp_Pnt p = sphere_->Location().Translated(gp_Vec(d) * sphere_->Radius());
    double u, v;
    ElSLib::SphereParameters(sphere_->Position(), sphere_->Radius(), p, u, v);
    u += kTwoPi * std::floor((umin_ - u) / kTwoPi + 1.0);  // in [umin, umin + 2 pi)
    if (u - kTwoPi >= umin_ - 1e-12) u -= kTwoPi;
    return BRepClass_FaceClassifier(face_, gp_Pnt2d(u, v), 1e-9).State();
  }

 private:
  TopoDS_Face face_;
  Handle(Geom_SphericalSurface) sphere_;
  double umin_ = 0.0;
};

// Whether the twin covers the same part of the sphere as the face: the two agree at 256 points spread over the
// sphere (a point on a boundary, by either, left out).
bool same_region(const TopoDS_Face& face, const TopoDS_Face& twin) {
  constexpr int kPoints = 256;
  const SphereClassifier before(face), after(twin);
  for (int k = 0; k < kPoints; ++k) {
    const double z = 1.0 - (2.0 * k + 1.0) / kPoints, r = std::sqrt(1.0 - z * z), a = k * 2.399963229728653;
    const gp_Dir d(r * std::cos(a), r * std::sin(a), z);
    const TopAbs_State s0 = before.at(d), s1 = after.at(d);
    if (s0 == TopAbs_ON || s1 == TopAbs_ON) continue;
    if (s0 != s1) return false;
  }
  return true;
}

// Clearance (radians) the seam and poles keep from every loop (away from where the seam crosses one): enough for
// the classification of a pole to be sure and for the sampled loops not to hide a crossing.
constexpr double kMinClearance = 0.02;
constexpr int kFramesTried = 4;

// An edge of a loop cut in two where the seam crosses it (both pieces forward, sharing the new vertex).
struct SplitEdge {
  TopoDS_Edge whole, first, second;
};

// Cuts the loop's edge holding samples `at` and `at + 1` where it meets the seam's plane (through `centre`, of
// normal `normal`): the loop then starts at the new vertex. False when the edge is placed (its pieces could not
// share its vertices as they are) or its curves do not share one parameter.
bool split_at_seam(std::vector<TopoDS_Edge>& loop, const SampledLoop& samples, int at, const gp_Pnt& centre,
                   const gp_Dir& normal, std::vector<SplitEdge>& splits) {
  const int i = samples[at].edge;
  const TopoDS_Edge& edge = loop[i];
  // Both pieces keep every curve of the edge on their part of its range: the curves must share the parameter.
  if (!edge.Location().IsIdentity() || !BRep_Tool::SameParameter(edge) || !BRep_Tool::SameRange(edge)) return false;
  Standard_Real t0, t1;
  const Handle(Geom_Curve) c = BRep_Tool::Curve(edge, t0, t1);
  auto side = [&](double t) { return gp_Vec(centre, c->Value(t)).Dot(gp_Vec(normal)); };
  double ta = samples[at].t, tb = samples[at + 1].t;
  const bool a_negative = side(ta) < 0.0;
  for (int k = 0; k < 100 && ta != tb; ++k) {
    const double tm = 0.5 * (ta + tb);
    if ((side(tm) < 0.0) == a_negative) ta = tm; else tb = tm;
  }
  const double t = 0.5 * (ta + tb);
  BRep_Builder b;
  const double tolerance = BRep_Tool::Tolerance(edge);
  TopoDS_Vertex cut;
  b.MakeVertex(cut, c->Value(t), tolerance);
  const TopoDS_Edge forward = TopoDS::Edge(edge.Oriented(TopAbs_FORWARD));
  TopoDS_Vertex v0, v1;
  TopExp::Vertices(forward, v0, v1);
  SplitEdge split{forward, TopoDS::Edge(forward.EmptyCopied()), TopoDS::Edge(forward.EmptyCopied())};
  b.Add(split.first, v0.Oriented(TopAbs_FORWARD));
  b.Add(split.first, cut.Oriented(TopAbs_REVERSED));
  b.Range(split.first, t0, t);
  b.Add(split.second, cut.Oriented(TopAbs_FORWARD));
  b.Add(split.second, v1.Oriented(TopAbs_REVERSED));
  b.Range(split.second, t, t1);
  b.UpdateVertex(cut, t, split.first, tolerance);
  // The loop from the cut: the piece leaving it, the rest of the loop, the piece coming back to it.
  const bool reversed = edge.Orientation() == TopAbs_REVERSED;
  const TopoDS_Edge leaving = reversed ? TopoDS::Edge(split.first.Reversed()) : split.second;
  const TopoDS_Edge arriving = reversed ? TopoDS::Edge(split.second.Reversed()) : split.first;
  std::vector<TopoDS_Edge> from_cut = {leaving};
  for (std::size_t k = 1; k < loop.size(); ++k) from_cut.push_back(loop[(i + k) % loop.size()]);
  from_cut.push_back(arriving);
  loop = std::move(from_cut);
  splits.push_back(split);
  return true;
}

// The sphere's seam from latitude v0 to v1 (its 3D meridian, u = 2 pi for the edge forward, u = 0 reversed), or a
// degenerate edge at a pole (v = -pi/2 or pi/2, u from 0 to 2 pi).
TopoDS_Edge seam_edge(const Handle(Geom_SphericalSurface)& surface, const TopoDS_Face& twin, double v0, double v1,
                      const TopoDS_Vertex& from, const TopoDS_Vertex& to) {
  BRep_Builder b;
  TopoDS_Edge e;
  b.MakeEdge(e, surface->UIso(0.0), 1e-7);
  b.UpdateEdge(e, new Geom2d_Line(gp_Pnt2d(kTwoPi, 0.0), gp_Dir2d(0.0, 1.0)),
               new Geom2d_Line(gp_Pnt2d(0.0, 0.0), gp_Dir2d(0.0, 1.0)), twin, 1e-7);
  b.Range(e, v0, v1);
  b.Add(e, from.Oriented(TopAbs_FORWARD));
  b.Add(e, to.Oriented(TopAbs_REVERSED));
  return e;
}
TopoDS_Edge pole_edge(const TopoDS_Face& twin, double v, const TopoDS_Vertex& pole) {
  BRep_Builder b;
  TopoDS_Edge e;
  b.MakeEdge(e);
  b.UpdateEdge(e, new Geom2d_Line(gp_Pnt2d(0.0, v), gp_Dir2d(1.0, 0.0)), twin, 1e-7);
  b.Range(e, 0.0, kTwoPi);
  b.Add(e, pole.Oriented(TopAbs_FORWARD));
  b.Add(e, pole.Oriented(TopAbs_REVERSED));
  b.Degenerated(e, Standard_True);
  return e;
}

// Where the seam runs in the face: from its lower end (the south pole, or the loop it crosses there) to its upper
// end; loop indices -1 at a pole.
struct SeamInFace {
  bool present = false;
  int lower_loop = -1, upper_loop = -1;
};

// From the poles' places (in the face or not) and the crossed loops (by latitude): where the seam runs in the face,
// or false when they do not fit (a loop crossed by a seam whose poles are both in the face).
bool seam_in_face(TopAbs_State south, TopAbs_State north, std::vector<std::pair<double, int>> crossed,
                  SeamInFace& out) {
  std::sort(crossed.begin(), crossed.end());
  const bool s_in = south == TopAbs_IN, n_in = north == TopAbs_IN;
  if (crossed.empty()) {
    if (s_in != n_in) return false;
    out.present = s_in;
    return true;
  }
  out.present = true;
  if (crossed.size() == 1 && s_in != n_in) {
    (s_in ? out.upper_loop : out.lower_loop) = crossed[0].second;
    return true;
  }
  if (crossed.size() == 2 && !s_in && !n_in) {
    out.lower_loop = crossed[0].second;
    out.upper_loop = crossed[1].second;
    return true;
  }
  return false;
}

// The latitude of point p on the sphere of `frame`.
double latitude(const gp_Ax3& frame, const gp_Pnt& p) {
  const gp_Vec at(frame.Location(), p);
  return std::asin(std::clamp(at.Dot(gp_Vec(frame.Direction())) / at.Magnitude(), -1.0, 1.0));
}

// The twin of `face` on `frame`, or a null face and why not. Adds the split edges to `splits`.
TopoDS_Face twin_on(const TopoDS_Face& face, const SeamFrame& fr, const gp_Ax3& frame, double radius,
                    std::vector<std::vector<TopoDS_Edge>> loops, const std::vector<SampledLoop>& samples,
                    const BRepTools_ReShape& reshape, std::vector<SplitEdge>& splits, std::string& why_not) {
  const gp_Pnt centre = frame.Location();
  const gp_Dir normal = gp_Dir(fr.pole).Crossed(fr.seam);
  std::vector<std::pair<double, int>> crossed;  // latitude, loop
  for (const SeamCrossing& c : fr.crossings) {
    const TopoDS_Edge& edge = loops[c.loop][samples[c.loop][c.at].edge];
    if (reshape.IsRecorded(edge.Oriented(TopAbs_FORWARD)) ||
        !split_at_seam(loops[c.loop], samples[c.loop], c.at, centre, normal, splits)) {
      why_not = "the seam would cross an edge already cut or placed";
      return {};
    }
    const TopoDS_Vertex cut = TopExp::FirstVertex(loops[c.loop].front(), Standard_True);
    crossed.emplace_back(latitude(frame, BRep_Tool::Pnt(cut)), c.loop);
  }
  SeamInFace seam;
  const SphereClassifier in_face(face);
  if (!seam_in_face(in_face.at(frame.Direction().Reversed()), in_face.at(frame.Direction()), crossed, seam)) {
    why_not = "the poles and the crossed loops do not fit together";
    return {};
  }
  BRep_Builder b;
  const Handle(Geom_SphericalSurface) surface = new Geom_SphericalSurface(frame, radius);
  TopoDS_Face twin;
  b.MakeFace(twin, surface, BRep_Tool::Tolerance(face));
  std::vector<TopoDS_Wire> wires(loops.size());
  for (std::size_t l = 0; l < loops.size(); ++l) {
    b.MakeWire(wires[l]);
    for (const TopoDS_Edge& e : loops[l]) {
      double error = 0.0;
      const Handle(Geom2d_BSplineCurve) pc = pcurve_on(e, frame, radius, error);
      if (pc.IsNull()) {
        why_not = "a (u, v) curve could not be approximated";
        return {};
      }
      b.UpdateEdge(e, pc, twin, std::max(BRep_Tool::Tolerance(e), 2.0 * error * radius));
      b.Add(wires[l], e);
    }
  }
  if (seam.present) {
    // Up the side u = 2 pi from the lower end, the upper end from u = 2 pi to 0, down the side u = 0.
    TopoDS_Wire outer;
    b.MakeWire(outer);
    TopoDS_Vertex from, to;
    double v0 = -M_PI / 2, v1 = M_PI / 2;
    auto pole_vertex = [&](double v) {
      TopoDS_Vertex pole;
      b.MakeVertex(pole, surface->Value(0.0, v), 1e-7);
      return pole;
    };
    auto loop_start = [&](int l, double& v) {
      const TopoDS_Vertex start = TopExp::FirstVertex(loops[l].front(), Standard_True);
      v = latitude(frame, BRep_Tool::Pnt(start));
      return start;
    };
    from = seam.lower_loop < 0 ? pole_vertex(v0) : loop_start(seam.lower_loop, v0);
    to = seam.upper_loop < 0 ? pole_vertex(v1) : loop_start(seam.upper_loop, v1);
    const TopoDS_Edge side = seam_edge(surface, twin, v0, v1, from, to);
    auto add_end = [&](int l, double v, const TopoDS_Vertex& pole, bool reversed) {
      if (l >= 0) {
        for (TopExp_Explorer e(wires[l], TopAbs_EDGE); e.More(); e.Next()) b.Add(outer, e.Current());
      } else {
        const TopoDS_Edge e = pole_edge(twin, v, pole);
        b.Add(outer, reversed ? e.Reversed() : TopoDS_Shape(e));
      }
    };
    add_end(seam.lower_loop, v0, from, false);
    b.Add(outer, side);
    add_end(seam.upper_loop, v1, to, true);
    b.Add(outer, side.Reversed());
    outer.Closed(Standard_True);
    b.Add(twin, outer);
  }
  for (std::size_t l = 0; l < loops.size(); ++l) {
    if (static_cast<int>(l) == seam.lower_loop || static_cast<int>(l) == seam.upper_loop) continue;
    wires[l].Closed(Standard_True);
    b.Add(twin, wires[l]);
  }
  return twin;
}

// The face (forward) rebuilt on a portable frame, recording the edges it cut in `reshape`; or a null face and why
// not.
TopoDS_Face portable_twin(const TopoDS_Face& face, BRepTools_ReShape& reshape, bool& through_loops,
                          std::string& why_not) {
  const Handle(Geom_SphericalSurface) sphere = sphere_of(face);
  const gp_Ax3 old_frame = sphere->Position();
  const double radius = sphere->Radius();
  const auto loops = loops_of(face);
  if (loops.empty()) {
    why_not = "its loops could not be followed across the seam";
    return {};
  }
  const std::vector<SampledLoop> samples = sample_loops(loops, old_frame.Location(), radius);
  if (samples.empty()) {
    why_not = "an edge has no 3D curve, or is far from the sphere";
    return {};
  }
  const std::vector<SeamFrame> frames = ranked_seam_frames(samples, kMinClearance);
  why_not = "no frame leaves " + std::to_string(kMinClearance) + " rad between the seam and the loops";
  for (int k = 0; k < kFramesTried && k < static_cast<int>(frames.size()); ++k) {
    const SeamFrame& fr = frames[k];
    gp_Ax3 frame(old_frame.Location(), fr.pole, fr.seam);
    if (!old_frame.Direct()) frame.YReverse();  // the same normal, so the face keeps its orientation
    std::vector<SplitEdge> splits;
    const TopoDS_Face twin = twin_on(face, fr, frame, radius, loops, samples, reshape, splits, why_not);
    if (twin.IsNull()) continue;
    if (!BRepCheck_Analyzer(twin, Standard_True).IsValid()) {
      why_not = "the rebuilt face is invalid";
      continue;
    }
    if (has_chain_across_seam(twin)) {
      why_not = "the rebuilt face still has a chain across its seam";
      continue;
    }
    if (!same_region(face, twin)) {
      why_not = "the rebuilt face covers another part of the sphere";
      continue;
    }
    BRep_Builder b;
    for (const SplitEdge& split : splits) {
      TopoDS_Compound pieces;
      b.MakeCompound(pieces);
      b.Add(pieces, split.first);
      b.Add(pieces, split.second);
      reshape.Replace(split.whole, pieces);
    }
    through_loops = !fr.crossings.empty();
    return twin;
  }
  return {};
}

}  // namespace

bool has_chain_across_seam(const TopoDS_Face& any_face) {
  if (sphere_of(any_face).IsNull()) return false;
  const TopoDS_Face face = TopoDS::Face(any_face.Oriented(TopAbs_FORWARD));
  constexpr double kOnSeam = 1e-9;
  // The side of the seam a point on it lies on: which multiple of 2 pi its u is; none off the seam.
  auto side_of = [&](const gp_Pnt2d& p, long& side) {
    const double turns = std::round(p.X() / kTwoPi);
    side = static_cast<long>(turns);
    return std::abs(p.X() - turns * kTwoPi) < kOnSeam;
  };
  std::vector<Run> runs;
  if (!wire_runs(face, runs)) return false;
  auto end_point = [&](const TopoDS_Edge& edge, bool at_start) {
    Standard_Real t0, t1;
    const Handle(Geom2d_Curve) pcurve = BRep_Tool::CurveOnSurface(edge, face, t0, t1);
    if (pcurve.IsNull()) return gp_Pnt2d(0.5, 0.0);  // off the seam: no verdict on this run
    return pcurve->Value(at_start == (edge.Orientation() != TopAbs_REVERSED) ? t0 : t1);
  };
  for (const Run& run : runs) {
    if (!run.from_seam || !run.to_seam) continue;
    const gp_Pnt2d start = end_point(run.edges.front(), true), end = end_point(run.edges.back(), false);
    long start_side = 0, end_side = 0;
    if (side_of(start, start_side) && side_of(end, end_side) && start_side == end_side &&
        std::abs(end.Y() - start.Y()) > kOnSeam)
      return true;
  }
  return false;
}

PortableSphereFaces reseat_sphere_faces(const TopoDS_Shape& shape, BRepTools_ReShape& reshape) {
  PortableSphereFaces out;
  TopTools_IndexedMapOfShape faces;
  TopExp::MapShapes(shape, TopAbs_FACE, faces);
  for (int i = 1; i <= faces.Extent(); ++i) {
    const TopoDS_Face face = TopoDS::Face(faces(i));
    if (!has_chain_across_seam(face)) continue;
    std::string why_not;
    bool through_loops = false;
    const TopoDS_Face twin =
        portable_twin(TopoDS::Face(face.Oriented(TopAbs_FORWARD)), reshape, through_loops, why_not);
    if (twin.IsNull()) {
      if (out.kept++ == 0) out.kept_reason = why_not;
      continue;
    }
    reshape.Replace(face.Oriented(TopAbs_FORWARD), twin);
    ++out.reseated;
    out.seam_through_loops += through_loops;
  }
  return out;
}

}  // namespace steady
