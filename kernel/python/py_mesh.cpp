// Python bindings of the mesh side: the lattice as numpy arrays, and the printer formats (STL streamed from the
// lattice, OBJ, 3MF, 3MF beam lattice). Thin: conversions only; the GIL is released while the kernel works.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cstring>

#include "convert.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/bridges.hpp"
#include "steady/brep/trim.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/mesh/lattice_mesh.hpp"
#include "steady/mesh/mesh_files.hpp"
#include "steady/mesh/threemf_reader.hpp"
#include "steady/mesh/trimmed_mesh.hpp"

namespace steadypy {

using steady::Lattice;

namespace {

py::dict stats_dict(const steady::LatticeMeshStats& s) {
  py::dict d;
  d["hubs"] = s.hubs;
  d["crowded_hubs"] = s.crowded_hubs;
  d["beams"] = s.beams;
  d["distinct_hubs"] = s.distinct_hubs;
  d["templates"] = s.templates;
  d["vertices"] = s.vertices;
  d["triangles"] = s.triangles;
  d["foreign_groups"] = s.foreign_groups;
  d["foreign_hubs"] = s.foreign_hubs;
  d["short_beams"] = s.short_beams;
  d["template_seconds"] = s.template_seconds;
  d["group_seconds"] = s.group_seconds;
  d["placing_seconds"] = s.placing_seconds;
  return d;
}

py::tuple mesh_arrays(const steady::TriangleMesh& mesh) {
  py::array_t<double> vertices({static_cast<py::ssize_t>(mesh.vertices.size()), py::ssize_t(3)});
  py::array_t<std::uint32_t> triangles({static_cast<py::ssize_t>(mesh.triangles.size()), py::ssize_t(3)});
  if (!mesh.vertices.empty()) std::memcpy(vertices.mutable_data(), mesh.vertices.data(), mesh.vertices.size() * 3 * sizeof(double));
  if (!mesh.triangles.empty())
    std::memcpy(triangles.mutable_data(), mesh.triangles.data(), mesh.triangles.size() * 3 * sizeof(std::uint32_t));
  return py::make_tuple(vertices, triangles);
}

// (vertices N x 3, triangles M x 3) from Python into a kernel mesh; ValueError naming `name` otherwise.
steady::TriangleMesh to_triangle_mesh(const py::object& value, const std::string& name) {
  if (!py::isinstance<py::tuple>(value) && !py::isinstance<py::list>(value))
    value_error(name, "expected (vertices, triangles): an N x 3 array of points and an M x 3 array of indices");
  const py::sequence pair = value.cast<py::sequence>();
  if (pair.size() != 2) value_error(name, "expected (vertices, triangles)");
  bool single = false;
  const py::array_t<double> points = to_points(pair[0], name + " vertices", 3, &single);
  const auto indices = py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(pair[1]);
  if (!indices || indices.ndim() != 2 || indices.shape(1) != 3) value_error(name, "triangles must be an M x 3 array of indices");
  steady::TriangleMesh mesh;
  const auto p = points.unchecked<2>();
  for (py::ssize_t i = 0; i < p.shape(0); ++i) mesh.vertices.emplace_back(p(i, 0), p(i, 1), p(i, 2));
  const auto t = indices.unchecked<2>();
  for (py::ssize_t i = 0; i < t.shape(0); ++i) {
    steady::Triangle tri;
    for (int k = 0; k < 3; ++k) {
      if (t(i, k) < 0 || t(i, k) >= p.shape(0)) value_error(name, "triangle " + std::to_string(i) + " has an index out of range");
      tri[k] = static_cast<std::uint32_t>(t(i, k));
    }
    mesh.triangles.push_back(tri);
  }
  return mesh;
}

// The lattice's mesh, trimmed into `body` (and with a skin down to `inner`) when given; its stats into `stats`.
// How a trimmed mesh treats the hubs at the wall: policy 'clip', or 'bridge' with the body's B-rep (its nearest
// points place the bridges) and the skin's thickness (its inner wall is the one bridged to).
struct MeshPolicy {
  std::string policy = "clip";
  py::object brep = py::none();
  double skin = 0.0;
};

// The lattice the mesh is made of: the lattice itself (clip), or its bridged lattice (plan_bridges), which the
// body's mesh then clips like any lattice: the wall cuts only bridges. Bridge counts go into `stats`.
steady::FlatLattice mesh_lattice(const Lattice& lat, const MeshPolicy& m, const py::object& body,
                                 const py::object& inner, py::dict& stats) {
  const steady::TrimPolicy policy = steady::trim_policy_from_string(m.policy);
  if (policy == steady::TrimPolicy::Clip) {
    if (!m.brep.is_none()) value_error("brep", "only policy 'bridge' uses the body's B-rep");
    return steady::flatten(lat);
  }
  if (policy == steady::TrimPolicy::Whole)
    value_error("policy", "a trimmed mesh clips ('clip') or bridges ('bridge'); 'whole' is the B-rep's only");
  if (body.is_none()) value_error("policy", "'bridge' needs a body to trim into (body=, its mesh)");
  if (m.brep.is_none() || !py::isinstance<py::str>(m.brep))
    value_error("brep", "policy 'bridge' needs the body's BREP text (Part.Shape.exportBrepToString()): the bridges "
                        "run to its nearest points");
  if ((m.skin > 0.0) != !inner.is_none())
    value_error("skin", "must be the thickness of the skin whose inner surface `inner` is (> 0 with inner, 0 without)");
  const std::string text = m.brep.cast<std::string>();
  const steady::BridgePlan plan = run_interruptible(
      [&] { return steady::plan_bridges(steady::flatten(lat), steady::read_body_brep(text, "brep"), m.skin); });
  stats["kept_hubs"] = static_cast<std::int64_t>(plan.kept.size());
  stats["lost_neighbour_hubs"] = plan.lost_neighbour_hubs;
  stats["bridges"] = static_cast<std::int64_t>(plan.bridges.size());
  stats["rerouted_bridges"] = static_cast<std::int64_t>(
      std::count_if(plan.bridges.begin(), plan.bridges.end(), [](const steady::Bridge& b) { return b.rerouted; }));
  stats["blocked_bridges"] = static_cast<std::int64_t>(plan.blocked.size());
  return plan.lattice;
}

steady::TriangleMesh lattice_mesh_of(const Lattice& lat, double tolerance, const py::object& body,
                                     const py::object& inner, const py::object& progress, py::dict& stats,
                                     const MeshPolicy& policy = {}) {
  py::dict bridges;
  const steady::FlatLattice flat = mesh_lattice(lat, policy, body, inner, bridges);
  if (body.is_none()) {
    if (!inner.is_none()) value_error("inner", "a skin's inner surface needs the body too");
    steady::LatticeMeshStats s;
    steady::TriangleMesh mesh = run_with_progress(progress, [&](steady::Progress& p) {
      return steady::lattice_mesh(flat, {tolerance}, &s, p);
    });
    stats = stats_dict(s);
    return mesh;
  }
  const steady::TriangleMesh body_mesh = to_triangle_mesh(body, "body");
  steady::TriangleMesh inner_mesh;
  steady::TrimmedMeshRequest request;
  request.body = &body_mesh;
  if (!inner.is_none()) {
    inner_mesh = to_triangle_mesh(inner, "inner");
    request.inner = &inner_mesh;
  }
  steady::TrimmedMeshStats s;
  steady::TriangleMesh mesh = run_with_progress(progress, [&](steady::Progress& p) {
    return steady::trimmed_lattice_mesh(flat, {tolerance}, request, &s, p);
  });
  stats = stats_dict(s.mesh);
  stats["inside_hubs"] = s.inside_hubs;
  stats["crossing_hubs"] = s.crossing_hubs;
  stats["outside_hubs"] = s.outside_hubs;
  stats["band_triangles"] = s.band_triangles;
  stats["boolean_seconds"] = s.boolean_seconds;
  stats["moved_clear"] = s.moved_clear;
  stats["float_removed_triangles"] = s.float_removed_triangles;
  stats["float_seconds"] = s.float_seconds;
  stats["check_seconds"] = s.check_seconds;
  stats["plan_seconds"] = s.plan_seconds;
  stats["classify_seconds"] = s.classify_seconds;
  stats["pieces_seconds"] = s.pieces_seconds;
  stats["join_seconds"] = s.join_seconds;
  for (const auto& item : bridges) stats[item.first] = item.second;
  return mesh;
}

// The body and inner arguments, for the docstrings (a literal, so that it joins theirs).
#define STEADY_BODY_DOC \
    " body: None, or (vertices, triangles) of a closed, outward mesh of the body the lattice is trimmed into: " \
    "hubs inside it are placed whole, outside ones dropped, and only the band of crossing hubs goes through a " \
    "Boolean (CGAL's corefinement). inner: with a body, None or the mesh of the body's inner offset: the skin " \
    "between the two is united with the lattice, which is trimmed to the inner surface. policy: 'clip', or " \
    "'bridge' (as for brep(): hubs whole inside kept, each that lost a neighbour bridged to the nearest wall " \
    "point (or by another route when that one is blocked), the body's mesh cutting only bridges; needs brep=, the " \
    "body's BREP text, and skin=, the thickness whose inner surface `inner` is; stats get kept_hubs, " \
    "lost_neighbour_hubs, bridges, rerouted_bridges, blocked_bridges)."

}  // namespace

// to_mesh's docstring, with the body arguments'.
const char* const kToMeshDoc =
  "The lattice as one closed, outward-oriented triangle mesh with no self-intersection, straight from its "
  "definition (no B-rep; a Boolean only where hubs must be united): (vertices float64 N x 3, triangles uint32 "
  "M x 3). tolerance: the largest distance, in model units, from a triangle to the exact ball or cone it "
  "approximates (every vertex of a placed hub or strip lies on the exact surface); it must be > 0 and below a "
  "quarter of the smallest ball radius. Each distinct hub shape is tessellated once per scale level and placed "
  "as similar copies. Without a body, the hubs of elements "
  "meeting foreign ones, and of beams too short for their collars, are united in groups (exact Booleans); "
  "with a body, such lattices are refused. progress: as for brep(). stats: None or a dict, filled with hubs, "
  "crowded_hubs, beams, distinct_hubs, templates, vertices, triangles, foreign_groups, foreign_hubs, "
  "short_beams, template_seconds, group_seconds, placing_seconds (and with a body inside_hubs, crossing_hubs, "
  "outside_hubs, band_triangles, moved_clear (band vertices within a float's resolution of the wall, moved off "
  "it), "
  "float_removed_triangles (made flat by rounding to the floats of STL and 3MF, removed), "
  "boolean_seconds, and the other phases: check_seconds, plan_seconds, classify_seconds, pieces_seconds, "
  "float_seconds, join_seconds)." STEADY_BODY_DOC;

void bind_mesh(py::module_& m) {
  auto lattice = py::reinterpret_borrow<py::class_<Lattice>>(m.attr("Lattice"));
  lattice.def(
      "to_mesh",
      [](const Lattice& lat, double tolerance, const py::object& body, const py::object& inner,
         const py::object& progress, const py::object& stats, const std::string& policy, const py::object& brep,
         double skin) {
        require_stats_target(stats);
        py::dict s;
        const steady::TriangleMesh mesh =
            lattice_mesh_of(lat, tolerance, body, inner, progress, s, {policy, brep, skin});
        fill_stats(stats, s);
        return mesh_arrays(mesh);
      },
      py::arg("tolerance"), py::arg("body") = py::none(), py::arg("inner") = py::none(),
      py::arg("progress") = py::none(), py::arg("stats") = py::none(), py::arg("policy") = "clip",
      py::arg("brep") = py::none(), py::arg("skin") = 0.0,
      kToMeshDoc);
  lattice.def(
      "write_stl",
      [](const Lattice& lat, const std::string& path, double tolerance, const std::string& name,
         const py::object& body, const py::object& inner, const py::object& progress, const py::object& stats,
         const std::string& policy, const py::object& brep, double skin) {
        require_stats_target(stats);
        if (!body.is_none() || policy != "clip") {
          py::dict s;
          const steady::TriangleMesh mesh =
              lattice_mesh_of(lat, tolerance, body, inner, progress, s, {policy, brep, skin});
          {
            py::gil_scoped_release release;
            steady::write_stl(mesh, path, name);
          }
          fill_stats(stats, s);
          return;
        }
        const steady::LatticeMeshStats s = run_with_progress(progress, [&](steady::Progress& p) {
          return steady::write_lattice_stl(steady::flatten(lat), {tolerance}, path, name, p);
        });
        fill_stats(stats, stats_dict(s));
      },
      py::arg("path"), py::arg("tolerance"), py::arg("name") = "lattice", py::arg("body") = py::none(),
      py::arg("inner") = py::none(), py::arg("progress") = py::none(), py::arg("stats") = py::none(),
      py::arg("policy") = "clip", py::arg("brep") = py::none(), py::arg("skin") = 0.0,
      "Writes the lattice's mesh (see to_mesh) as binary STL, streamed chunk by chunk: the whole mesh is never "
      "held, so lattices too large for an indexed mesh still reach the printer. Written beside the path and renamed "
      "when complete: a failure or a cancel leaves no partial file. With a body (see to_mesh: body, inner, policy, "
      "brep, skin) the trimmed mesh is made whole first.");
  lattice.def(
      "write_obj",
      [](const Lattice& lat, const std::string& path, double tolerance, const std::string& name,
         const py::object& body, const py::object& inner, const py::object& progress, const std::string& policy,
         const py::object& brep, double skin) {
        py::dict s;
        const steady::TriangleMesh mesh =
            lattice_mesh_of(lat, tolerance, body, inner, progress, s, {policy, brep, skin});
        py::gil_scoped_release release;
        steady::write_obj(mesh, path, name);
      },
      py::arg("path"), py::arg("tolerance"), py::arg("name") = "lattice", py::arg("body") = py::none(),
      py::arg("inner") = py::none(), py::arg("progress") = py::none(), py::arg("policy") = "clip",
      py::arg("brep") = py::none(), py::arg("skin") = 0.0,
      "Writes the lattice's mesh (see to_mesh: body, inner, policy, brep, skin too) as Wavefront OBJ.");
  lattice.def(
      "write_3mf",
      [](const Lattice& lat, const std::string& path, const py::object& tolerance, bool beam_lattice,
         const std::string& name, const std::string& unit, const py::object& clipping, const py::object& body,
         const py::object& inner, const py::object& progress, const py::object& stats) {
        require_stats_target(stats);
        if (beam_lattice && !body.is_none())
          value_error("body", "a beam lattice is not trimmed: give the body's mesh as clipping=");
        steady::BeamLatticeOptions options;
        steady::TriangleMesh clipping_mesh;
        if (!clipping.is_none()) {
          if (!beam_lattice) value_error("clipping", "only a beam lattice is clipped by a mesh");
          clipping_mesh = to_triangle_mesh(clipping, "clipping");
          options.clipping = &clipping_mesh;
        }
        options.name = name;
        options.unit = unit;
        py::dict d;
        steady::TriangleMesh mesh;
        if (!tolerance.is_none()) mesh = lattice_mesh_of(lat, to_double(tolerance, "tolerance"), body, inner, progress, d);
        else if (!beam_lattice) value_error("tolerance", "a mesh 3MF needs a tolerance (a beam lattice does not)");
        if (beam_lattice) {
          if (!tolerance.is_none()) options.representation = &mesh;
          const steady::BeamLatticeStats b = run_with_progress(progress, [&](steady::Progress& p) {
            return steady::write_3mf_beam_lattice(steady::flatten(lat), path, options, p);
          });
          d["beams_written"] = b.beams;
          d["balls_written"] = b.balls;
          d["lone_balls"] = b.lone_balls;
          d["bytes"] = b.bytes;
        } else {
          py::gil_scoped_release release;
          steady::write_3mf(mesh, path, options);
        }
        fill_stats(stats, d);
      },
      py::arg("path"), py::arg("tolerance") = py::none(), py::arg("beam_lattice") = false,
      py::arg("name") = "lattice", py::arg("unit") = "millimeter", py::arg("clipping") = py::none(),
      py::arg("body") = py::none(), py::arg("inner") = py::none(), py::arg("progress") = py::none(),
      py::arg("stats") = py::none(),
      "Writes a 3MF. beam_lattice=False: the lattice's mesh (see to_mesh; tolerance required) as a core 3MF mesh "
      "object through lib3mf. beam_lattice=True: the 3MF Beam Lattice extension v1.2, a beam per beam with its two "
      "radii and a ball per ball (megabytes for a million beams); with a tolerance, the mesh rides along as the "
      "representation mesh that viewers without beam-lattice support show; clipping: None or (vertices, triangles) of "
      "a closed mesh of the body, written as the lattice's clipping mesh (clippingmode inside: the printer keeps "
      "what lies inside it). body, inner: for a mesh 3MF, the lattice trimmed (and skinned), see to_mesh. unit: "
      "micron, millimeter, centimeter, inch, foot or meter.");
  m.def(
      "read_3mf",
      [](const std::string& path) {
        steady::ThreeMfContents c;
        {
          py::gil_scoped_release release;
          c = steady::read_3mf(path);
        }
        py::list objects;
        for (const steady::ThreeMfObject& o : c.objects) {
          py::dict d;
          d["id"] = o.id;
          d["name"] = o.name;
          const py::tuple arrays = mesh_arrays(o.mesh);
          d["vertices"] = arrays[0];
          d["triangles"] = arrays[1];
          py::list beams;
          for (const steady::ThreeMfBeam& b : o.beams) beams.append(py::make_tuple(b.v1, b.v2, b.r1, b.r2));
          d["beams"] = beams;
          objects.append(d);
        }
        py::dict out;
        out["unit"] = c.unit;
        out["objects"] = objects;
        out["warnings"] = c.warnings;
        return out;
      },
      py::arg("path"),
      "A 3MF file as lib3mf (an independent reader) reads it: {unit, warnings, objects: [{id, name, vertices, "
      "triangles, beams: [(v1, v2, r1, r2)]}]}.");
}

}  // namespace steadypy
