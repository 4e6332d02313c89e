// Python bindings of the queries: ball interference, point membership, distance, rays, voxels on
// lattices and filtered lattices, and the node filters. Thin: conversions, the GIL released while the
// kernel works (and taken back by Python callables used as filters), every call interruptible by Ctrl-C.
#include <pybind11/functional.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <limits>
#include <memory>
#include <unordered_map>

#include "convert.hpp"
#include "steady/core/errors.hpp"
#include "steady/query/filtered_lattice.hpp"
#include "steady/brep/body_filter.hpp"
#include "steady/query/lattice_query.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/query/queries.hpp"

namespace steadypy {

using steady::Ball;
using steady::FilteredLattice;
using steady::FilterPtr;
using steady::Lattice;
using steady::LatticeQuery;
using steady::QueryMethod;

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
// Filtered coarse lattices up to this many balls are materialized when a Lattice-in-Lattice filter is
// made from them (16 MB of mask at most).
constexpr std::int64_t kMaterializeCoarseBalls = std::int64_t(1) << 24;

// One LatticeQuery per Python Lattice object (its tables and plan cost O(u + v + w) to build), dropped
// with the object through a weak reference. Lattice objects are immutable, so the cache never goes stale.
std::shared_ptr<const LatticeQuery> query_for(const py::object& self) {
  static std::unordered_map<const void*, std::shared_ptr<const LatticeQuery>> cache;
  const Lattice& lat = self.cast<const Lattice&>();
  auto it = cache.find(&lat);
  if (it != cache.end()) return it->second;
  if (lat.ball_count() == 0) value_error("lattice", "has no balls (every node is omitted): there is nothing to query");
  auto q = std::make_shared<const LatticeQuery>(lat);
  const void* key = &lat;
  py::cpp_function forget([key](py::handle ref) {
    cache.erase(key);
    ref.dec_ref();
  });
  py::weakref(self, forget).release();  // kept alive until the callback runs
  cache.emplace(key, q);
  return q;
}

QueryMethod method_of(const std::string& name) { return steady::query_method_from_string(name, "method"); }

Ball query_ball_arg(py::handle center, py::handle radius) {
  const steady::Vec3 c = to_vec3(center, "center");
  const double r = to_double(radius, "radius");
  if (r < 0.0) value_error("radius", "must be >= 0 (got " + std::to_string(r) + ")");
  return {c, r};
}

py::tuple result_arrays(const steady::BallQueryResult& r) {
  py::array_t<std::int64_t> balls(static_cast<py::ssize_t>(r.balls.size())), beams(static_cast<py::ssize_t>(r.beams.size()));
  std::copy(r.balls.begin(), r.balls.end(), balls.mutable_data());
  std::copy(r.beams.begin(), r.beams.end(), beams.mutable_data());
  return py::make_tuple(balls, beams);
}

// --- the derived queries on any source -------------------------------------------------------------

py::object contains_impl(const steady::InterferenceSource& src, py::handle points) {
  bool single = false;
  auto p = to_points(points, "points", 3, &single);
  const auto n = static_cast<std::size_t>(p.shape(0));
  py::array_t<bool> out(static_cast<py::ssize_t>(n));
  run_interruptible([&] { steady::contains(src, p.data(), n, reinterpret_cast<std::uint8_t*>(out.mutable_data())); });
  if (single) return py::bool_(out.at(0));
  return std::move(out);
}

py::object distance_impl(const steady::InterferenceSource& src, py::handle points, double bound) {
  bool single = false;
  auto p = to_points(points, "points", 3, &single);
  const auto n = static_cast<std::size_t>(p.shape(0));
  py::array_t<double> out(static_cast<py::ssize_t>(n));
  run_interruptible([&] { steady::distance(src, p.data(), n, bound, out.mutable_data()); });
  if (single) return py::float_(out.at(0));
  return std::move(out);
}

py::object raycast_impl(const steady::InterferenceSource& src, py::handle origins, py::handle directions, double max_distance) {
  bool single_o = false, single_d = false;
  auto o = to_points(origins, "origins", 3, &single_o);
  auto d = to_points(directions, "directions", 3, &single_d);
  if (o.shape(0) != d.shape(0)) value_error("directions", "needs one direction per origin");
  const auto n = static_cast<std::size_t>(o.shape(0));
  py::array_t<double> out(static_cast<py::ssize_t>(n));
  run_interruptible([&] { steady::raycast(src, o.data(), d.data(), n, max_distance, out.mutable_data()); });
  if (single_o && single_d) return py::float_(out.at(0));
  return std::move(out);
}

py::array voxelize_impl(const steady::InterferenceSource& src, py::handle lo, py::handle hi, py::handle shape) {
  const steady::Vec3 l = to_vec3(lo, "lo"), h = to_vec3(hi, "hi");
  auto s = py::reinterpret_borrow<py::sequence>(shape);
  if (!py::isinstance<py::sequence>(shape) || s.size() != 3) value_error("shape", "expected 3 counts (nx, ny, nz)");
  const std::int64_t n[3] = {to_int(s[0], "shape[0]"), to_int(s[1], "shape[1]"), to_int(s[2], "shape[2]")};
  for (int c = 0; c < 3; ++c)
    if (n[c] < 1) value_error("shape", "every count must be >= 1 (got " + std::to_string(n[c]) + ")");
  steady::require_memory(static_cast<std::uint64_t>(n[0]) * n[1] * n[2], "voxelize(): " + std::to_string(n[0] * n[1] * n[2]) + " voxels",
                         "use a smaller shape, or voxelize the box in parts");
  py::array_t<bool> out({py::ssize_t(n[0]), py::ssize_t(n[1]), py::ssize_t(n[2])});
  std::uint8_t* data = reinterpret_cast<std::uint8_t*>(out.mutable_data());
  run_interruptible([&] { steady::voxelize(src, l, h, n, data); });
  return std::move(out);
}

// --- filters -----------------------------------------------------------------------------------------

struct PyFilter {
  FilterPtr filter;
};

std::shared_ptr<FilteredLattice> as_filtered(py::handle value, const char* name) {
  if (py::isinstance<FilteredLattice>(value)) return value.cast<std::shared_ptr<FilteredLattice>>();
  if (py::isinstance<Lattice>(value)) {
    const Lattice& lat = value.cast<const Lattice&>();
    if (lat.ball_count() == 0) value_error(name, "the lattice has no balls");
    return std::make_shared<FilteredLattice>(lat);
  }
  value_error(name, "expected a Lattice or a FilteredLattice");
}

// A Python callable points (N x 3) -> N booleans, as a kernel point classifier (takes the GIL).
steady::PointClassifier python_classifier(py::function f) {
  auto shared = std::make_shared<py::function>(std::move(f));
  return [shared](const double* points, std::size_t n, std::uint8_t* inside) {
    py::gil_scoped_acquire gil;
    py::array_t<double> pts({py::ssize_t(n), py::ssize_t(3)});
    std::copy(points, points + 3 * n, pts.mutable_data());
    py::object r = (*shared)(pts);
    auto a = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(r);
    if (!a || a.size() != static_cast<py::ssize_t>(n))
      throw steady::InvalidInput("body: the classifier must return one boolean per point");
    const bool* b = a.data();
    for (std::size_t q = 0; q < n; ++q) inside[q] = b[q] ? 1 : 0;
  };
}

PyFilter make_stencil(py::handle mask) {
  auto a = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(
      py::module_::import("numpy").attr("asarray")(mask, "bool").attr("astype")("uint8"));
  if (!a || (a.ndim() != 3 && a.ndim() != 4)) value_error("mask", "expected a 3D (x, y, z) or 4D (x, y, z, node) boolean array");
  for (int d = 0; d < a.ndim(); ++d)
    if (a.shape(d) < 1) value_error("mask", "every dimension must be >= 1");
  std::vector<std::uint8_t> cells(a.data(), a.data() + a.size());
  return {steady::index_stencil(std::move(cells), a.shape(0), a.shape(1), a.shape(2),
                                a.ndim() == 4 ? static_cast<int>(a.shape(3)) : 0)};
}

}  // namespace

