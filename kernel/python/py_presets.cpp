// Python bindings of the preset unit cells (steady/lattice/presets.hpp): the workbench's presets are these.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "steady/lattice/presets.hpp"

namespace steadypy {

namespace {

py::tuple vec3_tuple(const steady::Vec3& v) { return py::make_tuple(v.x, v.y, v.z); }


}  // namespace

void bind_presets(py::module_& m) {
  m.def("preset_names", &steady::preset_names, "The names of the preset unit cells.");
  m.def(
      "preset",
      [](const std::string& name) {
        const steady::PresetCell& cell = steady::preset_cell(name, "name");
        py::list basis, patterns;
        for (const steady::Vec3& b : cell.basis) basis.append(vec3_tuple(b));
        for (const steady::BeamPattern& p : steady::preset_beam_patterns(cell))
          patterns.append(py::make_tuple(p.from, p.di, p.dj, p.dk, p.to));
        py::dict d;
        d["name"] = cell.name;
        d["basis"] = basis;
        d["aspect"] = vec3_tuple(cell.aspect);
        d["neighbour_distance"] = cell.neighbour_distance;
        d["corner_beams_only"] = cell.corner_beams_only;
        d["patterns"] = patterns;
        return d;
      },
      py::arg("name"),
      "A preset unit cell: basis (node positions as fractions of the cell), aspect (cell edge per axis in units of "
      "the cell size), neighbour_distance (cell-size units), corner_beams_only, and the beam patterns "
      "(n1, di, dj, dk, n2) joining nearest neighbours.");
  m.def(
      "preset_outside_nodes",
      [](const std::string& name, const std::array<std::int64_t, 3>& cells) {
        py::list out;
        for (const steady::NodeId& id : steady::preset_outside_nodes(steady::preset_cell(name, "name"), cells))
          out.append(py::make_tuple(id.i, id.j, id.k, id.n));
        return out;
      },
      py::arg("name"), py::arg("cells"),
      "The nodes (i, j, k, n) of groups 0..cells that lie outside the box of `cells` whole cells.");
  auto lattice = py::reinterpret_borrow<py::class_<steady::Lattice>>(m.attr("Lattice"));
  lattice.def_static("preset", &steady::preset_lattice, py::arg("name"), py::arg("cells"), py::arg("cell_size"),
                     py::arg("node_radius"), py::arg("beam_radius") = 0.0,
                     "A regular lattice of a preset cell: cells (cu, cv, cw), cell_size, node_radius, beam_radius (0: "
                     "each beam the hull of its balls).");
}

}  // namespace steadypy
