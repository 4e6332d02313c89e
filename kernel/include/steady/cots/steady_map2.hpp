#pragma once
// Steady 2-maps and the rectified steady slab lattices on them (constructive-lattice-geometry, 2.6.4 to 2.6.6 and
// chapter 3). The map M(u, v) = V^v o U^u (O) takes the unit square to a warped one; its iso-curves are helices or
// conchospirals. Unlike a COTS map, U and V need not commute, so tiles are similar only along V (tiles of one
// column), and a warped slab is not a steady lattice until it is rectified: only the template group is warped and
// replaced by true balls (template rectification, 3.4), and every group is then a copy of it placed by the field,
// group (i, j) = V^{j/nv} o U^{i/nu} (template). The result is an ordinary Lattice.
#include <string>
#include <vector>

#include "steady/core/frame.hpp"
#include "steady/core/similarity.hpp"
#include "steady/lattice/lattice.hpp"

namespace steady {

// How a warped template ball becomes a true ball (3.4): the sphere through the images of four points at a regular
// tetrahedron's vertices, or the least-squares sphere through the images of 64 points spread evenly over the ball
// (antipodal pairs: where the map is linear, an ellipsoid, its fit is centred on the warped centre).
enum class Rectification { FourPoints, LeastSquares };

class SteadyMap2 {
 public:
  // The planar map through five points of the plane z = 0: M(0,0) = a, M(1,0) = b, M(0,1) = c, M(1,1) = d and
  // M(1/2, 0) = e (10 degrees of freedom: no 3D map goes through five arbitrary points). U = Similarity(a->e,
  // e->b)^2 and V = Similarity(a->c, b->d). InvalidInput naming the points when a NaN is given or two of them
  // coincide where a similarity needs them apart (a and e, e and b, a and b, c and d).
  static SteadyMap2 from_points(const Vec2& a, const Vec2& b, const Vec2& c, const Vec2& d, const Vec2& e);
  // The 3D map of three frames: U takes frame a to b, V takes a to c, O is a's origin, so M(1,0) and M(0,1) are
  // the origins of b and c. InvalidInput naming the frame when one is not a scaled orthonormal right-handed
  // basis. (A frame fixes a rotation up to a half turn: Similarity::from_frames.)
  static SteadyMap2 from_frames(const Frame& a, const Frame& b, const Frame& c);

  // The field S(u, v) = V^v o U^u (U applied first), and the map M(u, v) = S(u, v)(O).
  Similarity field(double u, double v) const;
  Vec3 map(double u, double v) const { return field(u, v).apply_point(origin_); }
  // A point (u, v, w) of the slab's domain: S(u, v)(O + w L n), with n the normal at O (planar: +z; frames: a's
  // z axis) and L = |M(1,0) - M(0,0)| the length of the domain's unit at O.
  Vec3 warp(const Vec3& uvw) const;
  // Template rectification (3.4) of the domain ball (center, radius in the domain's units): the sphere through the
  // images under warp() of points of it, chosen by `method`. InvalidInput naming `field` when the radius is not
  // positive or the images are flat (the warp folds there).
  Ball rectify(const Vec3& center, double radius, const std::string& field = "radius",
               Rectification method = Rectification::FourPoints) const;

  const Similarity& u() const { return u_; }
  const Similarity& v() const { return v_; }
  const Vec3& origin() const { return origin_; }
  const Vec3& normal() const { return normal_; }
  double unit() const { return unit_; }

 private:
  SteadyMap2(const Similarity& u, const Similarity& v, const Vec3& origin, const Vec3& normal);
  Similarity u_, v_;
  Vec3 origin_{0.0}, normal_{0.0, 0.0, 1.0};
  double unit_ = 1.0;
};

// The rectified steady slab on `map`: counts.u x counts.v groups in one layer (counts.w must be 1). Node n of the
// template group is the rectification of the domain ball at (s / nu, t / nv, w), radius r (s, t in tile units,
// w and r in units of L), with nodes[n] = {(s, t, w), r}, rectified by `method`; group (i, j) is V^{j/nv} o
// U^{i/nu} of the template.
// Beams are the hull of their balls or, with beam_ratio in (0, 1], cones of beam_ratio times their balls' radii.
Lattice steady_slab_lattice(const SteadyMap2& map, const std::vector<TemplateNode>& nodes,
                            std::vector<BeamPattern> beams, const Counts& counts, double beam_ratio = 0.0,
                            Rectification method = Rectification::FourPoints);

}  // namespace steady
