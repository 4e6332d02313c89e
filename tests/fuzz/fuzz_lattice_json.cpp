// Fuzz target: the lattice file loader (docs/lattice-format.md). Any bytes either load or are refused with
// InvalidInput / ResourceLimit. A file that loads must
//   * save and load again to the same text (the format's exact round trip),
//   * evaluate its first and last ball and beam to finite geometry,
//   * answer a point query at its first ball's center with that ball (through the automatic query path).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "fuzz_common.hpp"
#include "steady/lattice/lattice_io.hpp"
#include "steady/query/lattice_query.hpp"

namespace {

using namespace steady;

bool finite(const Ball& b) {
  return std::isfinite(b.center.x) && std::isfinite(b.center.y) && std::isfinite(b.center.z) &&
         std::isfinite(b.radius) && b.radius > 0.0;
}

void check_loaded(const Lattice& lattice) {
  const std::string saved = lattice_to_json(lattice, -1);
  const std::string again = lattice_to_json(lattice_from_json(saved), -1);
  if (again != saved) fuzz::finding("round trip changed the file:\n" + saved + "\n" + again);
  if (lattice.ball_count() == 0) return;
  for (std::int64_t x : {std::int64_t(0), lattice.ball_count() - 1})
    if (!finite(lattice.ball(lattice.ball_id(x)))) fuzz::finding("ball " + std::to_string(x) + " is not finite");
  for (std::int64_t x : {std::int64_t(0), lattice.beam_count() - 1}) {
    if (lattice.beam_count() == 0) break;
    const BeamGeometry g = lattice.beam(lattice.beam_id(x));
    if (!finite(g.start) || !finite(g.end)) fuzz::finding("beam " + std::to_string(x) + " is not finite");
  }
  const Ball first = lattice.ball(lattice.ball_id(0));
  const LatticeQuery query(lattice);
  const BallQueryResult hits = query.query_ball({first.center, 0.0});
  bool found = false;
  for (std::int64_t b : hits.balls) found |= b == 0;
  if (!found) fuzz::finding("the query at ball 0's center does not return ball 0");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::optional<Lattice> lattice;
  fuzz::refusals_only("lattice_from_json", [&] { lattice.emplace(lattice_from_json(text)); });
  // A lattice that loaded must save, load again and answer queries: only the memory budget may refuse now.
  if (lattice) fuzz::budget_refusals_only("loaded lattice", [&] { check_loaded(*lattice); });
  return 0;
}
