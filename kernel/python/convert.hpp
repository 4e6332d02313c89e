#pragma once
// Conversions between Python values and kernel types. Every failure is a ValueError naming the parameter.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <string>

#include "steady/core/frame.hpp"
#include "steady/core/progress.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/core/vec.hpp"

namespace steadypy {

namespace py = pybind11;

[[noreturn]] void value_error(const std::string& name, const std::string& what);

double to_double(py::handle value, const std::string& name);
std::int64_t to_int(py::handle value, const std::string& name);
steady::Vec3 to_vec3(py::handle value, const std::string& name);
steady::Vec2 to_vec2(py::handle value, const std::string& name);
// A frame (origin, x, y, z).
steady::Frame to_frame(py::handle value, const std::string& name);
// Points as an N x 3 float64 array (a single point (3,) is accepted as 1 x 3); `single` tells which.
py::array_t<double> to_points(py::handle value, const std::string& name, int dims, bool* single);

py::array_t<double> vec3_array(const steady::Vec3& v);

std::vector<steady::TemplateNode> to_nodes(py::handle value);
std::vector<steady::BeamPattern> to_beams(py::handle value);
steady::Counts to_counts(py::handle value);
std::vector<steady::NodeId> to_omitted(py::handle value);

// Copies `values` into the caller's stats dict (a Python argument `stats`: None, or a dict to fill).
void fill_stats(const py::object& target, const py::dict& values);
// Refuses a stats argument that is neither None nor a dict before any work starts (not after minutes of it).
void require_stats_target(const py::object& target);

// A kernel progress callback from a Python callable `report(fraction)` (None: no reporting). The callable runs
// with the GIL held, on the calling thread only; returning False cancels (steadylattice.Cancelled is raised).
// An exception raised by the callable cancels too, and is raised again by rethrow_callback_error(). With or
// without a callable, the callback runs Python's signal handlers first: Ctrl-C, which only sets a flag while the
// kernel works without the GIL, cancels the call and KeyboardInterrupt is raised.
struct PythonProgress {
  explicit PythonProgress(py::object report);
  steady::Progress::Callback callback();
  void rethrow_callback_error();

 private:
  py::object report_;
  py::object error_type_, error_value_, error_trace_;
};

// Runs `work(progress)` with the GIL released, reporting to the Python callable `report` (or None): Cancelled
// becomes steadylattice.Cancelled, or the callable's own exception when it raised one.
template <class Work>
auto run_with_progress(const py::object& report, Work&& work) {
  if (!report.is_none() && !PyCallable_Check(report.ptr()))
    value_error("progress", "expected a callable progress(fraction) -> bool, or None");
  PythonProgress python(report);
  steady::Progress progress(python.callback());
  try {
    py::gil_scoped_release release;
    const steady::ProgressScope scope(&progress);  // for the kernel's code that polls instead of being handed one
    return work(progress);
  } catch (const steady::Cancelled&) {
    python.rethrow_callback_error();
    throw;
  }
}

// Runs `work()` with the GIL released, interruptible by Ctrl-C (the kernel polls the current progress; see
// PythonProgress): for long calls that report no progress of their own.
template <class Work>
auto run_interruptible(Work&& work) {
  return run_with_progress(py::none(), [&](steady::Progress&) { return work(); });
}

}  // namespace steadypy
