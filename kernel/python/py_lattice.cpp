// Python bindings of the lattice: thin conversions, bulk results as numpy arrays, the GIL
// released while the kernel works.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "steady/lattice/table_layout.hpp"
#include "steady/core/memory_budget.hpp"

namespace steadypy {

using steady::Lattice;
using steady::Similarity;

namespace {

Similarity optional_similarity(const py::object& value, const char* name) {
  if (value.is_none()) return Similarity::identity();
  try {
    return value.cast<Similarity>();
  } catch (const py::cast_error&) {
    value_error(name, "expected a Similarity");
  }
}

Similarity required_similarity(const py::object& value, const char* name) {
  if (value.is_none()) value_error(name, "expected a Similarity (got None)");
  return optional_similarity(value, name);
}

Lattice steady_lattice(py::handle nodes, py::handle beams, py::handle counts, const py::object& U,
                       const py::object& V, const py::object& W, const py::object& G, py::handle omitted,
                       const std::string& order, steady::StepControl control) {
  return Lattice::ordered(to_nodes(nodes), to_beams(beams), to_counts(counts), {required_similarity(U, "U"), control},
                          {required_similarity(V, "V"), control}, {required_similarity(W, "W"), control},
                          optional_similarity(G, "G"), steady::axis_order_from_string(order, "order"),
                          to_omitted(omitted));
}

// The steady-brick view, or a ValueError saying the layout has no steps.
const steady::SteadyBrick& steady_view(const Lattice& l, const char* what) {
  const steady::SteadyBrick* view = l.layout().steady_brick();
  if (!view) value_error(what, "the lattice's layout (" + l.layout().kind() + ") is not a steady brick: it has no steps");
  return *view;
}

steady::NodeId node_id(std::int64_t i, std::int64_t j, std::int64_t k, int n) { return {i, j, k, n}; }

}  // namespace

namespace {
void bind_lattice_contents(py::class_<Lattice>& cls);
}  // namespace

void bind_lattice(py::module_& m) {
  py::class_<Lattice> cls(m, "Lattice", R"doc(
A steady brick lattice: template balls and beam patterns placed by G o W^k o V^j o U^i for every group
(i, j, k) of the counts (u, v, w). Nothing is stored per element; balls() and beams() list them in a
stable order, and every query returns indices into those lists.

nodes: list of ((x, y, z), radius), the template balls.
beams: list of (n1, di, dj, dk, n2) joining ball n1 of group (i, j, k) to ball n2 of group
       (i+di, j+dj, k+dk), or (n1, di, dj, dk, n2, r1, r2) with the beam's own end radii in template units.
counts: (u, v, w). U, V, W: the steps between neighbouring groups. G: the placement (default identity).
omitted: optional list of (i, j, k, n) nodes left out, with their beams.)doc");
  cls
      .def(py::init([](py::handle nodes, py::handle beams, py::handle counts, const py::object& U,
                       const py::object& V, const py::object& W, const py::object& G, py::handle omitted,
                       const std::string& order) {
             return steady_lattice(nodes, beams, counts, U, V, W, G, omitted, order, steady::StepControl::Incremental);
           }),
           py::arg("nodes"), py::arg("beams"), py::arg("counts"), py::arg("U"), py::arg("V"), py::arg("W"),
           py::arg("G") = py::none(), py::arg("omitted") = py::none(), py::arg("order") = "UVW")
      .def_static(
          "interpolating",
          [](py::handle nodes, py::handle beams, py::handle counts, const py::object& U, const py::object& V,
             const py::object& W, const py::object& G, py::handle omitted, const std::string& order) {
            return steady_lattice(nodes, beams, counts, U, V, W, G, omitted, order, steady::StepControl::Cumulative);
          },
          py::arg("nodes"), py::arg("beams"), py::arg("counts"), py::arg("U_total"), py::arg("V_total"),
          py::arg("W_total"), py::arg("G") = py::none(), py::arg("omitted") = py::none(), py::arg("order") = "UVW",
          "A lattice whose U, V, W are given from the first group to the last of each direction; the steps are "
          "their 1/(count-1) powers.")
      .def_static(
          "from_table",
          [](py::handle nodes, py::handle beams, py::handle counts, const std::vector<Similarity>& similarities,
             py::handle omitted) {
            const steady::Counts c = to_counts(counts);
            return Lattice({to_nodes(nodes), to_beams(beams), steady::TableLayout::make(c, similarities),
                            to_omitted(omitted)});
          },
          py::arg("nodes"), py::arg("beams"), py::arg("counts"), py::arg("similarities"), py::arg("omitted") = py::none(),
          "A lattice whose groups are placed by a table: one Similarity per group, group (i, j, k) at index "
          "(k * v + j) * u + i. Not steady: queries and properties take their general (slower) paths.")
      .def_static(
          "from_frames",
          [](py::handle nodes, py::handle beams, py::handle counts, py::handle base, py::handle end_u,
             py::handle end_v, py::handle end_w) {
            return Lattice::from_frames(to_nodes(nodes), to_beams(beams), to_counts(counts), to_frame(base, "base"),
                                        to_frame(end_u, "end_u"), to_frame(end_v, "end_v"), to_frame(end_w, "end_w"));
          },
          py::arg("nodes"), py::arg("beams"), py::arg("counts"), py::arg("base"), py::arg("end_u"), py::arg("end_v"),
          py::arg("end_w"),
          "A lattice from four frames (origin, x, y, z): base places group (0,0,0), end_u, end_v, end_w place "
          "groups (u-1,0,0), (0,v-1,0), (0,0,w-1).")
      .def_static("from_json", &steady::lattice_from_json, py::arg("text"))
      .def("to_json", &steady::lattice_to_json, py::arg("indent") = 2);
  bind_lattice_contents(cls);
}

namespace {

// What a lattice holds: its elements in bulk and one by one, its template and layout, its indices.
void bind_lattice_contents(py::class_<Lattice>& cls) {
  cls.def(
          "balls",
          [](const Lattice& lat) {
            steady::require_memory(static_cast<std::uint64_t>(lat.ball_count()) * 32u,
                                   "balls(): " + std::to_string(lat.ball_count()) + " balls",
                                   "query a region (query_ball), iterate with ball(i, j, k, n), or use properties()");
            py::array_t<double> centers({py::ssize_t(lat.ball_count()), py::ssize_t(3)});
            py::array_t<double> radii(py::ssize_t(lat.ball_count()));
            double *c = centers.mutable_data(), *r = radii.mutable_data();
            run_interruptible([&] { lat.balls(c, r); });  // seconds at 10^8 balls: Ctrl-C stops it
            return py::make_tuple(centers, radii);
          },
          "(centers N x 3, radii N) of every ball, in the stable order.")
      .def(
          "beams",
          [](const Lattice& lat) {
            const py::ssize_t n = lat.beam_count();
            steady::require_memory(static_cast<std::uint64_t>(n) * 32u, "beams(): " + std::to_string(n) + " beams",
                                   "query a region (query_ball) or use properties()");
            py::array_t<std::int64_t> a(n), b(n);
            py::array_t<double> ra(n), rb(n);
            std::int64_t *pa = a.mutable_data(), *pb = b.mutable_data();
            double *pra = ra.mutable_data(), *prb = rb.mutable_data();
            run_interruptible([&] { lat.beams(pa, pb, pra, prb); });
            return py::make_tuple(a, b, ra, rb);
          },
          "(a, b, ra, rb): indices into balls() of each beam's two balls and its two end radii, in the stable order.")
      .def_property_readonly("ball_count", &Lattice::ball_count)
      .def_property_readonly("beam_count", &Lattice::beam_count)
      .def_property_readonly("counts",
                             [](const Lattice& l) { return py::make_tuple(l.counts().u, l.counts().v, l.counts().w); })
      .def_property_readonly("node_count", &Lattice::node_count)
      .def_property_readonly("pattern_count", &Lattice::pattern_count)
      .def_property_readonly("nodes",
                             [](const Lattice& l) {
                               py::list out;
                               for (const auto& n : l.definition().nodes)
                                 out.append(py::make_tuple(py::make_tuple(n.center.x, n.center.y, n.center.z), n.radius));
                               return out;
                             })
      .def_property_readonly("beam_patterns",
                             [](const Lattice& l) {
                               py::list out;
                               for (const auto& b : l.definition().beams) {
                                 if (b.has_radii())
                                   out.append(py::make_tuple(b.from, b.di, b.dj, b.dk, b.to, *b.from_radius, *b.to_radius));
                                 else
                                   out.append(py::make_tuple(b.from, b.di, b.dj, b.dk, b.to));
                               }
                               return out;
                             })
      .def_property_readonly("omitted",
                             [](const Lattice& l) {
                               py::list out;
                               for (const auto& o : l.definition().omitted) out.append(py::make_tuple(o.i, o.j, o.k, o.n));
                               return out;
                             })
      .def_property_readonly("layout", [](const Lattice& l) { return l.layout().kind(); },
                             "The layout's kind: 'steady-brick', 'any-order-brick' or 'table'.")
      .def_property_readonly(
          "order",
          [](const Lattice& l) { return steady::to_string(steady_view(l, "order").axes); },
          "The order the steps apply in, first to last ('UVW' for G W^k V^j U^i).")
      .def_property_readonly(
          "U", [](const Lattice& l) { return steady_view(l, "U").step_along(0); },
          "The step between neighbouring groups along i.")
      .def_property_readonly("V", [](const Lattice& l) { return steady_view(l, "V").step_along(1); })
      .def_property_readonly("W", [](const Lattice& l) { return steady_view(l, "W").step_along(2); })
      .def_property_readonly("G", [](const Lattice& l) { return steady_view(l, "G").placement; })
      .def("placed", &Lattice::placed, py::arg("G"),
           "The same lattice moved by the similarity G as a whole (group (i, j, k) placed by G o S(i, j, k)).")
      .def("group", &Lattice::group_similarity, py::arg("i"), py::arg("j"), py::arg("k"),
           "The similarity placing group (i, j, k) (G W^k V^j U^i for the steps applied in the U V W order).")
      .def(
          "ball",
          [](const Lattice& l, std::int64_t i, std::int64_t j, std::int64_t k, int n) {
            if (!l.node_exists(node_id(i, j, k, n))) value_error("ball", "(i, j, k, n) names no node of the lattice");
            const steady::Ball b = l.ball(node_id(i, j, k, n));
            return py::make_tuple(vec3_array(b.center), b.radius);
          },
          py::arg("i"), py::arg("j"), py::arg("k"), py::arg("n"), "(center, radius) of ball n of group (i, j, k).")
      .def(
          "beam",
          [](const Lattice& l, std::int64_t i, std::int64_t j, std::int64_t k, int p) {
            const steady::BeamId id{i, j, k, p};
            if (!l.beam_exists(id)) value_error("beam", "(i, j, k, pattern) names no beam of the lattice");
            const steady::BeamGeometry g = l.beam(id);
            return py::make_tuple(vec3_array(g.start.center), g.start.radius, vec3_array(g.end.center), g.end.radius);
          },
          py::arg("i"), py::arg("j"), py::arg("k"), py::arg("pattern"),
          "(center_a, ra, center_b, rb) of the beam of a pattern starting in group (i, j, k).")
      .def("ball_index", [](const Lattice& l, std::int64_t i, std::int64_t j, std::int64_t k,
                            int n) { return l.ball_index(node_id(i, j, k, n)); },
           py::arg("i"), py::arg("j"), py::arg("k"), py::arg("n"), "Index into balls(), or -1.")
      .def("ball_id",
           [](const Lattice& l, std::int64_t index) {
             const steady::NodeId id = l.ball_id(index);
             return py::make_tuple(id.i, id.j, id.k, id.n);
           },
           py::arg("index"), "(i, j, k, n) of a ball index.")
      .def("beam_index", [](const Lattice& l, std::int64_t i, std::int64_t j, std::int64_t k,
                            int p) { return l.beam_index(steady::BeamId{i, j, k, p}); },
           py::arg("i"), py::arg("j"), py::arg("k"), py::arg("pattern"), "Index into beams(), or -1.")
      .def("beam_id",
           [](const Lattice& l, std::int64_t index) {
             const steady::BeamId id = l.beam_id(index);
             return py::make_tuple(id.i, id.j, id.k, id.pattern);
           },
           py::arg("index"), "(i, j, k, pattern) of a beam index.")
      .def("__repr__", [](const Lattice& l) {
        return "<Lattice " + std::to_string(l.counts().u) + "x" + std::to_string(l.counts().v) + "x" +
               std::to_string(l.counts().w) + " groups, " + std::to_string(l.ball_count()) + " balls, " +
               std::to_string(l.beam_count()) + " beams>";
      });
}

}  // namespace

}  // namespace steadypy
