// Python bindings of the B-rep side: the clean check, the part as BREP text, STEP assemblies, and the B-rep
// properties tests and scripts need (validity, volume, counts). Thin: conversions only; the GIL is released
// while the kernel works.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "convert.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/brep/bridges.hpp"
#include "steady/query/clean_check.hpp"
#include "steady/lattice/flat_lattice.hpp"
#include "steady/lattice/lattice.hpp"
#include "steady/brep/lattice_part.hpp"
#include "steady/brep/step_assembly.hpp"
#include "steady/brep/trim.hpp"

namespace steadypy {

using steady::Lattice;

namespace {

steady::LatticePartRequest part_request(const py::object& body, const std::string& policy, double skin,
                                        const std::string& dangling) {
  steady::LatticePartRequest r;
  if (!body.is_none()) {
    if (!py::isinstance<py::str>(body)) value_error("body", "expected BREP text (str), as Part.Shape.exportBrepToString() gives");
    r.body_brep = body.cast<std::string>();
  }
  r.trim.policy = steady::trim_policy_from_string(policy);
  r.trim.dangling = steady::dangling_from_string(dangling);
  r.trim.skin = skin;
  return r;
}

// Developers' diagnostics of a trim (TrimOptions::report) to a Python callable log(message); a diagnostic that
// raises is reported as unraisable, never stops the trim.
void set_log(steady::TrimOptions& options, const py::object& log) {
  if (log.is_none()) return;
  if (!PyCallable_Check(log.ptr())) value_error("log", "expected a callable log(message), or None");
  options.report = [log](const std::string& message) {
    py::gil_scoped_acquire gil;
    try {
      log(message);
    } catch (py::error_already_set& e) {
      e.discard_as_unraisable("steadylattice log");
    }
  };
}

std::array<double, 3> to_color(py::handle value, const std::string& name) {
  const steady::Vec3 c = to_vec3(value, name);
  for (int k = 0; k < 3; ++k)
    if (c[k] < 0.0 || c[k] > 1.0) value_error(name, "colour components must lie in [0, 1]");
  return {c.x, c.y, c.z};
}

struct Properties {
  bool valid = false;
  double volume = 0.0;
  std::int64_t faces = 0, solids = 0;
  std::string report;
  double max_edge_tolerance = 0.0;
};

Properties properties(const TopoDS_Shape& shape) {
  return {steady::is_valid(shape), steady::shape_volume(shape), steady::face_count(shape), steady::solid_count(shape),
          steady::validity_report(shape), steady::max_edge_tolerance(shape)};
}

py::dict to_dict(const Properties& p) {
  py::dict d;
  d["valid"] = p.valid;
  d["volume"] = p.volume;
  d["faces"] = p.faces;
  d["solids"] = p.solids;
  d["max_edge_tolerance"] = p.max_edge_tolerance;
  d["report"] = p.report;
  return d;
}

// How a trim went, into the caller's dict: what the report view shows (retries, fuzzy Booleans, fallbacks).
void fill_stats(const steady::TrimStats& s, py::dict& d) {
  d["inside_hubs"] = s.inside_hubs;
  d["outside_hubs"] = s.outside_hubs;
  d["crossing_hubs"] = s.crossing_hubs;
  d["removed_beams"] = s.removed_beams;
  d["band_clusters"] = s.band_clusters;
  d["moved_cuts"] = s.moved_cuts;
  d["joined_band_hubs"] = s.joined_band_hubs;
  d["retried_clusters"] = s.retried_clusters;
  d["relaid_clusters"] = s.relaid_clusters;
  d["turned_clusters"] = s.turned_clusters;
  d["fuzzy_clusters"] = s.fuzzy_clusters;
  d["merged_clusters"] = s.merged_clusters;
  d["holed_clusters"] = s.holed_clusters;
  d["rim_clusters"] = s.rim_clusters;
  d["rim_clusters_unclipped"] = s.rim_clusters_unclipped;
  d["rim_cut_reason"] = s.rim_cut_reason;
  d["core_hubs"] = s.core_hubs;
  d["distinct_cores"] = s.distinct_cores;
  d["fused_cores"] = s.fused_cores;
  d["tight_cores"] = s.tight_cores;
  d["hub_groups"] = s.hub_groups;
  d["grouped_hubs"] = s.grouped_hubs;
  d["foreign_groups"] = s.foreign_groups;
  d["foreign_hubs"] = s.foreign_hubs;
  d["relaid_out"] = s.relaid_out;
  d["relaid_reason"] = s.relaid_reason;
  d["union_through_pores"] = s.union_through_pores;
  d["pores_reason"] = s.pores_reason;
  d["skin_pieces"] = s.skin_pieces;
  d["skin_pieces_volume"] = s.skin_pieces_volume;
  d["grazing_pieces"] = s.grazing_pieces;
  d["grazing_kept_reason"] = s.grazing_kept_reason;
  d["grazing_seconds"] = s.grazing_seconds;
  d["reseated_sphere_faces"] = s.reseated_sphere_faces;
  d["kept_straddling_faces"] = s.kept_straddling_faces;
  d["kept_straddling_reason"] = s.kept_straddling_reason;
  d["reseat_seconds"] = s.reseat_seconds;
  d["loose_edges"] = s.loose_edges;
  d["retraced_edges"] = s.retraced_edges;
  d["refitted_edges"] = s.refitted_edges;
  d["loosest_edge_before"] = s.loosest_edge_before;
  d["loosest_edge_after"] = s.loosest_edge_after;
  d["retrace_seconds"] = s.retrace_seconds;
  d["kept_hubs"] = s.kept_hubs;
  d["lost_neighbour_hubs"] = s.lost_neighbour_hubs;
  d["bridges"] = s.bridges;
  d["rerouted_bridges"] = s.rerouted_bridges;
  d["blocked_bridges"] = s.blocked_bridges;
  d["ambiguous_bridges"] = s.ambiguous_bridges;
  d["faces"] = s.faces;
  d["volume"] = s.volume;
  d["boolean_seconds"] = s.boolean_seconds;
  d["union_seconds"] = s.union_seconds;
}

// Lattice.bridge_plan: the bridged lattice the 'bridge' policy trims, as arrays, with its bridges.
py::dict bridge_plan_dict(const Lattice& lat, const std::string& body, double skin) {
  const steady::BridgePlan plan = run_interruptible(
      [&] { return steady::plan_bridges(steady::flatten(lat), steady::read_body_brep(body, "body"), skin); });
  const steady::FlatLattice& f = plan.lattice;
  py::array_t<double> centers({f.ball_count(), std::int64_t(3)}), radii(f.ball_count()), ra(f.beam_count()),
      rb(f.beam_count());
  py::array_t<std::int64_t> a(f.beam_count()), b(f.beam_count());
  for (std::int64_t i = 0; i < f.ball_count(); ++i) {
    for (int k = 0; k < 3; ++k) centers.mutable_at(i, k) = f.balls[i].center[k];
    radii.mutable_at(i) = f.balls[i].radius;
  }
  for (std::int64_t e = 0; e < f.beam_count(); ++e) {
    a.mutable_at(e) = f.beams[e].a;
    b.mutable_at(e) = f.beams[e].b;
    ra.mutable_at(e) = f.beams[e].ra;
    rb.mutable_at(e) = f.beams[e].rb;
  }
  py::list bridges;
  for (const steady::Bridge& br : plan.bridges)
    bridges.append(py::dict(py::arg("hub") = br.hub, py::arg("wall") = vec3_array(br.wall),
                            py::arg("end") = vec3_array(br.end), py::arg("radius") = br.radius,
                            py::arg("ambiguous") = br.ambiguous,
                            py::arg("route") = br.rerouted ? "rerouted" : "nearest"));
  py::dict d;
  d["balls"] = py::make_tuple(centers, radii);
  d["beams"] = py::make_tuple(a, b, ra, rb);
  d["kept"] = py::array_t<std::int64_t>(plan.kept.size(), plan.kept.data());
  d["bridges"] = bridges;
  d["blocked"] = plan.blocked;
  d["lost_neighbour_hubs"] = plan.lost_neighbour_hubs;
  return d;
}

}  // namespace

void bind_brep(py::module_& m) {
  auto lattice = py::reinterpret_borrow<py::class_<Lattice>>(m.attr("Lattice"));
  lattice.def(
      "clean_check",
      [](const Lattice& lat, std::int64_t max_reported) {
        // minutes on 10^7 elements: the check polls, so Ctrl-C stops it
        const steady::CleanReport r = run_interruptible([&] { return steady::check_clean(lat, {max_reported}); });
        py::list issues;
        for (const steady::CleanIssue& i : r.issues)
          issues.append(py::dict(py::arg("kind") = steady::to_string(i.kind), py::arg("ball") = i.ball,
                                 py::arg("other_ball") = i.other_ball, py::arg("beam") = i.beam,
                                 py::arg("other_beam") = i.other_beam, py::arg("message") = i.describe()));
        py::dict d;
        d["clean"] = r.clean();
        d["issue_count"] = r.issue_count;
        d["issues"] = issues;
        d["absorbed_balls"] = r.absorbed_balls;
        d["degenerate_beams"] = r.degenerate_beams;
        return d;
      },
      py::arg("max_reported") = 10000,
      "Whether the lattice can become a B-rep with no Boolean: exit circles disjoint on every ball, no element "
      "meeting a foreign one. Returns {clean, issue_count, issues: [{kind, ball, other_ball, beam, other_beam, "
      "message}], absorbed_balls, degenerate_beams}; indices refer to balls() and beams().");
  lattice.def(
      "brep",
      [](const Lattice& lat, const py::object& body, const std::string& policy, double skin,
         const std::string& dangling, const py::object& progress, const py::object& stats, const py::object& log,
         const std::string& dump_dir) {
        steady::LatticePartRequest request = part_request(body, policy, skin, dangling);
        set_log(request.trim, log);
        request.trim.dump_directory = dump_dir;
        require_stats_target(stats);
        steady::TrimStats trim;
        std::string text = run_with_progress(progress, [&](steady::Progress& p) {
          // The part's volume in the stats takes as long as the build of a crowded lattice: only when asked.
          return steady::lattice_part_brep(steady::flatten(lat), request, p, stats.is_none() ? nullptr : &trim);
        });
        if (!stats.is_none()) {
          py::dict d = stats.cast<py::dict>();
          fill_stats(trim, d);
        }
        return text;
      },
      py::arg("body") = py::none(), py::arg("policy") = "clip", py::arg("skin") = 0.0, py::arg("dangling") = "keep",
      py::arg("progress") = py::none(), py::arg("stats") = py::none(), py::arg("log") = py::none(),
      py::arg("dump_dir") = "",
      "BREP text of the lattice as one solid (a compound of solids when it has several components). body: BREP "
      "text of a solid (Part.Shape.exportBrepToString()) to trim into; policy: 'clip' (cut at the boundary) or "
      "'whole' (keep only hubs entirely inside, never cut) or 'bridge' (the hubs 'whole' keeps, and from each that "
      "lost a neighbour a bridge beam to the nearest point of the wall, or by another route when that one is "
      "blocked, cut there; dangling does not apply); skin: wall thickness of a skin united with the "
      "lattice; dangling: 'keep' or 'remove' beams joining a kept hub to a dropped one. progress: None or a "
      "callable progress(fraction) called on this thread about every 0.1 s with a growing fraction in [0, 1] "
      "(1 at the end); returning False cancels: steadylattice.Cancelled is raised soon after (an exception the "
      "callable raises is raised instead), and nothing has changed. stats: None or a dict, filled with how the trim "
      "went: hubs inside/outside/crossing, band_clusters (local Booleans), moved_cuts (beams cut off their middle "
      "to keep clusters apart), retried_clusters and of those "
      "relaid_/turned_/fuzzy_clusters (fuzzy: clipped with a tolerance of 1e-4 to 1e-3 of the cluster's size, "
      "exact only to that; merged: with the thin bands of cone between crowded hubs' collars merged into their "
      "stumps first), holed_clusters (glued to the skin with no Boolean), rim_clusters (on the inner boundary's edges and seams: united with the skin by one Cut) and of those rim_clusters_unclipped (found before their Common), relaid_out and union_through_pores "
      "with their reasons, with 'bridge' kept_hubs, lost_neighbour_hubs, bridges, rerouted_bridges (of bridges, those "
      "whose route to the nearest wall point was blocked and took another), blocked_bridges (refused: on every route "
      "tried they would meet another kept element) and ambiguous_bridges (several nearest points), reseated_sphere_faces (sphere faces a Boolean left with a loop across the seam, which STEP readers find invalid, rebuilt on a frame whose seam clears their loops; kept_straddling_faces and kept_straddling_reason: those left as they were, and why; reseat_seconds), loose_edges (edges a Boolean left with a tolerance above 2e-7, approximations of where two quadrics meet) and retraced_edges (of those, given curves on the exact intersection), refitted_edges (intersection edges, loose or not, given curves with the angle around a beam or ball as parameter: exact to 1e-8 with far fewer poles), loosest_edge_before and loosest_edge_after (their largest tolerance), retrace_seconds, faces, volume (by Green's theorem on each face, to about 1e-12: FreeCAD's Shape.Volume can be 1e-3 off on crowded spheres), boolean_seconds, union_seconds. log: None or a callable log(message) receiving "
      "the trim's diagnostics as they happen (build times, failed attempts, a union through the pores). dump_dir: "
      "a folder where a boundary cluster that fails every attempt is written as BREP, for study.");
  lattice.def(
      "bridge_plan",
      &bridge_plan_dict,
      py::arg("body"), py::arg("skin") = 0.0,
      "What brep(body, 'bridge', skin) trims with policy 'clip': {balls: (centers, radii), beams: (a, b, ra, rb)} of "
      "the bridged lattice (the kept hubs first, then one far node per bridge; the beams between kept hubs, then the "
      "bridges), kept (the source ball of each kept hub), bridges [{hub, wall, end, radius, ambiguous, route}] "
      "(route: 'nearest', or 'rerouted' when the nearest point's route was blocked and `wall` is where another route "
      "meets the wall; the nearest ones first), blocked (hubs with no clear route to the wall), lost_neighbour_hubs. "
      "For checks and pictures (docs/cots.md).");
  lattice.def(
      "write_step",
      [](const Lattice& lat, const std::string& path, const py::object& body, const std::string& policy, double skin,
         const std::string& dangling, const std::string& lattice_name, const std::string& skin_name,
         const py::object& lattice_color, const py::object& skin_color, const py::object& progress,
         const py::object& stats, bool united) {
        const steady::LatticePartRequest request = part_request(body, policy, skin, dangling);
        require_stats_target(stats);
        steady::StepNames names;
        names.layout = united ? steady::StepLayout::OneSolid : steady::StepLayout::Assembly;
        names.lattice = lattice_name;
        names.skin = skin_name;
        names.lattice_color = to_color(lattice_color, "lattice_color");
        names.skin_color = to_color(skin_color, "skin_color");
        steady::TrimStats trim;
        run_with_progress(progress, [&](steady::Progress& p) {
          steady::write_lattice_step(path, steady::flatten(lat), request, names, p, &trim);
          return 0;
        });
        if (!stats.is_none()) {
          py::dict d = stats.cast<py::dict>();
          fill_stats(trim, d);
        }
      },
      py::arg("path"), py::arg("body") = py::none(), py::arg("policy") = "clip", py::arg("skin") = 0.0,
      py::arg("dangling") = "keep", py::arg("lattice_name") = "Lattice", py::arg("skin_name") = "Skin",
      py::arg("lattice_color") = py::make_tuple(0.85, 0.55, 0.20), py::arg("skin_color") = py::make_tuple(0.55, 0.65, 0.80),
      py::arg("progress") = py::none(), py::arg("stats") = py::none(), py::arg("united") = false,
      "Writes a STEP assembly: the lattice (trimmed to the inner offset when there is a skin) and the skin as two "
      "named, coloured parts. Pieces of the trimmed lattice that hold no hub built whole (ends of beams and hubs cut "
      "at the skin's inner wall, touching only the skin) are part of the skin, so the lattice part is one solid. "
      "united=True: one part instead, named lattice_name, the lattice united with its skin (the solid brep() "
      "gives): the part as printed, and what a mesher for analysis takes (docs/fea.md). "
      "progress: as for brep(); a cancelled call raises steadylattice.Cancelled and leaves "
      "the file untouched (it is written only at the end). stats: None or a dict, filled as by brep() (without "
      "volume), with skin_pieces and skin_pieces_volume: the pieces given to the skin; of those, grazing_pieces: "
      "the lenses of beams whose axis runs outside the inner wall while their cone dips through it, split off "
      "the lattice in grazing_seconds (grazing_kept_reason: why not, when that split failed its checks).");
  m.def(
      "brep_properties",
      [](const std::string& text) {
        // Read in a reader process (the text may come from anywhere), interruptible by Ctrl-C.
        return to_dict(run_interruptible([&] { return properties(steady::read_body_brep(text, "text")); }));
      },
      py::arg("text"), "{valid, volume, faces, solids, report, max_edge_tolerance} of a shape given as BREP text "
      "(OpenCASCADE's checks; max_edge_tolerance: how far apart the curves of its loosest edge may be).");
  m.def(
      "read_step",
      [](const std::string& path) {
        std::vector<steady::StepPart> parts;
        std::vector<Properties> props;
        std::vector<std::string> texts;
        run_interruptible([&] {
          parts = steady::read_step_parts(path);
          for (const steady::StepPart& p : parts) {
            props.push_back(properties(p.shape));
            texts.push_back(steady::brep_to_text(p.shape));
          }
        });
        py::list out;
        for (std::size_t i = 0; i < parts.size(); ++i) {
          py::dict d = to_dict(props[i]);
          d["name"] = parts[i].name;
          d["color"] = parts[i].has_color
                           ? py::object(py::make_tuple(parts[i].color[0], parts[i].color[1], parts[i].color[2]))
                           : py::none();
          d["brep"] = texts[i];
          out.append(d);
        }
        return out;
      },
      py::arg("path"), "The parts of a STEP file as read by OpenCASCADE: [{name, color, brep, valid, volume, faces, "
      "solids, report, max_edge_tolerance}].");
}

}  // namespace steadypy
