#pragma once
// A CAD body prepared for trimming a lattice: a validated closed solid, with fast bounds on the distance from a
// point to its boundary (a triangulation in a CGAL AABB tree, off the true surface by at most its deflection),
// the exact distance (BRepExtrema) for the few points the bounds cannot decide, and point containment
// (BRepClass3d_SolidClassifier).
#include <TopoDS_Shape.hxx>
#include <TopoDS_Solid.hxx>

#include <memory>
#include <string>
#include <vector>

#include "steady/lattice/broad_phase.hpp"
#include "steady/core/vec.hpp"

namespace steady {

// The triangulation's deflection, relative to the body's bounding-box diagonal: fine enough that few hubs fall
// in the band where the exact distance is needed, coarse enough to mesh any CAD body in well under a second.
constexpr double kBodyMeshRelativeDeflection = 1e-3;
// Distances from the triangulation are trusted to this many deflections (BRepMesh keeps its chords within about
// one deflection of the surface; the factor covers its angular and edge-discretization slack).
constexpr double kBodyMeshDeflectionFactor = 4.0;

// The largest tolerance (of a vertex, edge or face) a body may carry, relative to its size: within its tolerance
// zone OpenCASCADE classifies points as on the boundary, and that zone must stay inside the slack of the distance
// bounds (kBodyMeshDeflectionFactor deflections, 4e-3 of the size) so that the exact tests decide there.
constexpr double kMaxBodyRelativeTolerance = 1e-3;

class SolidBody {
 public:
  // Validates `shape` (exactly one solid, valid, closed, positive volume); InvalidInput naming `field` otherwise.
  SolidBody(const TopoDS_Shape& shape, const std::string& field);
  ~SolidBody();
  SolidBody(SolidBody&&) noexcept;

  const TopoDS_Solid& solid() const { return solid_; }
  const Box& bounds() const { return bounds_; }
  double volume() const { return volume_; }
  double size() const { return glm::length(bounds_.hi - bounds_.lo); }

  // A lower bound of the distance from p to the boundary, fast (thread-safe).
  double distance_lower_bound(const Vec3& p) const;
  // A lower bound of the distance from p to the boundary's edges, seams and vertices, fast (thread-safe): where a
  // lattice meets the boundary farther than that from them, what it cuts out of the boundary lies inside faces.
  double edge_distance_lower_bound(const Vec3& p) const;
  // The distance from p to the boundary (BRepExtrema; serial).
  double exact_distance(const Vec3& p) const;
  // The points of the boundary nearest to p (BRepExtrema's solutions at the least distance, over every shell;
  // several where p lies on the medial axis; serial).
  std::vector<Vec3> nearest_points(const Vec3& p) const;
  // True when p lies inside (BRepClass3d; serial). Points within tolerance of the boundary count as inside.
  bool contains(const Vec3& p) const;

 private:
  void prepare(const TopoDS_Shape& shape, const std::string& field);
  void add_edge_segments();  // the edge tree, from the triangulation
  bool classifier_says_inside(const Vec3& p) const;
  // InvalidInput naming `field` when the classifier contradicts the body's own faces (see the definition).
  void check_classifier_consistent(const std::string& field) const;

  struct Tree;
  TopoDS_Solid solid_;
  Box bounds_;
  double volume_ = 0.0;
  double slack_ = 0.0;  // the triangulation's distance error bound
  std::unique_ptr<Tree> tree_;
};

}  // namespace steady
