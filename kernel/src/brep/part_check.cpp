#include "brep/part_check.hpp"

#include <BRepBndLib.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <Bnd_Box.hxx>
#include <TopExp_Explorer.hxx>

#include <algorithm>
#include <sstream>
#include <stdexcept>
#include <string>

#include "core/disjoint_sets.hpp"
#include "steady/brep/brep_io.hpp"
#include "steady/core/errors.hpp"

namespace steady {

std::int64_t component_count(const FlatLattice& f,
                             const std::vector<std::pair<std::int64_t, std::int64_t>>& touching) {
  DisjointSets sets(static_cast<std::size_t>(f.ball_count()));
  std::int64_t count = f.ball_count();
  auto join = [&](std::int64_t a, std::int64_t b) {
    const std::size_t ra = sets.root(a), rb = sets.root(b);
    if (ra != rb) sets.join(ra, rb), --count;
  };
  for (const FlatBeam& b : f.beams) join(b.a, b.b);
  for (const auto& [a, b] : touching) join(a, b);
  return count;
}

std::vector<std::int64_t> balls_near_invalid_faces(const FlatLattice& f, const TopoDS_Shape& shape, int limit) {
  std::vector<std::int64_t> out;
  for (TopExp_Explorer x(shape, TopAbs_FACE); x.More() && static_cast<int>(out.size()) < limit; x.Next()) {
    if (BRepCheck_Analyzer(x.Current()).IsValid()) continue;
    Bnd_Box box;
    BRepBndLib::Add(x.Current(), box);
    double x0, y0, z0, x1, y1, z1;
    box.Get(x0, y0, z0, x1, y1, z1);
    const Vec3 mid(0.5 * (x0 + x1), 0.5 * (y0 + y1), 0.5 * (z0 + z1));
    std::int64_t best = 0;
    for (std::int64_t i = 1; i < f.ball_count(); ++i)
      if (glm::length(f.balls[i].center - mid) < glm::length(f.balls[best].center - mid)) best = i;
    if (std::find(out.begin(), out.end(), best) == out.end()) out.push_back(best);
  }
  return out;
}

namespace {

// The shape as a reader of its BREP text gets it: the text keeps 15 digits, and a core whose edges met in a cusp was
// valid in memory and invalid once read (docs/brep.md, section 6). The Boolean-free faces of clean hubs read back
// as they were written (tested so), and the text costs time: only shapes with cores go through it.
TopoDS_Shape as_read_back(const TopoDS_Shape& shape) { return brep_from_text(brep_to_text(shape), "lattice"); }

}  // namespace

// One solid per connected component, always; and, where crowded hubs were built from cores (a Fuse of
// OpenCASCADE's, which has returned wrong shapes that it reported as done), a valid shape as it reads back from its
// BREP text. (The Boolean-free faces of clean hubs are valid by construction and tested so; checking them all would
// cost as much as the build.)
void check_built_lattice(const FlatLattice& f, const LatticeBrep& built,
                         const std::vector<std::pair<std::int64_t, std::int64_t>>& touching) {
  const std::int64_t solids = solid_count(built.shape), components = component_count(f, touching);
  const bool with_cores = built.stats.core_hubs > 0;
  const TopoDS_Shape as_read = with_cores ? as_read_back(built.shape) : TopoDS_Shape();
  const bool valid = !with_cores || is_valid(as_read);
  if (valid && solids == components) return;
  std::ostringstream os;
  os << "the B-rep built for this lattice ";
  if (!valid) {
    os << "is invalid near balls";
    for (std::int64_t b : balls_near_invalid_faces(f, as_read, 5)) os << " " << b;
    os << " (" << built.stats.core_hubs << " crowded hubs built from cores)";
  } else {
    os << "has " << solids << " solids for " << components << " connected components";
  }
  os << "; crowded hubs whose beams are nearly as thick as their nodes are not all built yet: thin the beams or "
        "enlarge the nodes";
  fail_input("lattice", os.str());
}

// Every piece of a trimmed part has been checked on its own way (the clean hubs by construction, the cores and
// groups when built, the Booleans' faces by the trim's phases), but not the whole: how the pieces met (shells
// closed, faces joined along shared edges) and, for cores, what their BREP text gives back. A trimmed part has no
// closed-form volume and may hold several solids (a body can cut a lattice apart), so validity is what is checked.
void check_trimmed_part(const FlatLattice& f, const TopoDS_Shape& part, std::int64_t core_hubs) {
  const TopoDS_Shape checked = core_hubs > 0 ? as_read_back(part) : part;
  if (is_valid(checked)) return;
  std::string report = validity_report(checked, 2);
  std::replace(report.begin(), report.end(), '\n', ' ');
  std::ostringstream os;
  os << "the trimmed part is invalid";
  const std::vector<std::int64_t> near = balls_near_invalid_faces(f, checked, 5);
  if (!near.empty()) os << " near balls";
  for (std::int64_t b : near) os << " " << b;
  os << " (" << report << ")";
  throw std::runtime_error(os.str());
}

}  // namespace steady
