// Python bindings of Similarity (3D) and Similarity2 (planar): thin conversions, no logic.
#include <pybind11/numpy.h>
#include <pybind11/operators.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "steady/core/similarity.hpp"
#include "steady/core/similarity2d.hpp"

namespace steadypy {

using steady::Similarity;
using steady::Similarity2;
using steady::Vec3;

namespace {

// Applies `map` to every row of an N x dims array (or to one point), returning the same shape.
template <int Dims, class Map>
py::array_t<double> map_points(py::handle points, const char* name, Map map) {
  bool single = false;
  auto in = to_points(points, name, Dims, &single);
  const py::ssize_t n = in.shape(0);
  py::array_t<double> out({n, py::ssize_t(Dims)});
  const double* src = in.data();
  double* dst = out.mutable_data();
  {
    py::gil_scoped_release release;
    for (py::ssize_t q = 0; q < n; ++q) map(src + Dims * q, dst + Dims * q);
  }
  if (single) return out.reshape({py::ssize_t(Dims)});
  return out;
}

py::tuple frame_tuple(const steady::Frame& f) {
  return py::make_tuple(vec3_array(f.origin), vec3_array(f.x), vec3_array(f.y), vec3_array(f.z));
}

}  // namespace

namespace {
void bind_similarity2(py::module_& m);
}  // namespace

void bind_similarity(py::module_& m) {
  py::class_<Similarity>(m, "Similarity", R"doc(
An orientation-preserving similarity p -> s R p + t of 3D space (translation, rotation, screw, dilation
or swirl). Stored by its generator, so that real powers S.power(t) are exact, and a rotation built with
more than a half turn keeps its winding. S * T applies T first, then S.)doc")
      .def(py::init<>(), "The identity.")
      .def_static("identity", &Similarity::identity)
      .def_static("translation", [](py::handle v) { return Similarity::translation(to_vec3(v, "v")); }, py::arg("v"))
      .def_static(
          "rotation",
          [](double angle, py::handle axis, py::handle point) {
            return Similarity::rotation(angle, to_vec3(axis, "axis"), to_vec3(point, "point"));
          },
          py::arg("angle"), py::arg("axis"), py::arg("point") = py::make_tuple(0.0, 0.0, 0.0),
          "Rotation by `angle` radians (any real) about the line through `point` along `axis`.")
      .def_static(
          "dilation",
          [](double scale, py::handle center) { return Similarity::dilation(scale, to_vec3(center, "center")); },
          py::arg("scale"), py::arg("center") = py::make_tuple(0.0, 0.0, 0.0))
      .def_static(
          "screw",
          [](double angle, py::handle axis, py::handle point, double distance) {
            return Similarity::screw(angle, to_vec3(axis, "axis"), to_vec3(point, "point"), distance);
          },
          py::arg("angle"), py::arg("axis"), py::arg("point"), py::arg("distance"),
          "Rotation about the line (point, axis) and translation by `distance` along it.")
      .def_static(
          "swirl",
          [](double angle, py::handle axis, py::handle center, double scale) {
            return Similarity::swirl(angle, to_vec3(axis, "axis"), to_vec3(center, "center"), scale);
          },
          py::arg("angle"), py::arg("axis"), py::arg("center"), py::arg("scale"),
          "Rotation about the line (center, axis) and dilation by `scale` about `center`.")
      .def_static(
          "from_frames",
          [](py::handle a, py::handle b) { return Similarity::from_frames(to_frame(a, "a"), to_frame(b, "b")); },
          py::arg("a"), py::arg("b"),
          "The similarity taking frame a to frame b; a frame is (origin, x, y, z) with |x| = |y| = |z| its scale.")
      .def_static("from_frame", [](py::handle f) { return Similarity::from_frame(to_frame(f, "frame")); },
                  py::arg("frame"), "The similarity taking the unit frame to `frame`.")
      .def_static(
          "from_generator",
          [](double log_scale, py::handle w, py::handle v) {
            return Similarity::from_generator(log_scale, to_vec3(w, "rotation_vector"), to_vec3(v, "velocity"));
          },
          py::arg("log_scale"), py::arg("rotation_vector"), py::arg("velocity"))
      .def_static(
          "from_matrix",
          [](py::handle matrix) {
            auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(matrix);
            if (!a || a.ndim() != 2 || a.shape(0) < 3 || a.shape(1) != 4) value_error("matrix", "expected a 4 x 4 or 3 x 4 array");
            auto r = a.unchecked<2>();
            steady::Mat3 linear;
            for (int c = 0; c < 3; ++c)
              for (int k = 0; k < 3; ++k) linear[c][k] = r(k, c);
            // the scale of a scaled rotation is the cube root of its determinant
            const double s = std::cbrt(glm::determinant(linear));
            if (!(s > 0.0) || !std::isfinite(s))
              value_error("matrix", "the linear part must be a scaled rotation (positive determinant)");
            const steady::Mat3 rot = linear / s;
            return Similarity::from_matrix(s, rot, Vec3(r(0, 3), r(1, 3), r(2, 3)));
          },
          py::arg("matrix"), "From a 4 x 4 homogeneous matrix whose linear part is a scaled rotation.")
      .def_static("from_json", &steady::similarity_from_json, py::arg("text"))
      .def("to_json", &steady::similarity_to_json)
      .def(py::self * py::self)
      .def("power", &Similarity::power, py::arg("t"), "The real power S^t (closed form).")
      .def("inverse", &Similarity::inverse)
      .def(
          "apply",
          [](const Similarity& s, py::handle points) {
            return map_points<3>(points, "points", [&s](const double* p, double* q) {
              const Vec3 r = s.apply_point({p[0], p[1], p[2]});
              q[0] = r.x, q[1] = r.y, q[2] = r.z;
            });
          },
          py::arg("points"), "Images of an N x 3 array of points (or of one point).")
      .def(
          "apply_vectors",
          [](const Similarity& s, py::handle vectors) {
            return map_points<3>(vectors, "vectors", [&s](const double* p, double* q) {
              const Vec3 r = s.apply_vector({p[0], p[1], p[2]});
              q[0] = r.x, q[1] = r.y, q[2] = r.z;
            });
          },
          py::arg("vectors"))
      .def("frame", [](const Similarity& s) { return frame_tuple(s.frame()); }, "The image of the unit frame.")
      .def_property_readonly("scale", &Similarity::scale)
      .def_property_readonly("kind", [](const Similarity& s) { return std::string(steady::to_string(s.kind())); })
      .def_property_readonly("angle", [](const Similarity& s) { return s.canonical().angle; })
      .def_property_readonly("axis", [](const Similarity& s) { return vec3_array(s.canonical().axis); })
      .def_property_readonly("point", [](const Similarity& s) { return vec3_array(s.canonical().point); },
                             "The fixed point (dilation, swirl) or the axis point nearest the origin (rotation, screw).")
      .def_property_readonly("distance", [](const Similarity& s) { return s.canonical().distance; })
      .def_property_readonly("translation_part", [](const Similarity& s) { return vec3_array(s.translation_part()); },
                             "The translation part t of p -> s R p + t.")
      .def_property_readonly("rotation_matrix",
                             [](const Similarity& s) {
                               py::array_t<double> a({3, 3});
                               auto m = a.mutable_unchecked<2>();
                               for (int r = 0; r < 3; ++r)
                                 for (int c = 0; c < 3; ++c) m(r, c) = s.rotation_matrix()[c][r];
                               return a;
                             })
      .def_property_readonly("matrix",
                             [](const Similarity& s) {
                               py::array_t<double> a({4, 4});
                               auto m = a.mutable_unchecked<2>();
                               for (int r = 0; r < 4; ++r)
                                 for (int c = 0; c < 4; ++c) m(r, c) = 0.0;
                               for (int r = 0; r < 3; ++r) {
                                 for (int c = 0; c < 3; ++c) m(r, c) = s.scale() * s.rotation_matrix()[c][r];
                                 m(r, 3) = s.translation_part()[r];
                               }
                               m(3, 3) = 1.0;
                               return a;
                             })
      .def_property_readonly("generator",
                             [](const Similarity& s) {
                               return py::make_tuple(s.log_scale(), vec3_array(s.rotation_vector()),
                                                     vec3_array(s.velocity()));
                             })
      .def("approx_equal", [](const Similarity& a, const Similarity& b, double tol) { return a.map_distance(b) <= tol; },
           py::arg("other"), py::arg("tol") = 1e-9)
      .def("__repr__", [](const Similarity& s) { return "<Similarity " + s.describe() + ">"; });

  bind_similarity2(m);
}

namespace {

// The planar similarity z -> a z + b.
void bind_similarity2(py::module_& m) {
  py::class_<Similarity2>(m, "Similarity2", "An orientation-preserving similarity of the plane, z -> a z + b.")
      .def(py::init<>())
      .def_static("translation", [](py::handle v) { return Similarity2::translation(to_vec2(v, "v")); }, py::arg("v"))
      .def_static(
          "spiral",
          [](double angle, double scale, py::handle center) {
            return Similarity2::spiral(angle, scale, to_vec2(center, "center"));
          },
          py::arg("angle"), py::arg("scale"), py::arg("center"))
      .def_static(
          "from_point_pairs",
          [](py::handle a, py::handle b, py::handle c, py::handle d) {
            return Similarity2::from_point_pairs(to_vec2(a, "a"), to_vec2(b, "b"), to_vec2(c, "c"), to_vec2(d, "d"));
          },
          py::arg("a"), py::arg("b"), py::arg("c"), py::arg("d"), "The similarity taking a to c and b to d.")
      .def(py::self * py::self)
      .def("power", &Similarity2::power, py::arg("t"))
      .def("inverse", &Similarity2::inverse)
      .def(
          "apply",
          [](const Similarity2& s, py::handle points) {
            return map_points<2>(points, "points", [&s](const double* p, double* q) {
              const steady::Vec2 r = s.apply({p[0], p[1]});
              q[0] = r.x, q[1] = r.y;
            });
          },
          py::arg("points"))
      .def_property_readonly("scale", &Similarity2::scale)
      .def_property_readonly("angle", &Similarity2::angle)
      .def_property_readonly("kind", [](const Similarity2& s) { return std::string(steady::to_string(s.kind())); })
      .def_property_readonly("fixed_point", [](const Similarity2& s) {
        const steady::Vec2 f = s.fixed_point();
        return py::make_tuple(f.x, f.y);
      });
}

}  // namespace

}  // namespace steadypy
