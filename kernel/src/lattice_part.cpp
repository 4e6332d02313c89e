#include "steady/lattice_part.hpp"

#include "steady/brep_builder.hpp"
#include "steady/brep_io.hpp"
#include "steady/errors.hpp"
#include "steady/step_assembly.hpp"

namespace steady {

namespace {

TrimResult make_part(const FlatLattice& lattice, const LatticePartRequest& request) {
  TrimResult out;
  if (!request.body_brep) {
    if (request.trim.skin != 0.0) fail_input("skin", "needs a body to wrap");
    out.part = out.lattice = build_lattice_brep(lattice).shape;
    return out;
  }
  return trim_lattice(lattice, brep_from_text(*request.body_brep, "body"), request.trim);
}

}  // namespace

std::string lattice_part_brep(const FlatLattice& lattice, const LatticePartRequest& request) {
  return brep_to_text(make_part(lattice, request).part);
}

void write_lattice_step(const std::string& path, const FlatLattice& lattice, const LatticePartRequest& request,
                        const StepNames& names) {
  LatticePartRequest separate = request;
  separate.trim.unite_skin = false;
  const TrimResult r = make_part(lattice, separate);
  std::vector<StepPart> parts = {{names.lattice, r.lattice, names.lattice_color, true}};
  if (!r.skin.IsNull()) parts.push_back({names.skin, r.skin, names.skin_color, true});
  write_step_assembly(path, parts, names.assembly);
}

}  // namespace steady
