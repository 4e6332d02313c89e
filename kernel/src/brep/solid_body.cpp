#include "steady/brep/solid_body.hpp"

#include <BRepBndLib.hxx>
#include <BRepBuilderAPI_Copy.hxx>
#include <BRepBuilderAPI_MakeVertex.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepMesh_IncrementalMesh.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <CGAL/AABB_traits.h>
#include <CGAL/AABB_tree.h>
#include <CGAL/AABB_segment_primitive.h>
#include <CGAL/AABB_triangle_primitive.h>
#include <CGAL/Simple_cartesian.h>
#include <Poly_PolygonOnTriangulation.hxx>
#include <Poly_Triangulation.hxx>
#include <Standard_Failure.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopTools_IndexedDataMapOfShapeListOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Vertex.hxx>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <sstream>
#include <vector>

#include "steady/brep/brep_builder.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {
using Kernel = CGAL::Simple_cartesian<double>;
using Triangle = Kernel::Triangle_3;
using Primitive = CGAL::AABB_triangle_primitive<Kernel, std::vector<Triangle>::const_iterator>;
using Tree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, Primitive>>;
using Segment = Kernel::Segment_3;
using SegmentPrimitive = CGAL::AABB_segment_primitive<Kernel, std::vector<Segment>::const_iterator>;
using SegmentTree = CGAL::AABB_tree<CGAL::AABB_traits<Kernel, SegmentPrimitive>>;

// Edges bounding only one face (not seams, not degenerate): the shell is open there.
int free_edge_count(const TopoDS_Shape& solid) {
  TopTools_IndexedDataMapOfShapeListOfShape edge_faces;
  TopExp::MapShapesAndAncestors(solid, TopAbs_EDGE, TopAbs_FACE, edge_faces);
  int free_edges = 0;
  for (int i = 1; i <= edge_faces.Extent(); ++i) {
    const TopoDS_Edge& e = TopoDS::Edge(edge_faces.FindKey(i));
    if (BRep_Tool::Degenerated(e)) continue;
    const TopTools_ListOfShape& faces = edge_faces(i);
    if (faces.Extent() == 1 && !BRep_Tool::IsClosed(e, TopoDS::Face(faces.First()))) ++free_edges;
  }
  return free_edges;
}
}  // namespace

struct SolidBody::Tree {
  std::vector<Triangle> triangles;
  steady::Tree tree;
  std::vector<Segment> edge_segments;  // the edges' polygons on the triangulation, and a short one at each vertex
  SegmentTree edge_tree;
  std::mutex classifier_mutex;  // the classifier keeps the state of its last point
  std::unique_ptr<BRepClass3d_SolidClassifier> classifier;  // made on the first classification
};

SolidBody::SolidBody(const TopoDS_Shape& shape, const std::string& field) {
  // A body that passed the checks can still make OpenCASCADE throw while it is prepared (meshed, measured,
  // classified): that is a body it cannot work with, said as such, not an internal error.
  try {
    prepare(shape, field);
  } catch (const Standard_Failure& e) {
    fail_input(field, std::string("could not be prepared by OpenCASCADE (") + e.DynamicType()->Name() + ": " +
                          e.GetMessageString() + "): repair the shape, e.g. FreeCAD's Part > Check geometry");
  }
}