namespace {

// The queries of a Lattice: ball interference, points, distances, rays, voxels.
void bind_lattice_queries(py::module_& m) {
  auto lattice = py::reinterpret_borrow<py::class_<Lattice>>(m.attr("Lattice"));
  lattice
      .def(
          "query_ball",
          [](const py::object& self, py::handle center, py::handle radius, const std::string& method) {
            const Ball q = query_ball_arg(center, radius);
            const QueryMethod mm = method_of(method);
            auto lq = query_for(self);
            steady::BallQueryResult r;
            run_interruptible([&] { r = lq->query_ball(q, mm); });
            return result_arrays(r);
          },
          py::arg("center"), py::arg("radius"), py::arg("method") = "auto",
          "(ball_indices, beam_indices): sorted int64 indices into balls() and beams() of exactly the elements "
          "meeting the closed ball (touching counts). A beam is the convex hull of its two end balls. method: "
          "auto, naive, rows, slabs, constant, blocks, rows-paper, slabs-paper, becots (a BeCOTS slab or stack).")
      .def(
          "contains",
          [](const py::object& self, py::handle points, const std::string& method) {
            auto lq = query_for(self);
            return contains_impl(steady::LatticeSource(*lq, method_of(method)), points);
          },
          py::arg("points"), py::arg("method") = "auto",
          "Point membership: a bool per point (N x 3), or a bool for one point. Boundary points are inside.")
      .def(
          "distance",
          [](const py::object& self, py::handle points, double bound, const std::string& method) {
            auto lq = query_for(self);
            return distance_impl(steady::LatticeSource(*lq, method_of(method)), points, bound);
          },
          py::arg("points"), py::arg("bound") = kInf, py::arg("method") = "auto",
          "Distance from each point to the lattice (0 inside) when at most bound, inf otherwise.")
      .def(
          "raycast",
          [](const py::object& self, py::handle origins, py::handle directions, double max_distance,
             const std::string& method) {
            auto lq = query_for(self);
            return raycast_impl(steady::LatticeSource(*lq, method_of(method)), origins, directions, max_distance);
          },
          py::arg("origins"), py::arg("directions"), py::arg("max_distance") = kInf, py::arg("method") = "auto",
          "Distance t along each (normalized) direction to the first point of the lattice, inf for no hit "
          "(exact: sphere tracing driven by ball-interference queries).")
      .def(
          "voxelize",
          [](const py::object& self, py::handle lo, py::handle hi, py::handle shape, const std::string& method) {
            auto lq = query_for(self);
            return voxelize_impl(steady::LatticeSource(*lq, method_of(method)), lo, hi, shape);
          },
          py::arg("lo"), py::arg("hi"), py::arg("shape"), py::arg("method") = "auto",
          "A bool array of the given shape (nx, ny, nz): voxel (i, j, k) of the box [lo, hi] is set when its "
          "center is in the lattice.")
      .def(
          "query_plan",
          [](const py::object& self) {
            auto lq = query_for(self);
            const steady::QueryPlan& p = lq->plan();
            py::dict d;
            d["automatic"] = steady::to_string(p.automatic);
            d["slabs"] = p.slabs_valid;
            d["slabs_reason"] = p.slabs_reason;
            d["constant"] = p.constant_valid;
            d["constant_reason"] = p.constant_reason;
            d["becots"] = p.becots_valid;
            d["becots_reason"] = p.becots_reason;
            d["description"] = p.describe();
            return d;
          },
          "Which ball-interference paths apply to this lattice (O(u) slabs, O(1) constant, O(1) becots on a BeCOTS "
          "slab or stack) and why not.")
      .def(
          "filtered",
          [](const Lattice& self, const PyFilter& f, const std::string& method) {
            if (self.ball_count() == 0) value_error("lattice", "has no balls");
            return std::make_shared<FilteredLattice>(self, f.filter, method_of(method));
          },
          py::arg("filter"), py::arg("method") = "auto", "This lattice seen through a node filter.");

}

// Node filters and their combinations.
void bind_filters(py::module_& m) {
  py::class_<PyFilter>(m, "Filter", R"doc(
A node filter: which nodes of a lattice exist. Combine with & (and), | (or), ~ (not). A filtered lattice
keeps a ball whose node passes and a beam whose two nodes both pass.)doc")
      .def("__and__", [](const PyFilter& a, const PyFilter& b) { return PyFilter{steady::all_of({a.filter, b.filter})}; })
      .def("__or__", [](const PyFilter& a, const PyFilter& b) { return PyFilter{steady::any_of({a.filter, b.filter})}; })
      .def("__invert__", [](const PyFilter& a) { return PyFilter{steady::negate(a.filter)}; })
      .def("describe", [](const PyFilter& a) { return a.filter->describe(); })
      .def("__repr__", [](const PyFilter& a) { return "<Filter " + a.filter->describe() + ">"; });
  m.def("IndexStencil", &make_stencil, py::arg("mask"),
        "Keep node (i, j, k, n) when mask[i % x, j % y, k % z] (or mask[i % x, j % y, k % z, n % nodes] for a 4D "
        "mask) is true.");
  m.def(
      "LatticeInLattice",
      [](py::handle coarse) {
        auto c = as_filtered(coarse, "coarse");
        // A filtered coarse lattice is evaluated once for all its nodes (one byte per ball) when that is
        // small next to the fine work it saves: every fine node then looks coarse nodes up instead of
        // filtering them again.
        if (c->filter() && !c->materialized() && c->lattice().ball_count() <= kMaterializeCoarseBalls)
          run_interruptible([&] { c->materialize(); });
        return PyFilter{steady::lattice_in_lattice(c)};
      },
      py::arg("coarse"),
      "Keep a node whose ball meets the coarse Lattice or FilteredLattice (cascade by filtering the coarse one; "
      "a filtered coarse lattice of up to 2^24 balls is materialized first).");
  m.def(
      "Gyroid",
      [](double period, double thickness, py::handle origin, const std::string& mode) {
        steady::GyroidMode gm = steady::GyroidMode::Sheet;
        if (mode == "solid")
          gm = steady::GyroidMode::Solid;
        else if (mode != "sheet")
          value_error("mode", "expected 'sheet' or 'solid'");
        return PyFilter{steady::gyroid(period, thickness, to_vec3(origin, "origin"), gm)};
      },
      py::arg("period"), py::arg("thickness"), py::arg("origin") = py::make_tuple(0.0, 0.0, 0.0), py::arg("mode") = "sheet",
      "Keep a node whose center is in the gyroid sheet |g| <= thickness (mode 'solid': g <= thickness), with "
      "g = sin x cos y + sin y cos z + sin z cos x at 2 pi (center - origin) / period.");
  m.def(
      "InsideBody",
      [](py::handle body) {
        if (py::isinstance<py::str>(body)) {
          const std::string text = body.cast<std::string>();
          return PyFilter{run_interruptible([&] { return steady::inside_brep(text, "body"); })};
        }
        if (py::isinstance<py::function>(body))
          return PyFilter{steady::inside(python_classifier(body.cast<py::function>()), false, "inside a Python body")};
        value_error("body", "expected B-rep text (str) or a callable points -> bools");
      },
      py::arg("body"),
      "Keep a node whose center is inside a body: B-rep text (OpenCASCADE format, e.g. Part shape "
      "exportBrepToString(); boundary counts inside) or a callable taking an N x 3 array and returning N bools.");

}

// A lattice seen through a filter, with the same queries.
void bind_filtered_lattice(py::module_& m) {
  py::class_<FilteredLattice, std::shared_ptr<FilteredLattice>>(m, "FilteredLattice", R"doc(
A lattice seen through a node filter. Indices are never renumbered: queries return indices into the
unfiltered lattice's balls() and beams(), and ball_mask() / beam_mask() say which exist (a dense
numbering is the running count of a mask, e.g. numpy.flatnonzero).)doc")
      .def(py::init([](const Lattice& lattice, py::object filter, const std::string& method) {
             if (lattice.ball_count() == 0) value_error("lattice", "has no balls");
             FilterPtr f;
             if (!filter.is_none()) {
               if (!py::isinstance<PyFilter>(filter)) value_error("filter", "expected a Filter or None");
               f = filter.cast<const PyFilter&>().filter;
             }
             return std::make_shared<FilteredLattice>(lattice, f, method_of(method));
           }),
           py::arg("lattice"), py::arg("filter") = py::none(), py::arg("method") = "auto")
      .def_property_readonly("lattice", [](const FilteredLattice& f) { return f.lattice(); }, "A copy of the unfiltered lattice.")
      .def_property_readonly("filter", [](const FilteredLattice& f) -> py::object {
        if (!f.filter()) return py::none();
        return py::cast(PyFilter{f.filter()});
      })
      .def("materialize", [](FilteredLattice& f) { run_interruptible([&] { f.materialize(); }); },
           "Evaluate the filter for every node once and keep the mask (one byte per ball).")
      .def_property_readonly("materialized", &FilteredLattice::materialized)
      .def("ball_mask", [](const FilteredLattice& f) {
        steady::require_memory(static_cast<std::uint64_t>(f.lattice().ball_count()),
                               "ball_mask(): a byte per ball of " + std::to_string(f.lattice().ball_count()),
                               "query a region (query_ball) or test nodes one at a time");
        py::array_t<bool> out(static_cast<py::ssize_t>(f.lattice().ball_count()));
        auto* d = reinterpret_cast<std::uint8_t*>(out.mutable_data());
        run_interruptible([&] { f.ball_mask(d); });
        return out;
      }, "A bool per ball of the unfiltered lattice: kept or not.")
      .def("beam_mask", [](const FilteredLattice& f) {
        steady::require_memory(static_cast<std::uint64_t>(f.lattice().beam_count() + f.lattice().ball_count()),
                               "beam_mask(): a byte per beam and ball of " +
                                   std::to_string(f.lattice().beam_count() + f.lattice().ball_count()),
                               "query a region (query_ball) or test beams one at a time");
        py::array_t<bool> out(static_cast<py::ssize_t>(f.lattice().beam_count()));
        auto* d = reinterpret_cast<std::uint8_t*>(out.mutable_data());
        run_interruptible([&] { f.beam_mask(d); });
        return out;
      }, "A bool per beam of the unfiltered lattice: kept when both its nodes are.")
      .def("query_ball", [](const FilteredLattice& f, py::handle center, py::handle radius) {
        const Ball q = query_ball_arg(center, radius);
        steady::BallQueryResult r;
        run_interruptible([&] { r = f.query_ball(q); });
        return result_arrays(r);
      }, py::arg("center"), py::arg("radius"))
      .def("contains", [](const FilteredLattice& f, py::handle points) { return contains_impl(f, points); }, py::arg("points"))
      .def("distance", [](const FilteredLattice& f, py::handle points, double bound) { return distance_impl(f, points, bound); },
           py::arg("points"), py::arg("bound") = kInf)
      .def("raycast",
           [](const FilteredLattice& f, py::handle o, py::handle d, double max_distance) {
             return raycast_impl(f, o, d, max_distance);
           },
           py::arg("origins"), py::arg("directions"), py::arg("max_distance") = kInf)
      .def("voxelize", [](const FilteredLattice& f, py::handle lo, py::handle hi, py::handle shape) {
        return voxelize_impl(f, lo, hi, shape);
      }, py::arg("lo"), py::arg("hi"), py::arg("shape"))
      .def("__repr__", [](const FilteredLattice& f) {
        return "<FilteredLattice of " + std::to_string(f.lattice().ball_count()) + " balls, " +
               (f.filter() ? f.filter()->describe() : std::string("no filter")) + ">";
      });
}

}  // namespace

void bind_queries(py::module_& m) {
  bind_lattice_queries(m);
  bind_filters(m);
  bind_filtered_lattice(m);
}

}  // namespace steadypy
