#pragma once
// Connectors and rods as STEP files (step_assembly.hpp's writer): each family of connectors is a part of its own,
// made once and placed at every member, as a manufacturer or a CAD assembly wants it.
#include <cstddef>
#include <string>

#include "steady/brep/connectors.hpp"
#include "steady/core/progress.hpp"

namespace steady {

// The part names in the files: "Connector_<k>" (k from 1, in family order) and "Rod_<k>" (k from 1, in cut-list
// order: by increasing length).
std::string connector_part_name(std::size_t family);
std::string rod_part_name(std::size_t cut);

// One family's template alone, in its own frame (its node at the origin): a STEP file holding one solid. Throws
// InvalidInput naming "family" when there is no such family, "path" when the file cannot be written.
void write_connector_family_step(const std::string& path, const ConnectorParts& parts, std::size_t family,
                                 Progress& progress = no_progress());

// One assembly: a part per family placed at each of its members, and (with_rods) a part per cut-list entry, a rod
// of that length placed on each of its beams. Cancelled while the shapes are translated leaves the file untouched.
void write_connectors_step(const std::string& path, const ConnectorParts& parts, bool with_rods = true,
                           Progress& progress = no_progress());

}  // namespace steady
