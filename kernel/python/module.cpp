// The Python module `steadylattice`: the steady kernel for scripts, tests and the FreeCAD workbench.
#include <Standard_Failure.hxx>
#include <Standard_OutOfMemory.hxx>
#include <pybind11/pybind11.h>

#include <string>

#include "steady/core/errors.hpp"
#include "steady/core/memory_budget.hpp"
#include "steady/core/numeric_range.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "steady/core/progress.hpp"

namespace steadypy {
namespace py = pybind11;
void bind_similarity(py::module_& m);
void bind_lattice(py::module_& m);
void bind_brep(py::module_& m);
void bind_connectors(py::module_& m);
void bind_queries(py::module_& m);
void bind_properties(py::module_& m);
void bind_presets(py::module_& m);
void bind_mesh(py::module_& m);
void bind_slices(py::module_& m);
void bind_cots(py::module_& m);
void bind_steady_map2(py::module_& m);
}  // namespace steadypy

PYBIND11_MODULE(steadylattice, m) {
  namespace py = pybind11;
  m.doc() = "Steady lattices: similarities, steady brick lattices, their file format (the LatticeWorkbench kernel).";
  // InvalidInput derives from std::invalid_argument, which pybind11 already raises as ValueError.
  // Raised when a progress callback returned False: the operation stopped and changed nothing.
  static py::exception<steady::Cancelled> cancelled(m, "Cancelled");
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const steady::ResourceLimit& e) {
      PyErr_SetString(PyExc_MemoryError, e.what());
    } catch (const std::bad_alloc& e) {  // an allocation no estimate refused: give the figures pybind11 would not
      PyErr_SetString(PyExc_MemoryError,
                      (std::string("out of memory (") + e.what() + ") with " + steady::memory_budget_description() +
                       ": the request was larger than its estimate; make it smaller (a preview, a mesh, a 3MF beam "
                       "lattice, a filter or a region)").c_str());
    } catch (const steady::Cancelled& e) {
      PyErr_SetString(cancelled.ptr(), e.what());
    } catch (const Standard_OutOfMemory& e) {  // OpenCASCADE's allocator under a memory limit
      PyErr_SetString(PyExc_MemoryError, (std::string("OpenCASCADE ran out of memory: ") + e.GetMessageString()).c_str());
    } catch (const Standard_Failure& e) {  // not a std::exception: pybind11 would only say "unknown exception"
      PyErr_SetString(PyExc_RuntimeError, (std::string("OpenCASCADE: ") + e.DynamicType()->Name() + ": " +
                                           e.GetMessageString()).c_str());
    }
  });
  m.attr("FORMAT_VERSION") = steady::kLatticeFormatVersion;
  // The supported numerical range (docs/design.md), for callers that check their own parameters against it.
  m.attr("MAX_COORDINATE") = steady::kMaxCoordinate;
  m.attr("MAX_ANGLE") = steady::kMaxAngle;
  m.attr("MAX_LOG_SCALE") = steady::kMaxLogScale;
  steadypy::bind_similarity(m);
  steadypy::bind_lattice(m);
  steadypy::bind_brep(m);
  steadypy::bind_connectors(m);
  steadypy::bind_queries(m);
  steadypy::bind_properties(m);
  steadypy::bind_presets(m);
  steadypy::bind_mesh(m);
  steadypy::bind_slices(m);
  steadypy::bind_cots(m);
  steadypy::bind_steady_map2(m);
}
