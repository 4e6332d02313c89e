#include "query/element_evaluator.hpp"

namespace steady::detail {

ElementEvaluator::ElementEvaluator(const Lattice& lattice, std::int64_t margin)
    : lattice_(&lattice),
      g_(lattice.placement().transform()),
      u_(lattice.step_u(), -margin, lattice.counts().u - 1 + margin),
      v_(lattice.step_v(), -margin, lattice.counts().v - 1 + margin),
      w_(lattice.step_w(), -margin, lattice.counts().w - 1 + margin) {}

}  // namespace steady::detail
