#pragma once
// Orientation-preserving similarities of 3D space: p -> s R p + t, with s > 0 and R a rotation.
//
// A similarity is stored by its *generator* xi = (sigma, omega, v): log-scale sigma = ln s, rotation
// vector omega = angle * axis, and velocity v, with S = exp(xi) in the similarity group. Real powers
// are then exact and uniform, S^t = exp(t xi), whatever the kind (translation, rotation, screw,
// dilation, swirl), and they stay accurate through s = 1 and angle 0 where the fixed-point formulas of
// the papers divide by zero. The generator also keeps the *winding*: a rotation by 3 pi, or by exactly
// 2 pi about an axis that misses the origin, keeps its angle and axis, so its fractional powers are the
// ones the designer meant. The group element (s, R, t) is cached for application to points.
#include <string>

#include "steady/core/ball.hpp"
#include "steady/core/frame.hpp"
#include "steady/core/vec.hpp"

namespace steady {

// The group element of a similarity in matrix form, p -> scale * rotation * p + translation: what the
// lattice's inner loops compose and apply (no logarithm is taken).
struct SimilarityTransform {
  double scale = 1.0;
  Mat3 rotation{1.0};
  Vec3 translation{0.0};

  Vec3 apply_point(const Vec3& p) const { return scale * (rotation * p) + translation; }
  Vec3 apply_vector(const Vec3& v) const { return scale * (rotation * v); }
  Ball apply(const Ball& b) const { return {apply_point(b.center), scale * b.radius}; }
  SimilarityTransform operator*(const SimilarityTransform& rhs) const {
    return {scale * rhs.scale, rotation * rhs.rotation, scale * (rotation * rhs.translation) + translation};
  }
};

enum class SimilarityKind { Identity, Translation, Rotation, Screw, Dilation, Swirl };
const char* to_string(SimilarityKind kind);

// The canonical decomposition S = (rotation about an axis through F) o (translation along the axis, or
// dilation about F), the two parts commuting. Which fields are meaningful depends on the kind:
//   Identity     nothing
//   Translation  translation
//   Rotation     angle, axis, point            (point: the axis point closest to the origin)
//   Screw        angle, axis, point, distance  (distance: translation along the axis)
//   Dilation     scale, point                  (point: the fixed point)
//   Swirl        scale, angle, axis, point     (point: the fixed point)
// The angle is >= 0 (the axis carries the sense); it exceeds pi only when the similarity was built with
// a winding angle (see the header comment).
struct CanonicalForm {
  SimilarityKind kind = SimilarityKind::Identity;
  double scale = 1.0;
  double angle = 0.0;
  Vec3 axis{0.0, 0.0, 1.0};
  Vec3 point{0.0};
  double distance = 0.0;
  Vec3 translation{0.0};
};

class Similarity {
 public:
  Similarity();  // identity

  static Similarity identity();
  static Similarity translation(const Vec3& vector);
  // Rotation by `angle` radians (any real: windings are kept) about the line through `point` along `axis`
  // (right-hand rule).
  static Similarity rotation(double angle, const Vec3& axis, const Vec3& point);
  static Similarity dilation(double scale, const Vec3& center);
  // Rotation about the line (point, axis) followed by a translation of `distance` along the unit axis.
  static Similarity screw(double angle, const Vec3& axis, const Vec3& point, double distance);
  // Rotation about the line (center, axis) and dilation by `scale` about `center`.
  static Similarity swirl(double angle, const Vec3& axis, const Vec3& center, double scale);
  // The exponential of the generator (sigma, omega, v).
  static Similarity from_generator(double log_scale, const Vec3& rotation_vector, const Vec3& velocity);
  // From the matrix form p -> scale * rotation * p + translation; the rotation matrix must be orthonormal
  // (to kFrameTolerance). The recovered angle is in [0, pi].
  static Similarity from_matrix(double scale, const Mat3& rotation, const Vec3& translation);
  // The similarity taking the unit frame to `frame`.
  static Similarity from_frame(const Frame& frame);
  // The similarity taking frame `a` to frame `b` (so that from_frame(b) = S * from_frame(a)).
  // Robust where Appendix A of the steady-lattices paper fails: any axis, negative angles, no rotation,
  // s = 1. The angle is in [0, pi]: frames cannot encode more than a half turn.
  static Similarity from_frames(const Frame& a, const Frame& b);
  // The principal similarity of a matrix-form transform (angle in [0, pi]).
  static Similarity from_transform(const SimilarityTransform& t);

  // Composition: (S * T)(p) = S(T(p)): apply T first.
  Similarity operator*(const Similarity& rhs) const;
  Similarity inverse() const;
  // The real power S^t in closed form. S^0 is the identity, S^-1 the inverse.
  Similarity power(double t) const;

  Vec3 apply_point(const Vec3& p) const { return scale_ * (rotation_ * p) + translation_; }
  Vec3 apply_vector(const Vec3& v) const { return scale_ * (rotation_ * v); }
  Ball apply(const Ball& b) const { return {apply_point(b.center), scale_ * b.radius}; }
  // The image of the unit frame.
  Frame frame() const;

  SimilarityTransform transform() const { return {scale_, rotation_, translation_}; }
  double scale() const { return scale_; }
  const Mat3& rotation_matrix() const { return rotation_; }
  const Vec3& translation_part() const { return translation_; }

  double log_scale() const { return log_scale_; }
  const Vec3& rotation_vector() const { return rotation_vector_; }
  const Vec3& velocity() const { return velocity_; }

  CanonicalForm canonical() const;
  SimilarityKind kind() const { return canonical().kind; }
  std::string describe() const;

  // True when the two similarities move every point of the ball (center, radius) by at most
  // tolerance * (1 + radius + |center|), compared as maps (windings are not compared).
  bool approx_equal(const Similarity& other, double tolerance, const Vec3& center = Vec3(0.0),
                    double radius = 1.0) const;
  // Largest distance between the images of the unit frame's origin and tips under the two maps.
  double map_distance(const Similarity& other) const;

 private:
  void cache_group_element();

  // generator
  double log_scale_ = 0.0;
  Vec3 rotation_vector_{0.0};
  Vec3 velocity_{0.0};
  // group element exp(generator)
  double scale_ = 1.0;
  Mat3 rotation_{1.0};
  Vec3 translation_{0.0};
};

}  // namespace steady
