// Python bindings of constant-radius lattices: Lattice.connectors() builds the connector families and the rods
// (steady/brep/connectors.hpp), returned as a Connectors object that gives them as arrays and BREP text and
// writes them as STEP. Thin: conversions only; the GIL is released while the kernel works.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/connector_step.hpp"
#include "steady/brep/connectors.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"

namespace steadypy {

using steady::ConnectorParts;
using steady::Lattice;

namespace {

steady::ConnectorParameters connector_parameters(double rod_radius, double sleeve, double reach, double hole,
                                                 double core_bulge, double angle_tolerance, double length_tolerance) {
  steady::ConnectorParameters p;
  p.rod_radius = rod_radius;
  p.sleeve = sleeve;
  p.reach = reach;
  p.hole = hole;
  p.core_bulge = core_bulge;
  p.angle_tolerance = angle_tolerance;
  p.length_tolerance = length_tolerance;
  return p;
}

py::array_t<double> placement_matrices(const steady::ConnectorFamily& family) {
  const std::int64_t n = static_cast<std::int64_t>(family.members.size());
  py::array_t<double> out({n, std::int64_t(4), std::int64_t(4)});
  for (std::int64_t m = 0; m < n; ++m) {
    const steady::ConnectorPlacement& p = family.members[m];
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) out.mutable_at(m, r, c) = r == 3 ? (c == 3 ? 1.0 : 0.0) : (c == 3 ? p.center[r] : p.rotation[c][r]);
  }
  return out;
}

py::dict family_dict(const ConnectorParts& parts, std::size_t k) {
  const steady::ConnectorFamily& family = parts.plan.families[k];
  py::dict d;
  d["name"] = steady::connector_part_name(k);
  d["count"] = family.members.size();
  py::array_t<std::int64_t> balls(static_cast<py::ssize_t>(family.members.size()));
  for (std::size_t m = 0; m < family.members.size(); ++m) balls.mutable_at(m) = family.members[m].ball;
  d["balls"] = balls;
  d["placements"] = placement_matrices(family);
  py::array_t<double> directions({static_cast<py::ssize_t>(family.directions.size()), py::ssize_t(3)});
  for (std::size_t s = 0; s < family.directions.size(); ++s)
    for (int c = 0; c < 3; ++c) directions.mutable_at(s, c) = family.directions[s][c];
  d["directions"] = directions;
  d["volume"] = parts.volumes[k];
  d["faces"] = steady::face_count(parts.templates[k]);
  d["valid"] = steady::is_valid(parts.templates[k]);
  d["build_seconds"] = parts.build_seconds[k];
  return d;
}

py::dict rods_dict(const steady::ConnectorPlan& plan) {
  const py::ssize_t n = static_cast<py::ssize_t>(plan.rods.size());
  py::array_t<std::int64_t> beams(n), a(n), b(n);
  py::array_t<double> starts({n, py::ssize_t(3)}), ends({n, py::ssize_t(3)}), lengths(n), exposed(n);
  for (py::ssize_t r = 0; r < n; ++r) {
    const steady::Rod& rod = plan.rods[r];
    beams.mutable_at(r) = rod.beam;
    a.mutable_at(r) = rod.a;
    b.mutable_at(r) = rod.b;
    for (int c = 0; c < 3; ++c) starts.mutable_at(r, c) = rod.start[c], ends.mutable_at(r, c) = rod.end[c];
    lengths.mutable_at(r) = rod.length;
    exposed.mutable_at(r) = rod.exposed;
  }
  py::dict d;
  d["beams"] = beams;
  d["a"] = a;
  d["b"] = b;
  d["starts"] = starts;
  d["ends"] = ends;
  d["lengths"] = lengths;
  d["exposed"] = exposed;
  return d;
}

py::list cut_list(const steady::ConnectorPlan& plan) {
  py::list out;
  for (std::size_t c = 0; c < plan.cut_list.size(); ++c) {
    const steady::RodLength& cut = plan.cut_list[c];
    py::dict d;
    d["name"] = steady::rod_part_name(c);
    d["length"] = cut.length;
    d["count"] = cut.rods.size();
    d["rods"] = py::array_t<std::int64_t>(static_cast<py::ssize_t>(cut.rods.size()), cut.rods.data());
    out.append(d);
  }
  return out;
}

constexpr const char* kParametersDoc =
    "rod_radius: the radius of every rod (model units, > 0); sleeve: the sleeves' outer radius in rod radii (> hole); "
    "reach: the radius of the ball bounding each connector, in rod radii (connector_reach_range() gives the range "
    "that fits); hole: the holes' radius in rod radii (>= 1, 1: the rod itself); core_bulge: the connector's core "
    "ball is this much wider than its arms (in [0.01, 0.5]: equal radii are tangent, which OpenCASCADE's Booleans "
    "do not survive); angle_tolerance: nodes whose beam directions agree to this (radians) up to a rotation share "
    "a family; length_tolerance: rods whose lengths agree to this share a cut-list entry (0: 1e-9 rod radii).";

}  // namespace

