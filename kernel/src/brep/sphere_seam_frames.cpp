#include "brep/sphere_seam_frames.hpp"

#include <gp_Ax3.hxx>
#include <gp_Pnt.hxx>
#include <gp_Vec.hxx>

#include <algorithm>
#include <cmath>

namespace steady {

namespace {

// Angle from the unit vector d to the half great circle from pole z through seam direction x to -z (the seam and
// its poles).
double angle_to_seam(const gp_Dir& d, const gp_Dir& z, const gp_Dir& x, const gp_Dir& normal) {
  if (d.Dot(x) >= 0.0) return std::asin(std::min(1.0, std::abs(d.Dot(normal))));
  return std::acos(std::min(1.0, std::abs(d.Dot(z))));
}

// A crossing must be transversal: the loop meets the seam at an angle whose sine is at least this. Points of a
// crossed loop farther than kNearCrossing (radians) from the crossing count toward the clearance.
constexpr double kMinCrossingSine = 0.25;
constexpr double kNearCrossing = 0.15;

// The frame's clearance and crossings; a clearance of -1 when a loop is crossed more than once or too obliquely.
SeamFrame evaluate(const std::vector<SampledLoop>& loops, const gp_Dir& z, const gp_Dir& x) {
  const gp_Dir normal = z.Crossed(x);
  SeamFrame frame;
  frame.pole = z;
  frame.seam = x;
  double clearance = M_PI;
  for (int li = 0; li < static_cast<int>(loops.size()); ++li) {
    const SampledLoop& loop = loops[li];
    const int n = static_cast<int>(loop.size());
    int crossings = 0, at = -1;
    gp_Vec crossing_point;
    for (int i = 0; i < n; ++i) {
      const LoopSample &a = loop[i], &b = loop[(i + 1) % n];
      const double sa = a.d.Dot(normal), sb = b.d.Dot(normal);
      if ((sa < 0.0) == (sb < 0.0)) continue;
      const double w = sa / (sa - sb);
      const gp_Vec p = gp_Vec(a.d) * (1.0 - w) + gp_Vec(b.d) * w;
      if (p.Dot(gp_Vec(x)) <= 0.0) continue;
      ++crossings, at = i, crossing_point = p;
    }
    if (crossings > 1) return {};
    if (crossings == 0) {
      for (const LoopSample& s : loop) clearance = std::min(clearance, angle_to_seam(s.d, z, x, normal));
      continue;
    }
    const LoopSample &a = loop[at], &b = loop[(at + 1) % n];
    const gp_Vec step = gp_Vec(b.d) - gp_Vec(a.d);
    if (a.edge != b.edge || step.Magnitude() == 0.0 ||
        std::abs(step.Dot(gp_Vec(normal))) < kMinCrossingSine * step.Magnitude())
      return {};
    const gp_Dir cross(crossing_point);
    for (int i = 0; i < n; ++i) {
      const LoopSample& s = loop[i];
      clearance = std::min(clearance, std::acos(std::min(1.0, std::abs(s.d.Dot(z)))));  // the poles
      if (s.d.Angle(cross) > kNearCrossing) clearance = std::min(clearance, angle_to_seam(s.d, z, x, normal));
      if (i == 0 || loop[i - 1].edge != s.edge) clearance = std::min(clearance, s.d.Angle(cross));  // vertices
    }
    frame.crossings.push_back({li, at});
  }
  frame.clearance = clearance;
  return frame;
}

}  // namespace

std::vector<SeamFrame> ranked_seam_frames(const std::vector<SampledLoop>& loops, double min_clearance) {
  constexpr int kFibonacci = 97, kSeams = 72;
  // Frames whose seam crosses no loop first, then by clearance.
  auto better = [min_clearance](const SeamFrame& a, const SeamFrame& b) {
    const bool a_clear = a.crossings.empty() && a.clearance >= min_clearance;
    const bool b_clear = b.crossings.empty() && b.clearance >= min_clearance;
    if (a_clear != b_clear) return a_clear;
    return a.clearance > b.clearance;
  };
  std::vector<SeamFrame> frames;
  for (int k = 0; k < kFibonacci; ++k) {
    const double z = 1.0 - (k + 0.5) / kFibonacci, r = std::sqrt(1.0 - z * z), a = k * 2.399963229728653;
    const gp_Dir pole(r * std::cos(a), r * std::sin(a), z);
    const gp_Ax3 around(gp_Pnt(0, 0, 0), pole);
    SeamFrame best;
    for (int j = 0; j < kSeams; ++j) {
      const double b = j * (2.0 * M_PI / kSeams);
      const gp_Dir seam = gp_Vec(around.XDirection()) * std::cos(b) + gp_Vec(around.YDirection()) * std::sin(b);
      SeamFrame frame = evaluate(loops, pole, seam);
      if (frame.clearance >= min_clearance && (best.clearance < 0.0 || better(frame, best))) best = std::move(frame);
    }
    if (best.clearance >= min_clearance) frames.push_back(std::move(best));
  }
  std::sort(frames.begin(), frames.end(), better);
  return frames;
}

}  // namespace steady
