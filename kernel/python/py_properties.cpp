// Python bindings of the integral properties, the clean check and density targeting: methods added to
// steadylattice.Lattice. Thin conversions; the GIL is released while the kernel works.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "steady/query/hub_overlaps.hpp"
#include "steady/properties/lattice_properties.hpp"
#include "steady/properties/radius_scaling.hpp"

namespace steadypy {

using steady::Lattice;

namespace {

py::array_t<double> mat3_array(const steady::Mat3& m) {
  py::array_t<double> out({py::ssize_t(3), py::ssize_t(3)});
  auto a = out.mutable_unchecked<2>();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) a(r, c) = m[c][r];  // glm is column-major
  return out;
}

py::dict properties_dict(const steady::LatticeProperties& p) {
  py::dict d;
  d["volume"] = p.volume;
  d["area"] = p.area;
  d["centroid"] = vec3_array(p.centroid);
  d["inertia"] = mat3_array(p.inertia);
  d["clean_verified"] = p.clean_verified;
  d["beam_shapes"] = p.beam_shapes;
  d["hub_shapes"] = p.hub_shapes;
  d["overlapping_hub_shapes"] = p.overlapping_hub_shapes;
  d["clean"] = p.clean_verified && p.overlap_count == 0;
  d["overlap_count"] = p.overlap_count;
  d["overlap_description"] = p.overlap_description;
  d["moved_cuts"] = p.moved_cuts;
  d["union_clusters"] = p.union_clusters;
  d["union_hubs"] = p.union_hubs;
  d["union_error"] = p.union_error;
  return d;
}

py::tuple node_tuple(const steady::NodeId& id) { return py::make_tuple(id.i, id.j, id.k, id.n); }

steady::RadiusScaleOptions scale_options(bool check_clean, double tolerance) {
  steady::RadiusScaleOptions o;
  o.check_clean = check_clean;
  if (!(tolerance > 0.0 && tolerance < 1.0)) value_error("tolerance", "must be in (0, 1)");
  o.relative_tolerance = tolerance;
  return o;
}

py::dict solution_dict(const steady::RadiusScaleSolution& s) {
  py::dict d;
  d["scale"] = s.scale;
  d["volume"] = s.volume;
  d["evaluations"] = s.evaluations;
  d["clean_verified"] = s.clean_verified;
  return d;
}

}  // namespace

