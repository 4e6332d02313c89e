// Python bindings of steady 2-maps and the rectified steady slabs on them: thin conversions, no logic.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "steady/cots/steady_map2.hpp"

namespace steadypy {

using steady::Ball;
using steady::Rectification;
using steady::SteadyMap2;

namespace {

Rectification to_rectification(const std::string& name) {
  if (name == "four points") return Rectification::FourPoints;
  if (name == "least squares") return Rectification::LeastSquares;
  value_error("method", "expected 'four points' or 'least squares' (got '" + name + "')");
}

}  // namespace

void bind_steady_map2(py::module_& m) {
  py::class_<SteadyMap2>(m, "SteadyMap2", R"doc(
A steady 2-map M(u, v) = V^v o U^u (O) on the unit square (constructive lattice geometry, 2.6): from five planar
points (from_points) or three frames (from_frames). U and V need not commute; the rectified slab on it (slab) is an
ordinary Lattice whose group (i, j) is V^(j/nv) o U^(i/nu) of one rectified template group.)doc")
      .def_static(
          "from_points",
          [](py::handle a, py::handle b, py::handle c, py::handle d, py::handle e) {
            return SteadyMap2::from_points(to_vec2(a, "a"), to_vec2(b, "b"), to_vec2(c, "c"), to_vec2(d, "d"),
                                           to_vec2(e, "e"));
          },
          py::arg("a"), py::arg("b"), py::arg("c"), py::arg("d"), py::arg("e"),
          "The planar map with M(0,0) = a, M(1,0) = b, M(0,1) = c, M(1,1) = d, M(1/2,0) = e (points (x, y)).")
      .def_static(
          "from_frames",
          [](py::handle a, py::handle b, py::handle c) {
            return SteadyMap2::from_frames(to_frame(a, "a"), to_frame(b, "b"), to_frame(c, "c"));
          },
          py::arg("a"), py::arg("b"), py::arg("c"),
          "The 3D map whose U takes frame a to b and V takes a to c (frames as for Similarity.from_frames).")
      .def(
          "map",
          [](const SteadyMap2& s, py::handle uv) -> py::array {
            bool single = false;
            auto in = to_points(uv, "uv", 2, &single);
            const py::ssize_t n = in.shape(0);
            py::array_t<double> out({n, py::ssize_t(3)});
            const double* src = in.data();
            double* dst = out.mutable_data();
            for (py::ssize_t q = 0; q < n; ++q) {
              const steady::Vec3 p = s.map(src[2 * q], src[2 * q + 1]);
              for (int k = 0; k < 3; ++k) dst[3 * q + k] = p[k];
            }
            if (single) return out.reshape({py::ssize_t(3)});
            return out;
          },
          py::arg("uv"), "Images of an N x 2 array of (u, v) (or one pair) as N x 3 points.")
      .def("field", &SteadyMap2::field, py::arg("u"), py::arg("v"), "The similarity V^v o U^u (U applied first).")
      .def(
          "warp", [](const SteadyMap2& s, py::handle uvw) { return vec3_array(s.warp(to_vec3(uvw, "uvw"))); },
          py::arg("uvw"), "The image of a domain point (u, v, w); w in units of the map's unit length along u at O.")
      .def(
          "rectify",
          [](const SteadyMap2& s, py::handle center, double radius, const std::string& method) {
            const Ball b = s.rectify(to_vec3(center, "center"), radius, "radius", to_rectification(method));
            return py::make_tuple(vec3_array(b.center), b.radius);
          },
          py::arg("center"), py::arg("radius"), py::arg("method") = "four points",
          "Template rectification: (center, radius) of the sphere through the images of points of the domain ball "
          "(center (u, v, w), radius in domain units): 'four points' at a regular tetrahedron's vertices, or "
          "'least squares' through 32 antipodal pairs.")
      .def(
          "slab",
          [](const SteadyMap2& s, py::handle nodes, py::handle beams, py::handle counts, double beam_ratio,
             const std::string& method) {
            return steady::steady_slab_lattice(s, to_nodes(nodes), to_beams(beams), to_counts(counts), beam_ratio,
                                               to_rectification(method));
          },
          py::arg("nodes"), py::arg("beams"), py::arg("counts"), py::arg("beam_ratio") = 0.0,
          py::arg("method") = "four points",
          "The rectified steady slab: counts (nu, nv, 1) groups; nodes [((s, t, w), r), ...] with s, t in tile units "
          "and w, r in domain units, each rectified; beams as for Lattice, the hull of their balls, or beam_ratio "
          "times their balls' radii.")
      .def_property_readonly("u_similarity", &SteadyMap2::u)
      .def_property_readonly("v_similarity", &SteadyMap2::v)
      .def_property_readonly("origin", [](const SteadyMap2& s) { return vec3_array(s.origin()); })
      .def_property_readonly("normal", [](const SteadyMap2& s) { return vec3_array(s.normal()); })
      .def_property_readonly("unit", &SteadyMap2::unit);
}

}  // namespace steadypy