void SolidBody::prepare(const TopoDS_Shape& shape, const std::string& field) {
  if (shape.IsNull()) fail_input(field, "is empty");
  int solids = 0;
  for (TopExp_Explorer x(shape, TopAbs_SOLID); x.More(); x.Next(), ++solids) solid_ = TopoDS::Solid(x.Current());
  if (solids == 0) {
    int faces = 0;
    for (TopExp_Explorer x(shape, TopAbs_FACE); x.More(); x.Next()) ++faces;
    fail_input(field, faces ? "is not a closed solid (it has " + std::to_string(faces) + " faces but no solid)"
                            : "is not a solid (it has no faces)");
  }
  if (solids > 1) fail_input(field, "holds " + std::to_string(solids) + " solids; give one solid");
  // Our own copy: the triangulation below is stored in it, never in the caller's shape.
  solid_ = TopoDS::Solid(BRepBuilderAPI_Copy(solid_).Shape());
  if (!is_valid(solid_)) fail_input(field, "is not a valid solid: " + validity_report(solid_, 3));
  if (const int open = free_edge_count(solid_)) fail_input(field, "is not a closed solid (" + std::to_string(open) + " free edges)");
  volume_ = shape_volume(solid_);
  if (!(volume_ > 0.0)) fail_input(field, "has no positive volume (is it inside out?)");
  Bnd_Box box;
  BRepBndLib::Add(solid_, box);
  double x0, y0, z0, x1, y1, z1;
  box.Get(x0, y0, z0, x1, y1, z1);
  bounds_ = {{x0, y0, z0}, {x1, y1, z1}};
  // OpenCASCADE's mesher refused a 1e-5 box with an internal error; 1e4 tolerances is the least we take.
  constexpr double kMinimumBodySize = 1e4 * kBrepTolerance;
  if (!(size() >= kMinimumBodySize))
    fail_input(field, "is too small: its bounding box diagonal is " + (std::ostringstream() << size()).str() +
                          ", below " + (std::ostringstream() << kMinimumBodySize).str() + " (1e4 times OpenCASCADE's tolerance of 1e-7): scale "
                          "the model up, e.g. work in micrometres");
  // A tolerance is a zone where OpenCASCADE counts points as on the boundary: beyond the distance bounds' slack it
  // would classify points clear of the triangulated surface as inside (found by tests/fuzz/fuzz_body_brep: a vertex
  // tolerance of 1 on a box of 4 put points 0.7 outside its corner inside).
  const double tolerance = std::max({BRep_Tool::MaxTolerance(solid_, TopAbs_VERTEX),
                                     BRep_Tool::MaxTolerance(solid_, TopAbs_EDGE),
                                     BRep_Tool::MaxTolerance(solid_, TopAbs_FACE)});
  if (!(tolerance <= kMaxBodyRelativeTolerance * size()))
    fail_input(field, "has a tolerance of " + (std::ostringstream() << tolerance).str() + ", more than " +
                          (std::ostringstream() << kMaxBodyRelativeTolerance).str() +
                          " of its size: its geometry is too imprecise to trim against (repair the shape, e.g. "
                          "FreeCAD's Part > Check geometry, then Refine shape)");
  const double deflection = kBodyMeshRelativeDeflection * size();
  BRepMesh_IncrementalMesh mesh(solid_, deflection, Standard_False, 0.3, Standard_True);
  slack_ = kBodyMeshDeflectionFactor * deflection;
  tree_ = std::make_unique<Tree>();
  for (TopExp_Explorer x(solid_, TopAbs_FACE); x.More(); x.Next()) {
    const TopoDS_Face& face = TopoDS::Face(x.Current());
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
    if (tri.IsNull()) fail_input(field, "has a face that cannot be triangulated");
    const gp_Trsf t = loc.Transformation();
    for (int i = 1; i <= tri->NbTriangles(); ++i) {
      int a, b, c;
      tri->Triangle(i).Get(a, b, c);
      gp_Pnt p[3] = {tri->Node(a).Transformed(t), tri->Node(b).Transformed(t), tri->Node(c).Transformed(t)};
      tree_->triangles.emplace_back(Kernel::Point_3(p[0].X(), p[0].Y(), p[0].Z()),
                                    Kernel::Point_3(p[1].X(), p[1].Y(), p[1].Z()),
                                    Kernel::Point_3(p[2].X(), p[2].Y(), p[2].Z()));
    }
  }
  tree_->tree.insert(tree_->triangles.cbegin(), tree_->triangles.cend());
  tree_->tree.build();
  tree_->tree.accelerate_distance_queries();
  add_edge_segments();
  check_classifier_consistent(field);
}