void bind_properties(py::module_& m) {
  auto lattice = py::reinterpret_borrow<py::class_<Lattice>>(m.attr("Lattice"));
  lattice
      .def(
          "properties",
          [](const Lattice& lat, bool check_clean, double tolerance, const py::object& progress, bool union_overlaps) {
            steady::LatticePropertiesOptions o;
            o.check_clean = check_clean;
            o.union_overlaps = union_overlaps;
            if (!(tolerance > 0.0 && tolerance < 1.0)) value_error("tolerance", "must be in (0, 1)");
            o.hub.tolerance = tolerance;
            return properties_dict(
                run_with_progress(progress, [&](steady::Progress& p) { return steady::lattice_properties(lat, o, p); }));
          },
          py::arg("check_clean") = true, py::arg("tolerance") = 1e-12, py::arg("progress") = py::none(),
          py::arg("union_overlaps") = true,
          R"doc(
Integral properties of the lattice in closed form (row and slab sums over similar hubs), density 1:
a dict with 'volume', 'area' (outer surface), 'centroid' (3,), 'inertia' (3x3 about the centroid),
'clean_verified' (the clean check ran on the whole lattice) and the work done ('beam_shapes', 'hub_shapes',
'overlapping_hub_shapes': hubs whose stumps overlap, integrated to `tolerance`).
When hubs of different nodes overlap (the lattice is not clean) they are reported ('clean' False,
'overlap_count' pairs, 'overlap_description' naming the first) and the properties come from the exact union
of the overlapping hubs: beams' cuts moved past crowded hubs' collars when that makes the hubs disjoint
('moved_cuts', no Boolean), else an OpenCASCADE Fuse per cluster ('union_clusters', 'union_hubs',
'union_error'); with
union_overlaps=False such a lattice raises ValueError instead. check_clean=False skips the check and returns
the sum over hubs. Multiply volume and inertia by a density for mass properties.)doc")
      .def(
          "properties_brute_force",
          [](const Lattice& lat) {
            return properties_dict(run_interruptible([&] { return steady::lattice_properties_brute_force(lat); }));
          },
          "The same properties summed over every hub (slow: for checks).")
      .def(
          "hub_overlap_report",
          [](const Lattice& lat, std::size_t max_reports, const py::object& progress) {
            const steady::HubOverlapReport r = run_with_progress(
                progress, [&](steady::Progress& p) { return steady::check_hub_overlaps(lat, max_reports, p); });
            py::list overlaps;
            for (const steady::HubOverlap& o : r.overlaps)
              overlaps.append(py::make_tuple(node_tuple(o.a), node_tuple(o.b), o.detail));
            py::dict d;
            d["clean"] = r.clean();
            d["verified"] = r.verified;
            d["overlap_count"] = r.overlap_count;
            d["overlaps"] = overlaps;
            d["hubs_checked"] = r.hubs_checked;
            d["description"] = r.describe();
            return d;
          },
          py::arg("max_reports") = 100, py::arg("progress") = py::none(),
          R"doc(
Whether hubs of different nodes overlap: a dict with 'clean', 'verified' (False when the lattice is too large
to check), 'overlap_count', 'overlaps' (up to max_reports of ((i,j,k,n), (i,j,k,n), pieces)), 'description'.)doc")
      .def(
          "with_radius_scale",
          [](const Lattice& lat, double scale) { return steady::with_radius_scale(lat, scale); }, py::arg("scale"),
          "A copy with every node radius and beam radius multiplied by scale (positions kept).")
      .def(
          "radius_scale_for_volume",
          [](const Lattice& lat, double target, bool check_clean, double tolerance) {
            const steady::RadiusScaleOptions o = scale_options(check_clean, tolerance);
            // tens of volume evaluations over every distinct hub: interruptible (Ctrl-C)
            return solution_dict(run_interruptible([&] { return steady::radius_scale_for_volume(lat, target, o); }));
          },
          py::arg("target_volume"), py::arg("check_clean") = true, py::arg("tolerance") = 1e-10,
          "The radius scale reaching target_volume: a dict with 'scale', 'volume', 'evaluations', 'clean_verified'.")
      .def(
          "scale_radii_for_volume",
          [](const Lattice& lat, double target, bool check_clean, double tolerance) {
            const steady::RadiusScaleOptions o = scale_options(check_clean, tolerance);
            return run_interruptible(
                [&] { return steady::with_radius_scale(lat, steady::radius_scale_for_volume(lat, target, o).scale); });
          },
          py::arg("target_volume"), py::arg("check_clean") = true, py::arg("tolerance") = 1e-10,
          R"doc(
A new Lattice, every radius scaled so that its volume is target_volume (relative tolerance `tolerance`).
Raises ValueError naming target_volume when no clean lattice reaches it. radius_scale_for_volume gives the scale.)doc")
      .def(
          "scale_radii_for_density",
          [](const Lattice& lat, double density, const py::object& envelope, bool check_clean) {
            const steady::RadiusScaleOptions o = scale_options(check_clean, 1e-10);
            const double env = envelope.is_none() ? steady::cell_envelope_volume(lat) : to_double(envelope, "envelope_volume");
            return run_interruptible(
                [&] { return steady::with_radius_scale(lat, steady::radius_scale_for_density(lat, density, env, o).scale); });
          },
          py::arg("relative_density"), py::arg("envelope_volume") = py::none(), py::arg("check_clean") = true,
          "A new Lattice whose volume is relative_density times envelope_volume (default: cell_envelope_volume()).")
      .def(
          "scale_radii_for_mass",
          [](const Lattice& lat, double mass, double density, bool check_clean) {
            const steady::RadiusScaleOptions o = scale_options(check_clean, 1e-10);
            return run_interruptible(
                [&] { return steady::with_radius_scale(lat, steady::radius_scale_for_mass(lat, mass, density, o).scale); });
          },
          py::arg("mass"), py::arg("density"), py::arg("check_clean") = true,
          "A new Lattice of the given mass at the given density (mass / density is the target volume).")
      .def("cell_envelope_volume", &steady::cell_envelope_volume,
           "The volume of the lattice's cells (each group's template cell mapped by its similarity), the default "
           "envelope of relative density.");
}

}  // namespace steadypy
