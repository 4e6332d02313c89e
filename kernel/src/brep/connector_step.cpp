#include "steady/brep/connector_step.hpp"

#include "steady/brep/step_assembly.hpp"
#include "steady/core/errors.hpp"

namespace steady {

namespace {

// Colours of the parts in a CAD view: connectors alternate so neighbouring families read apart (the
// dissertation's figure 4.14 shows red and blue families); rods are left to the reader's default colour.
constexpr std::array<double, 3> kConnectorColors[] = {
    {0.80, 0.20, 0.20}, {0.20, 0.35, 0.85}, {0.95, 0.65, 0.10}, {0.20, 0.65, 0.30}, {0.60, 0.30, 0.70}, {0.10, 0.65, 0.70}};

StepPart family_part(const ConnectorParts& parts, std::size_t family) {
  StepPart part;
  part.name = connector_part_name(family);
  part.shape = parts.templates[family];
  part.color = kConnectorColors[family % (sizeof kConnectorColors / sizeof kConnectorColors[0])];
  return part;
}

}  // namespace

std::string connector_part_name(std::size_t family) { return "Connector_" + std::to_string(family + 1); }
std::string rod_part_name(std::size_t cut) { return "Rod_" + std::to_string(cut + 1); }

void write_connector_family_step(const std::string& path, const ConnectorParts& parts, std::size_t family,
                                 Progress& progress) {
  if (family >= parts.templates.size())
    fail_input("family", "there are " + std::to_string(parts.templates.size()) + " families (got index " +
                             std::to_string(family) + ")");
  write_step_assembly(path, {family_part(parts, family)}, connector_part_name(family), progress);
}

void write_connectors_step(const std::string& path, const ConnectorParts& parts, bool with_rods, Progress& progress) {
  std::vector<StepPart> out;
  for (std::size_t k = 0; k < parts.templates.size(); ++k) {
    StepPart part = family_part(parts, k);
    for (const ConnectorPlacement& m : parts.plan.families[k].members) part.instances.push_back(connector_transform(m));
    out.push_back(std::move(part));
  }
  if (with_rods)
    for (std::size_t c = 0; c < parts.plan.cut_list.size(); ++c) {
      const RodLength& cut = parts.plan.cut_list[c];
      StepPart rod;
      rod.name = rod_part_name(c);
      rod.shape = rod_solid(parts.plan.parameters.rod_radius, cut.length);
      // Uncoloured: each coloured part adds a presentation that make_reproducible (step_reproducible.cpp) moves
      // into place one entity at a time, quadratic in the file: 249 coloured rod lengths of a BeCOTS slab took
      // 123 s to write, uncoloured 0.8 s.
      rod.has_color = false;
      for (std::int64_t r : cut.rods) rod.instances.push_back(rod_transform(parts.plan.rods[r]));
      out.push_back(std::move(rod));
    }
  write_step_assembly(path, out, "Connectors", progress);
}

}  // namespace steady
