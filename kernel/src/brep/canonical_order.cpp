#include "brep/canonical_order.hpp"

#include <BRepAdaptor_Curve.hxx>
#include <BRepAdaptor_Surface.hxx>
#include <BRepBndLib.hxx>
#include <BRepGProp.hxx>
#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <Bnd_Box.hxx>
#include <GProp_GProps.hxx>
#include <TopExp.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Iterator.hxx>
#include <TopoDS_Wire.hxx>

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace steady {

namespace {

// A sort key of numbers rounded to a grid (`quantum`), so that rounding noise does not decide the order.
using Key = std::array<double, 5>;

double rounded(double value, double quantum) { return std::round(value / quantum); }

// An edge's key: the point at the middle of its range (a vertex for a degenerate edge), then its orientation.
Key edge_key(const TopoDS_Edge& edge, double quantum) {
  gp_Pnt p;
  if (BRep_Tool::Degenerated(edge)) {
    p = BRep_Tool::Pnt(TopExp::FirstVertex(edge));
  } else {
    const BRepAdaptor_Curve curve(edge);
    p = curve.Value(0.5 * (curve.FirstParameter() + curve.LastParameter()));
  }
  return {rounded(p.X(), quantum), rounded(p.Y(), quantum), rounded(p.Z(), quantum), double(edge.Orientation()), 0.0};
}

// A face's key: surface type, centre of mass of its area, area.
Key face_key(const TopoDS_Face& face, double quantum) {
  GProp_GProps props;
  BRepGProp::SurfaceProperties(face, props);
  const gp_Pnt c = props.CentreOfMass();
  return {double(BRepAdaptor_Surface(face, Standard_False).GetType()), rounded(c.X(), quantum),
          rounded(c.Y(), quantum), rounded(c.Z(), quantum), rounded(props.Mass(), quantum)};
}

// A wire's key: centre of mass of its edges, length, orientation.
Key wire_key(const TopoDS_Wire& wire, double quantum) {
  GProp_GProps props;
  BRepGProp::LinearProperties(wire, props);
  const gp_Pnt c = props.CentreOfMass();
  return {rounded(c.X(), quantum), rounded(c.Y(), quantum), rounded(c.Z(), quantum), rounded(props.Mass(), quantum),
          double(wire.Orientation())};
}

// Below, children are taken with their orientation and location composed with their parent's (TopoDS_Iterator's
// default), because BRep_Builder::Add composes them back relative to the new parent.
// The wire's edges rotated to start at the least key; the cyclic order is the wire's own.
TopoDS_Wire wire_in_order(const TopoDS_Wire& wire, double quantum) {
  std::vector<TopoDS_Shape> edges;
  for (TopoDS_Iterator it(wire); it.More(); it.Next()) edges.push_back(it.Value());
  if (edges.empty()) return wire;
  std::vector<Key> keys;
  for (const TopoDS_Shape& e : edges) keys.push_back(edge_key(TopoDS::Edge(e), quantum));
  const std::size_t first = std::min_element(keys.begin(), keys.end()) - keys.begin();
  std::rotate(edges.begin(), edges.begin() + first, edges.end());
  TopoDS_Wire out = TopoDS::Wire(wire.EmptyCopied());
  const BRep_Builder b;
  for (const TopoDS_Shape& e : edges) b.Add(out, e);
  out.Closed(wire.Closed());
  return out;
}

// The face on the same surface with its wires sorted and each in order.
TopoDS_Face face_in_order(const TopoDS_Face& face, double quantum) {
  std::vector<std::pair<Key, TopoDS_Wire>> wires;
  for (TopoDS_Iterator it(face); it.More(); it.Next()) {
    const TopoDS_Wire w = wire_in_order(TopoDS::Wire(it.Value()), quantum);
    wires.emplace_back(wire_key(w, quantum), w);
  }
  std::stable_sort(wires.begin(), wires.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  TopoDS_Face out = TopoDS::Face(face.EmptyCopied());
  const BRep_Builder b;
  for (const auto& [key, w] : wires) b.Add(out, w);
  return out;
}

}  // namespace

TopoDS_Shell in_canonical_order(const TopoDS_Shell& shell) {
  Bnd_Box box;
  BRepBndLib::Add(shell, box, Standard_False);
  const double quantum = std::max(1e-9 * std::sqrt(box.SquareExtent()), 1e-12);
  std::vector<std::pair<Key, TopoDS_Face>> faces;
  for (TopoDS_Iterator it(shell); it.More(); it.Next()) {
    const TopoDS_Face f = TopoDS::Face(it.Value());
    faces.emplace_back(face_key(f, quantum), face_in_order(f, quantum));
  }
  std::stable_sort(faces.begin(), faces.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  TopoDS_Shell out = TopoDS::Shell(shell.EmptyCopied());
  const BRep_Builder b;
  for (const auto& [key, f] : faces) b.Add(out, f);
  out.Closed(shell.Closed());
  return out;
}

}  // namespace steady
