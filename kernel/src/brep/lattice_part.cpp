#include "steady/brep/lattice_part.hpp"

#include <BRepTools_ReShape.hxx>

#include <chrono>

#include "brep/portable_sphere_faces.hpp"
#include "brep/retraced_edges.hpp"
#include "steady/brep/brep_builder.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"
#include "steady/brep/step_assembly.hpp"

namespace steady {

namespace {

// Sphere faces whose loops cross the seam (left so by a Boolean) rebuilt on portable frames, in every shape of
// the result: STEP readers would find them invalid (portable_sphere_faces.hpp).
void make_sphere_faces_portable(TrimResult& r) {
  const auto clock = std::chrono::steady_clock::now();
  Handle(BRepTools_ReShape) reshape = new BRepTools_ReShape;
  reshape->ModeConsiderLocation() = Standard_True;
  const PortableSphereFaces p = reseat_sphere_faces(r.part, *reshape);
  r.stats.reseated_sphere_faces = p.reseated;
  r.stats.kept_straddling_faces = p.kept;
  r.stats.kept_straddling_reason = p.kept_reason;
  if (p.reseated > 0) {
    const bool part_is_lattice = r.part.IsSame(r.lattice);
    r.lattice = reshape->Apply(r.lattice);
    if (!r.skin.IsNull()) r.skin = reshape->Apply(r.skin);
    r.part = part_is_lattice ? r.lattice : reshape->Apply(r.part);
  }
  r.stats.reseat_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
}

// Edges the Booleans left loose, retraced onto the exact curves their faces meet in, in every shape of the result
// at once (the parts share faces): a part holding one is defined only to its tolerance (retraced_edges.hpp).
void retrace_intersection_edges_of(TrimResult& r) {
  const auto clock = std::chrono::steady_clock::now();
  const RetracedEdges e = retrace_intersection_edges({r.part, r.lattice, r.skin});
  r.stats.loose_edges = e.loose;
  r.stats.retraced_edges = e.retraced;
  r.stats.refitted_edges = e.refitted;
  r.stats.loosest_edge_before = e.loosest_before;
  r.stats.loosest_edge_after = e.loosest_after;
  r.stats.retrace_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - clock).count();
}

TrimResult make_trimmed_or_whole_part(const FlatLattice& lattice, const LatticePartRequest& request,
                                      Progress& progress) {
  TrimResult out;
  if (!request.body_brep) {
    if (request.trim.skin != 0.0) fail_input("skin", "needs a body to wrap");
    const LatticeBrep built = build_lattice_brep(lattice, SeamPreference::FewestCrossings, progress);
    out.part = out.lattice = built.shape;
    out.stats.core_hubs = built.stats.core_hubs;
    out.stats.distinct_cores = built.stats.distinct_cores;
    out.stats.fused_cores = built.stats.fused_cores;
    out.stats.tight_cores = built.stats.tight_cores;
    out.stats.hub_groups = built.stats.hub_groups;
    out.stats.grouped_hubs = built.stats.grouped_hubs;
    out.stats.foreign_groups = built.stats.foreign_groups;
    out.stats.foreign_hubs = built.stats.foreign_hubs;
    return out;
  }
  TopoDS_Shape body;
  {
    const ProgressScope scope(&progress);  // the reader process is killed when the part is cancelled
    body = read_body_brep(*request.body_brep, "body");
  }
  return trim_lattice(lattice, body, request.trim, progress);
}

TrimResult make_part(const FlatLattice& lattice, const LatticePartRequest& request, Progress& progress) {
  TrimResult out = make_trimmed_or_whole_part(lattice, request, progress);
  retrace_intersection_edges_of(out);
  make_sphere_faces_portable(out);
  return out;
}

// Shares of the output's progress: the part, then its BREP text (quick) or its STEP file (translating and writing
// a STEP file takes longer than building a part trimmed into a box; a curved body's Booleans take longer still).
constexpr std::int64_t kPartUnits = 95, kTextUnits = 5;
constexpr std::int64_t kStepPartUnits = 60, kStepFileUnits = 40;

}  // namespace

std::string lattice_part_brep(const FlatLattice& lattice, const LatticePartRequest& request, Progress& progress,
                              TrimStats* stats) {
  progress.set_total(kPartUnits + kTextUnits);
  TrimResult r;
  {
    Progress part(progress, kPartUnits);
    r = make_part(lattice, request, part);
  }
  if (stats) {
    *stats = r.stats;
    stats->volume = shape_volume(r.part);
  }
  std::string text;
  {
    Progress part(progress, kTextUnits);
    text = brep_to_text(r.part, part);
  }
  progress.finish();
  return text;
}

void write_lattice_step(const std::string& path, const FlatLattice& lattice, const LatticePartRequest& request,
                        const StepNames& names, Progress& progress, TrimStats* stats) {
  // Checked before the trim, which may take minutes.
  check_output_path(path);
  check_step_name(names.lattice, "lattice_name");
  check_step_name(names.skin, "skin_name");
  check_step_name(names.assembly, "assembly_name");
  const bool one_solid = names.layout == StepLayout::OneSolid;
  LatticePartRequest trim_request = request;
  trim_request.trim.unite_skin = one_solid;
  progress.set_total(kStepPartUnits + kStepFileUnits);
  TrimResult r;
  {
    Progress part(progress, kStepPartUnits);
    r = make_part(lattice, trim_request, part);
  }
  if (stats) *stats = r.stats;
  std::vector<StepPart> parts = {{names.lattice, one_solid ? r.part : r.lattice, names.lattice_color, true, {}}};
  if (!one_solid && !r.skin.IsNull()) parts.push_back({names.skin, r.skin, names.skin_color, true, {}});
  {
    Progress part(progress, kStepFileUnits);
    write_step_assembly(path, parts, names.assembly, part);
  }
  progress.finish();
}

}  // namespace steady
