#include "brep/sphere_pcurve.hpp"

#include <AdvApprox_ApproxAFunction.hxx>
#include <AdvApprox_EvaluatorFunction.hxx>
#include <TColStd_HArray1OfInteger.hxx>
#include <TColStd_HArray1OfReal.hxx>
#include <TColgp_Array1OfPnt2d.hxx>

#include <algorithm>
#include <stdexcept>

namespace steady {

namespace {

// Degree and segment limits of the approximation: degree 14 needs a handful of segments per circle at 1e-9.
constexpr int kMaxDegree = 14;
constexpr int kMaxSegments = 400;

class ArcEvaluator : public AdvApprox_EvaluatorFunction {
 public:
  ArcEvaluator(const SphereLayout& layout, int circle, ArcBranch branch)
      : layout_(layout), circle_(circle), branch_(branch) {}
  void Evaluate(Standard_Integer* /*dimension*/, Standard_Real /*range*/[2], Standard_Real* parameter,
                Standard_Integer* derivative, Standard_Real* result, Standard_Integer* error) override {
    layout_.uv(circle_, branch_, *parameter, result, *derivative);
    *error = 0;
  }

 private:
  const SphereLayout& layout_;
  int circle_;
  ArcBranch branch_;
};

}  // namespace

double sphere_pcurve_tolerance(double largest_radius) {
  if (!(largest_radius > 0.0)) return kSpherePcurveTolerance;
  return std::clamp(kSpherePcurve3dTolerance / largest_radius, kFinestSpherePcurveTolerance,
                    kCoarsestSpherePcurveTolerance);
}

ArcPcurve approximate_arc_pcurve(const SphereLayout& layout, int circle, const CircleArc& arc, double tolerance) {
  ArcEvaluator f(layout, circle, arc.branch);
  Handle(TColStd_HArray1OfReal) tol2d = new TColStd_HArray1OfReal(1, 1);
  tol2d->SetValue(1, tolerance);
  AdvApprox_ApproxAFunction approx(0, 1, 0, Handle(TColStd_HArray1OfReal)(), tol2d, Handle(TColStd_HArray1OfReal)(),
                                   arc.t0, arc.t1, GeomAbs_C2, kMaxDegree, kMaxSegments, f);
  if (!approx.HasResult()) throw std::runtime_error("sphere pcurve: the approximation of a circle arc failed");
  TColgp_Array1OfPnt2d poles(1, approx.NbPoles());
  approx.Poles2d(1, poles);
  ArcPcurve out;
  out.curve = new Geom2d_BSplineCurve(poles, approx.Knots()->Array1(), approx.Multiplicities()->Array1(),
                                      approx.Degree());
  out.max_error = approx.MaxError(2, 1);
  return out;
}

}  // namespace steady
