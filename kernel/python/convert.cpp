#include "convert.hpp"

#include <cmath>

namespace steadypy {

using steady::Vec2;
using steady::Vec3;

void value_error(const std::string& name, const std::string& what) { throw py::value_error(name + ": " + what); }

void require_stats_target(const py::object& target) {
  if (!target.is_none() && !py::isinstance<py::dict>(target)) value_error("stats", "expected a dict to fill, or None");
}

void fill_stats(const py::object& target, const py::dict& values) {
  if (target.is_none()) return;
  require_stats_target(target);
  py::dict d = target.cast<py::dict>();
  for (auto item : values) d[item.first] = item.second;
}

double to_double(py::handle value, const std::string& name) {
  if (!py::isinstance<py::float_>(value) && !py::isinstance<py::int_>(value) &&
      !py::hasattr(value, "__float__"))
    value_error(name, "expected a number");
  const double x = py::cast<double>(py::float_(py::reinterpret_borrow<py::object>(value)));
  if (!std::isfinite(x)) value_error(name, "must be a finite number (got " + std::to_string(x) + ")");
  return x;
}

std::int64_t to_int(py::handle value, const std::string& name) {
  if (py::isinstance<py::bool_>(value) || !py::hasattr(value, "__index__"))
    value_error(name, "expected an integer");
  return py::cast<std::int64_t>(py::int_(py::reinterpret_borrow<py::object>(value)));
}

namespace {
py::sequence as_sequence(py::handle value, const std::string& name, std::size_t size, const char* what) {
  if (py::isinstance<py::str>(value) || !py::isinstance<py::sequence>(value)) {
    if (py::isinstance<py::array>(value)) return py::reinterpret_borrow<py::sequence>(value.attr("tolist")());
    value_error(name, std::string("expected ") + what);
  }
  auto seq = py::reinterpret_borrow<py::sequence>(value);
  if (size && seq.size() != size) value_error(name, std::string("expected ") + what);
  return seq;
}
}  // namespace

Vec3 to_vec3(py::handle value, const std::string& name) {
  auto s = as_sequence(value, name, 3, "3 numbers (x, y, z)");
  return {to_double(s[0], name + "[0]"), to_double(s[1], name + "[1]"), to_double(s[2], name + "[2]")};
}

Vec2 to_vec2(py::handle value, const std::string& name) {
  auto s = as_sequence(value, name, 2, "2 numbers (x, y)");
  return {to_double(s[0], name + "[0]"), to_double(s[1], name + "[1]")};
}

steady::Frame to_frame(py::handle value, const std::string& name) {
  auto s = as_sequence(value, name, 4, "a frame (origin, x, y, z)");
  steady::Frame f{to_vec3(s[0], name + ".origin"), to_vec3(s[1], name + ".x"), to_vec3(s[2], name + ".y"),
                  to_vec3(s[3], name + ".z")};
  steady::validate_frame(f, name.c_str());
  return f;
}

py::array_t<double> to_points(py::handle value, const std::string& name, int dims, bool* single) {
  py::array_t<double, py::array::c_style | py::array::forcecast> a;
  try {
    a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(value);
  } catch (const py::error_already_set&) {
    a = {};
  }
  if (!a) value_error(name, "expected an array of points");
  *single = a.ndim() == 1;
  if (*single) {
    if (a.shape(0) != dims) value_error(name, "expected " + std::to_string(dims) + " coordinates");
    a = a.reshape({py::ssize_t(1), py::ssize_t(dims)});
  }
  if (a.ndim() != 2 || a.shape(1) != dims)
    value_error(name, "expected an N x " + std::to_string(dims) + " array of points");
  const double* p = a.data();
  for (py::ssize_t q = 0; q < a.size(); ++q)
    if (!std::isfinite(p[q])) value_error(name, "contains a NaN or infinite coordinate (point " + std::to_string(q / dims) + ")");
  return a;
}

py::array_t<double> vec3_array(const Vec3& v) {
  py::array_t<double> a(3);
  auto m = a.mutable_unchecked<1>();
  m(0) = v.x;
  m(1) = v.y;
  m(2) = v.z;
  return a;
}

std::vector<steady::TemplateNode> to_nodes(py::handle value) {
  auto seq = as_sequence(value, "nodes", 0, "a list of ((x, y, z), radius)");
  std::vector<steady::TemplateNode> nodes;
  for (std::size_t n = 0; n < seq.size(); ++n) {
    const std::string name = "nodes[" + std::to_string(n) + "]";
    auto item = as_sequence(seq[n], name, 2, "((x, y, z), radius)");
    nodes.push_back({to_vec3(item[0], name + ".center"), to_double(item[1], name + ".radius")});
  }
  return nodes;
}

std::vector<steady::BeamPattern> to_beams(py::handle value) {
  auto seq = as_sequence(value, "beams", 0, "a list of (n1, di, dj, dk, n2) or (n1, di, dj, dk, n2, r1, r2)");
  std::vector<steady::BeamPattern> beams;
  for (std::size_t p = 0; p < seq.size(); ++p) {
    const std::string name = "beams[" + std::to_string(p) + "]";
    auto item = as_sequence(seq[p], name, 0, "(n1, di, dj, dk, n2) or (n1, di, dj, dk, n2, r1, r2)");
    if (item.size() != 5 && item.size() != 7)
      value_error(name, "expected (n1, di, dj, dk, n2) or (n1, di, dj, dk, n2, r1, r2)");
    auto small = [&](int at, const char* field) {
      const std::int64_t x = to_int(item[at], name + "." + field);
      if (x < -1000000000 || x > 1000000000) value_error(name + "." + field, "integer out of range");
      return static_cast<int>(x);
    };
    steady::BeamPattern b;
    b.from = small(0, "from");
    b.di = small(1, "di");
    b.dj = small(2, "dj");
    b.dk = small(3, "dk");
    b.to = small(4, "to");
    if (item.size() == 7) {
      b.from_radius = to_double(item[5], name + ".radii[0]");
      b.to_radius = to_double(item[6], name + ".radii[1]");
    }
    beams.push_back(b);
  }
  return beams;
}

steady::Counts to_counts(py::handle value) {
  auto s = as_sequence(value, "counts", 3, "3 integers (u, v, w)");
  return {to_int(s[0], "counts.u"), to_int(s[1], "counts.v"), to_int(s[2], "counts.w")};
}

std::vector<steady::NodeId> to_omitted(py::handle value) {
  std::vector<steady::NodeId> out;
  if (value.is_none()) return out;
  auto seq = as_sequence(value, "omitted", 0, "a list of (i, j, k, n)");
  for (std::size_t q = 0; q < seq.size(); ++q) {
    const std::string name = "omitted[" + std::to_string(q) + "]";
    auto item = as_sequence(seq[q], name, 4, "(i, j, k, n)");
    const std::int64_t n = to_int(item[3], name + ".n");
    if (n < 0 || n > 2147483647) value_error(name + ".n", "node index out of range");
    out.push_back({to_int(item[0], name + ".i"), to_int(item[1], name + ".j"), to_int(item[2], name + ".k"),
                   static_cast<int>(n)});
  }
  return out;
}

PythonProgress::PythonProgress(py::object report) : report_(std::move(report)) {}

steady::Progress::Callback PythonProgress::callback() {
  return [this](double fraction) {
    py::gil_scoped_acquire gil;
    try {
      if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // KeyboardInterrupt from Ctrl-C
      if (report_.is_none()) return true;
      py::object answer = report_(fraction);
      return answer.is_none() || answer.cast<bool>();
    } catch (py::error_already_set& e) {
      error_type_ = e.type();
      error_value_ = e.value();
      error_trace_ = e.trace();
      return false;
    }
  };
}

void PythonProgress::rethrow_callback_error() {
  if (!error_type_) return;
  PyErr_Restore(error_type_.release().ptr(), error_value_.release().ptr(), error_trace_.release().ptr());
  throw py::error_already_set();
}

}  // namespace steadypy
