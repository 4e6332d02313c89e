#include "query/element_evaluator.hpp"

namespace steady::detail {
namespace {
// The steady-brick view of a lattice in its own axes, or nullptr (not a brick, or a reordered one: the
// query paths run on its brick lattice instead).
const SteadyBrick* own_brick(const Lattice& lattice) {
  const SteadyBrick* view = lattice.layout().steady_brick();
  return view && !view->reordered() ? view : nullptr;
}
}  // namespace

ElementEvaluator::ElementEvaluator(const Lattice& lattice, std::int64_t margin) : lattice_(&lattice) {
  const SteadyBrick* brick = own_brick(lattice);
  if (!brick) return;
  steady_ = true;
  g_ = brick->placement.transform();
  u_ = PowerTable(brick->steps[0], -margin, lattice.counts().u - 1 + margin);
  v_ = PowerTable(brick->steps[1], -margin, lattice.counts().v - 1 + margin);
  w_ = PowerTable(brick->steps[2], -margin, lattice.counts().w - 1 + margin);
}

}  // namespace steady::detail
