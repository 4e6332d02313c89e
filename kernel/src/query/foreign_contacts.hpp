#pragma once
// Elements that meet foreign ones: a ball touching a beam of another node, two beams with no common ball, two
// balls (the clean check's rules 2 to 4, clean_check.hpp). No hub-by-hub construction holds there: the B-rep
// (brep/foreign_groups.hpp) and the mesh (mesh/mesh_groups.hpp) build the hubs of every element in a contact as
// one group, joined by the pairs listed here.
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "steady/lattice/flat_lattice.hpp"

namespace steady {

struct ForeignContacts {
  std::int64_t issue_count = 0;                                // contacts found (overlapping exit circles aside)
  std::vector<std::pair<std::int64_t, std::int64_t>> joined;   // balls whose hubs are built in one group
  std::vector<char> involved;                                  // per beam: it meets a foreign element
  std::string description;                                     // the first contacts, for messages
  bool empty() const { return issue_count == 0; }
};

// The contacts of a listing, by the clean check without its rule on exit circles (crowded hubs build those): a
// contact joins a ball's hub, or both hubs of a beam.
ForeignContacts foreign_contacts(const FlatLattice& f);

}  // namespace steady
