#include "brep/foreign_groups.hpp"

#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRep_Builder.hxx>
#include <TopExp_Explorer.hxx>

#include <utility>

namespace steady {

std::vector<CoreStump> member_stumps(const FlatLattice& f, const std::vector<BeamFrustum>& frustums, std::int64_t ball,
                                     const std::vector<std::pair<std::int64_t, int>>& stumps, const Mat3& rotation) {
  const double radius = f.balls[ball].radius;
  const Mat3 to_canonical = glm::transpose(rotation);
  std::vector<CoreStump> out;
  for (const auto& [e, end] : stumps) {
    const BeamFrustum& fr = frustums[e];
    CoreStump s;
    s.direction = glm::normalize(to_canonical * (end == 0 ? fr.cone.axis : -fr.cone.axis));
    s.exit = (end == 0 ? fr.exit_a : fr.exit_b) / radius;
    s.sin_phi = end == 0 ? fr.cone.sin_phi : -fr.cone.sin_phi;  // the cone as seen from this ball
    s.end_radius = (end == 0 ? f.beams[e].ra : f.beams[e].rb) / radius;
    out.push_back(s);
  }
  return out;
}

std::shared_ptr<const HubCore> lone_ball_core() {
  auto core = std::make_shared<HubCore>();
  core->kind = CoreKind::Transversal;
  const BRep_Builder b;
  b.MakeCompound(core->faces);
  for (TopExp_Explorer x(BRepPrimAPI_MakeSphere(gp_Pnt(0, 0, 0), 1.0).Shape(), TopAbs_FACE); x.More(); x.Next()) {
    b.Add(core->faces, x.Current());
    ++core->face_count;
  }
  return core;
}

CoreKind member_kind(const std::vector<CoreStump>& stumps) {
  for (const CoreStump& s : stumps)
    if (s.end_radius < 1.0 - 1e-12) return CoreKind::Transversal;
  return CoreKind::Hull;
}

double member_collar(double here, double there, double length, bool inner) {
  const double free = length - here - there;
  if (inner) return free > 0.0 ? here + 0.5 * free : here;
  return here + 0.25 * free;
}

}  // namespace steady