void SolidBody::add_edge_segments() {
  auto point = [](const gp_Pnt& p) { return Kernel::Point_3(p.X(), p.Y(), p.Z()); };
  std::vector<Segment>& segments = tree_->edge_segments;
  for (TopExp_Explorer x(solid_, TopAbs_FACE); x.More(); x.Next()) {
    const TopoDS_Face& face = TopoDS::Face(x.Current());
    TopLoc_Location loc;
    const Handle(Poly_Triangulation) tri = BRep_Tool::Triangulation(face, loc);
    const gp_Trsf t = loc.Transformation();
    for (TopExp_Explorer e(face, TopAbs_EDGE); e.More(); e.Next()) {
      const Handle(Poly_PolygonOnTriangulation)& polygon =
          BRep_Tool::PolygonOnTriangulation(TopoDS::Edge(e.Current()), tri, loc);
      if (polygon.IsNull()) continue;  // a degenerate edge: its vertex is added below
      const TColStd_Array1OfInteger& nodes = polygon->Nodes();
      for (int i = nodes.Lower(); i < nodes.Upper(); ++i)
        segments.emplace_back(point(tri->Node(nodes(i)).Transformed(t)), point(tri->Node(nodes(i + 1)).Transformed(t)));
    }
  }
  // Every vertex (the poles of degenerate edges among them), as a segment of the slack's length that starts there:
  // the distance to it is a lower bound of the distance to the vertex.
  for (TopExp_Explorer x(solid_, TopAbs_VERTEX); x.More(); x.Next()) {
    const gp_Pnt p = BRep_Tool::Pnt(TopoDS::Vertex(x.Current()));
    segments.emplace_back(point(p), point(p.Translated(gp_Vec(slack_, 0.0, 0.0))));
  }
  tree_->edge_tree.insert(segments.cbegin(), segments.cend());
  tree_->edge_tree.build();
  tree_->edge_tree.accelerate_distance_queries();
}

bool SolidBody::classifier_says_inside(const Vec3& p) const {
  // Loaded once: BRepClass3d_SolidClassifier's constructor prepares the solid (a box tree of its faces), which
  // took most of the time of each point's classification on a body of thousands of faces.
  const std::lock_guard<std::mutex> lock(tree_->classifier_mutex);
  if (!tree_->classifier) tree_->classifier = std::make_unique<BRepClass3d_SolidClassifier>(solid_);
  tree_->classifier->Perform(gp_Pnt(p.x, p.y, p.z), 1e-7);
  return tree_->classifier->State() != TopAbs_OUT;
}

