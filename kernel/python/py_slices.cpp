// Python bindings of the slices: one layer as a numpy bitmap, and the whole stack written as PNG (and SVG) layers.
// Thin: conversions only; the GIL is released while the kernel works.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstring>

#include "convert.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/mesh/slices.hpp"

namespace steadypy {

using steady::Lattice;

void bind_slices(py::module_& m) {
  auto lattice = py::reinterpret_borrow<py::class_<Lattice>>(m.attr("Lattice"));
  lattice.def(
      "slice",
      [](const Lattice& lat, double z, double pixel_size) {
        const steady::FlatLattice f = steady::flatten(lat);
        steady::SliceOptions whole;
        whole.layer_height = pixel_size;
        whole.pixel_size = pixel_size;
        const steady::LatticeSlicer box(f, whole);
        steady::SliceOptions at = whole;
        at.box_min = steady::Vec3(box.origin().x, box.origin().y, z - 0.5 * pixel_size);
        at.box_max = steady::Vec3(box.origin().x + box.width() * pixel_size, box.origin().y + box.height() * pixel_size,
                                  z + 0.5 * pixel_size);
        const steady::LatticeSlicer slicer(f, at);
        std::vector<std::uint8_t> pixels;
        {
          py::gil_scoped_release release;
          slicer.rasterize(0, pixels);
        }
        py::array_t<std::uint8_t> image({static_cast<py::ssize_t>(slicer.height()), static_cast<py::ssize_t>(slicer.width())});
        std::memcpy(image.mutable_data(), pixels.data(), pixels.size());
        return py::make_tuple(image, py::make_tuple(slicer.origin().x, slicer.origin().y));
      },
      py::arg("z"), py::arg("pixel_size"),
      "The lattice's section by the plane at height z as a bitmap: (pixels uint8 rows x columns, 1 inside, row 0 at "
      "the lowest y; (x0, y0) the corner of pixel (0, 0)), pixel centers at (x0, y0) + ((i, j) + 1/2) pixel_size, "
      "over the lattice's bounding box grown by a pixel. Each element crossing the plane is rasterised from its exact "
      "cross-section, row by row in closed form.");
  lattice.def(
      "write_slices",
      [](const Lattice& lat, const std::string& directory, double layer_height, double pixel_size, bool svg,
         const py::object& progress, const py::object& stats) {
        require_stats_target(stats);
        steady::SliceOptions options;
        options.layer_height = layer_height;
        options.pixel_size = pixel_size;
        const steady::SliceStats s = run_with_progress(progress, [&](steady::Progress& p) {
          return steady::write_slices(steady::flatten(lat), options, directory, svg, p);
        });
        py::dict d;
        d["layers"] = s.layers;
        d["width"] = s.width;
        d["height"] = s.height;
        d["element_layers"] = s.element_layers;
        d["raster_seconds"] = s.raster_seconds;
        d["write_seconds"] = s.write_seconds;
        fill_stats(stats, d);
      },
      py::arg("directory"), py::arg("layer_height"), py::arg("pixel_size"), py::arg("svg") = false,
      py::arg("progress") = py::none(), py::arg("stats") = py::none(),
      "Writes the lattice as layers for a printer into an existing directory: layer_00000.png, ... (1-bit "
      "grayscale, white = solid, +y up), layer k the section at z = z_min + (k + 1/2) layer_height of the "
      "lattice's bounding box grown by a pixel; with svg, layer_00000.svg too (a circle per ball, a polygon per beam "
      "through its exact row ends, in model units). stats: layers, width, height, element_layers, raster_seconds "
      "and write_seconds (summed over threads).");
}

}  // namespace steadypy