void bind_connectors(py::module_& m) {
  py::class_<ConnectorParts>(m, "Connectors",
                             "The connectors of a constant-radius lattice (Lattice.connectors()): one solid per family "
                             "of congruent connectors, placed at its members, and the rods.")
      .def_property_readonly(
          "families",
          [](const ConnectorParts& parts) {
            py::list out;
            for (std::size_t k = 0; k < parts.templates.size(); ++k) out.append(family_dict(parts, k));
            return out;
          },
          "Per family {name, count, balls (its members' ball indices), placements (count x 4 x 4: world = P @ "
          "template point; a rotation and a translation), directions (its beam directions in the template's frame), "
          "volume, faces, valid, build_seconds}.")
      .def(
          "brep",
          [](const ConnectorParts& parts, std::size_t family) {
            if (family >= parts.templates.size()) value_error("family", "no such family");
            return steady::brep_to_text(parts.templates[family]);
          },
          py::arg("family"), "BREP text of a family's template solid (its node at the origin).")
      .def_property_readonly(
          "family_of_ball",
          [](const ConnectorParts& parts) {
            return py::array_t<int>(static_cast<py::ssize_t>(parts.plan.family_of_ball.size()),
                                    parts.plan.family_of_ball.data());
          },
          "Per ball its family's index, -1 for a ball without beams (it gets no connector).")
      .def_property_readonly("rods", [](const ConnectorParts& parts) { return rods_dict(parts.plan); },
                             "One rod per beam, as arrays: {beams, a, b (the beam's balls), starts, ends (N x 3), "
                             "lengths (to cut), exposed (visible between the two connectors)}.")
      .def_property_readonly("cut_list", [](const ConnectorParts& parts) { return cut_list(parts.plan); },
                             "The rods grouped by length, shortest first: [{name, length, count, rods}].")
      .def_property_readonly("isolated_balls", [](const ConnectorParts& parts) { return parts.plan.isolated_balls; })
      .def_property_readonly(
          "reach_range", [](const ConnectorParts& parts) { return py::make_tuple(parts.plan.min_reach, parts.plan.max_reach); },
          "(min, max): the reaches (rod radii) that fit the lattice with these sleeve and hole.")
      .def(
          "write_step",
          [](const ConnectorParts& parts, const std::string& path, bool rods, const py::object& progress) {
            run_with_progress(progress, [&](steady::Progress& p) {
              steady::write_connectors_step(path, parts, rods, p);
              return 0;
            });
          },
          py::arg("path"), py::arg("rods") = true, py::arg("progress") = py::none(),
          "Writes one STEP assembly: a part per family (Connector_1, ...) placed at each member, and with rods a part "
          "per cut-list entry (Rod_1, ...) placed on each of its beams. progress: as for Lattice.brep().")
      .def(
          "write_family_step",
          [](const ConnectorParts& parts, std::size_t family, const std::string& path) {
            run_interruptible([&] {
              steady::write_connector_family_step(path, parts, family);
              return 0;
            });
          },
          py::arg("family"), py::arg("path"),
          "Writes one family's template alone (one solid, its node at the origin) as a STEP file, for making it.");

  auto lattice = py::reinterpret_borrow<py::class_<Lattice>>(m.attr("Lattice"));
  lattice.def(
      "connectors",
      [](const Lattice& lat, double rod_radius, double sleeve, double reach, double hole, double core_bulge,
         double angle_tolerance, double length_tolerance, const py::object& progress) {
        const steady::ConnectorParameters p =
            connector_parameters(rod_radius, sleeve, reach, hole, core_bulge, angle_tolerance, length_tolerance);
        return run_with_progress(progress, [&](steady::Progress& pr) {
          return steady::build_connectors(steady::flatten(lat), p, pr);
        });
      },
      py::arg("rod_radius"), py::arg("sleeve") = 1.6, py::arg("reach") = 2.5, py::arg("hole") = 1.0,
      py::arg("core_bulge") = 0.05, py::arg("angle_tolerance") = 1e-9, py::arg("length_tolerance") = 0.0,
      py::arg("progress") = py::none(),
      (std::string("The constant-radius version of the lattice (its radii are not used; every beam is a rod): the "
                   "connector of each node is Ball(node, reach) ∩ ExtendedHub(sleeve) − ExtendedHub(hole), and "
                   "connectors whose beam directions agree up to a rotation form one family, built once. ") +
       kParametersDoc +
       " progress: None or a callable progress(fraction) (False cancels: steadylattice.Cancelled). ValueError names "
       "the parameter; a reach outside the lattice's range names the node whose rods end too deep or the beam too "
       "short to separate its connectors, with the range that fits.")
          .c_str());
  lattice.def(
      "connector_reach_range",
      [](const Lattice& lat, double rod_radius, double sleeve, double hole, double core_bulge) {
        const steady::ConnectorParameters p = connector_parameters(rod_radius, sleeve, 0.0, hole, core_bulge, 0.0, 0.0);
        return run_interruptible([&] { return steady::connector_reach_range(steady::flatten(lat), p); });
      },
      py::arg("rod_radius"), py::arg("sleeve") = 1.6, py::arg("hole") = 1.0, py::arg("core_bulge") = 0.05,
      "(min, max): the reaches (in rod radii) for which connectors() accepts these parameters; min >= max when none "
      "does.");
}

}  // namespace steadypy