void SolidBody::check_classifier_consistent(const std::string& field) const {
  // A shell whose wires name the wrong edges can pass BRepCheck and still be classified wrongly (found by
  // fuzz_body_step: one edge reference changed, volume halved, "valid"; and by fuzz_body_brep in CI); trimming
  // against it would keep nodes far from the body. OpenCASCADE's classifier is compared with what the
  // triangulation says, an independent reading of the same faces: outside the bounding box nothing is inside, and
  // at the points of a 4 x 4 x 4 grid in the box clear of the surface, the parity of a ray's crossings with the
  // triangles (three rays in directions no face is likely to be parallel to; a point whose rays disagree, by
  // passing through an edge of the triangulation, is not judged) must be the classifier's answer.
  const std::string refusal =
      "is not a consistent solid: OpenCASCADE classifies a point %s that its faces put %s (its faces' wires or "
      "orientations contradict each other; repair the shape, e.g. FreeCAD's Part > Check geometry)";
  auto fail = [&](const char* classified, const char* geometric) {
    std::string text = refusal;
    text.replace(text.find("%s"), 2, classified);
    text.replace(text.find("%s"), 2, geometric);
    fail_input(field, text);
  };
  const Vec3 mid = 0.5 * (bounds_.lo + bounds_.hi), half = 0.5 * (bounds_.hi - bounds_.lo) + Vec3(0.1 * size());
  for (int corner = 0; corner < 8; ++corner) {
    const Vec3 p = mid + Vec3(corner & 1 ? 1.0 : -1.0, corner & 2 ? 1.0 : -1.0, corner & 4 ? 1.0 : -1.0) * half;
    if (classifier_says_inside(p)) fail("inside", "outside its bounding box");
  }
  const Kernel::Vector_3 directions[3] = {{0.5773, 0.6154, 0.5364}, {-0.8017, 0.1936, 0.5654}, {0.2135, -0.9311, 0.2958}};
  constexpr int kGrid = 4;
  for (int i = 0; i < kGrid * kGrid * kGrid; ++i) {
    const Vec3 f((i % kGrid + 0.5) / kGrid, (i / kGrid % kGrid + 0.5) / kGrid, (i / (kGrid * kGrid) + 0.5) / kGrid);
    const Vec3 p = bounds_.lo + f * (bounds_.hi - bounds_.lo);
    if (!(distance_lower_bound(p) > 0.0)) continue;  // within the triangulation's slack of the surface
    int odd = 0;
    for (const Kernel::Vector_3& d : directions)
      odd += tree_->tree.number_of_intersected_primitives(Kernel::Ray_3(Kernel::Point_3(p.x, p.y, p.z), d)) % 2;
    if (odd != 0 && odd != 3) continue;
    const bool inside = odd == 3;
    if (classifier_says_inside(p) != inside) fail(inside ? "outside" : "inside", inside ? "inside" : "outside");
  }
}

SolidBody::~SolidBody() = default;
SolidBody::SolidBody(SolidBody&&) noexcept = default;

double SolidBody::distance_lower_bound(const Vec3& p) const {
  const double d = std::sqrt(tree_->tree.squared_distance(Kernel::Point_3(p.x, p.y, p.z)));
  return std::max(0.0, d - slack_);
}

double SolidBody::edge_distance_lower_bound(const Vec3& p) const {
  if (tree_->edge_segments.empty()) return std::numeric_limits<double>::infinity();
  const double d = std::sqrt(tree_->edge_tree.squared_distance(Kernel::Point_3(p.x, p.y, p.z)));
  return std::max(0.0, d - slack_);
}

double SolidBody::exact_distance(const Vec3& p) const {
  // Measured to the shells: the distance to a solid counts as 0 inside it.
  const TopoDS_Vertex v = BRepBuilderAPI_MakeVertex(gp_Pnt(p.x, p.y, p.z)).Vertex();
  double best = std::numeric_limits<double>::infinity();
  for (TopExp_Explorer x(solid_, TopAbs_SHELL); x.More(); x.Next()) {
    BRepExtrema_DistShapeShape d(v, x.Current());
    if (!d.IsDone()) throw std::runtime_error("BRepExtrema failed to measure a distance to the body");
    best = std::min(best, d.Value());
  }
  return best;
}

std::vector<Vec3> SolidBody::nearest_points(const Vec3& p) const {
  const TopoDS_Vertex v = BRepBuilderAPI_MakeVertex(gp_Pnt(p.x, p.y, p.z)).Vertex();
  double best = std::numeric_limits<double>::infinity();
  std::vector<Vec3> out;
  for (TopExp_Explorer x(solid_, TopAbs_SHELL); x.More(); x.Next()) {
    BRepExtrema_DistShapeShape d(v, x.Current());
    if (!d.IsDone() || d.NbSolution() < 1)
      throw std::runtime_error("BRepExtrema failed to find the body's nearest point");
    if (d.Value() > best) continue;
    if (d.Value() < best) out.clear();
    best = d.Value();
    for (int k = 1; k <= d.NbSolution(); ++k) {
      const gp_Pnt q = d.PointOnShape2(k);
      out.emplace_back(q.X(), q.Y(), q.Z());
    }
  }
  return out;
}

bool SolidBody::contains(const Vec3& p) const { return classifier_says_inside(p); }

}  // namespace steady
