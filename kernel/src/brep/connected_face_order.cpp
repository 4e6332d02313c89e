#include "brep/connected_face_order.hpp"

#include <BRep_Builder.hxx>
#include <TopExp_Explorer.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Shell.hxx>

#include <cstddef>
#include <unordered_map>
#include <vector>

namespace steady {

namespace {

// The shell's faces breadth first through shared edges. Children are taken with their parent's orientation and
// location composed (TopoDS_Iterator's default), because BRep_Builder::Add composes them back relative to the copy,
// which keeps the parent's.
TopoDS_Shell shell_in_connected_order(const TopoDS_Shell& shell) {
  std::vector<TopoDS_Shape> faces;
  for (TopoDS_Iterator it(shell); it.More(); it.Next()) faces.push_back(it.Value());
  // Faces of each edge, by the edge's TShape (an edge is the same whatever its orientation or face).
  std::unordered_map<const void*, std::vector<std::size_t>> faces_of_edge;
  std::vector<std::vector<const void*>> edges_of_face(faces.size());
  for (std::size_t i = 0; i < faces.size(); ++i)
    for (TopExp_Explorer x(faces[i], TopAbs_EDGE); x.More(); x.Next()) {
      const void* key = x.Current().TShape().get();
      edges_of_face[i].push_back(key);
      faces_of_edge[key].push_back(i);
    }
  std::vector<char> placed(faces.size(), 0);
  std::vector<std::size_t> order;
  order.reserve(faces.size());
  for (std::size_t seed = 0; seed < faces.size(); ++seed) {
    if (placed[seed]) continue;
    placed[seed] = 1;
    order.push_back(seed);
    for (std::size_t next = order.size() - 1; next < order.size(); ++next)
      for (const void* edge : edges_of_face[order[next]])
        for (std::size_t neighbour : faces_of_edge[edge])
          if (!placed[neighbour]) {
            placed[neighbour] = 1;
            order.push_back(neighbour);
          }
  }
  TopoDS_Shell out = TopoDS::Shell(shell.EmptyCopied());
  const BRep_Builder b;
  for (std::size_t i : order) b.Add(out, faces[i]);
  out.Closed(shell.Closed());
  return out;
}

}  // namespace

TopoDS_Shape with_faces_in_connected_order(const TopoDS_Shape& shape) {
  if (shape.IsNull()) return shape;
  if (shape.ShapeType() == TopAbs_SHELL) return shell_in_connected_order(TopoDS::Shell(shape));
  if (shape.ShapeType() > TopAbs_SOLID) return shape;  // faces and below: nothing to order
  // Compounds, compsolids and solids: the same container around its children in their order, each reordered.
  TopoDS_Shape out = shape.EmptyCopied();
  const BRep_Builder b;
  for (TopoDS_Iterator it(shape); it.More(); it.Next())
    b.Add(out, with_faces_in_connected_order(it.Value()));
  out.Closed(shape.Closed());
  return out;
}

}  // namespace steady
