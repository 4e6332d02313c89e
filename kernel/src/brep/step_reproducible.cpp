#include "brep/step_reproducible.hpp"

#include <APIHeaderSection_MakeHeader.hxx>
#include <Interface_EntityIterator.hxx>
#include <Interface_Graph.hxx>
#include <StepRepr_NextAssemblyUsageOccurrence.hxx>
#include <StepVisual_MechanicalDesignGeometricPresentationRepresentation.hxx>
#include <TCollection_HAsciiString.hxx>

#include <algorithm>
#include <functional>
#include <vector>

namespace steady {

namespace {

// The presentations (MDGPRs) and everything OpenCASCADE added after the first of them, put in an order that depends
// on the entities alone: presentations sorted by the numbers of the entities before them that they refer to (the
// geometry they colour, its context: numbered in translation order, which is deterministic), each followed by what
// it refers to that lies in this tail, depth first; then the rest of the tail as it was.
void order_presentations(const Handle(StepData_StepModel)& model) {
  const int count = model->NbEntities();
  int first = 0;
  std::vector<Handle(Standard_Transient)> presentations;
  for (int i = 1; i <= count; ++i)
    if (model->Value(i)->IsKind(STANDARD_TYPE(StepVisual_MechanicalDesignGeometricPresentationRepresentation))) {
      if (!first) first = i;
      presentations.push_back(model->Value(i));
    }
  if (presentations.size() < 2) return;
  const Interface_Graph graph(model);
  auto in_tail = [&](const Handle(Standard_Transient)& e) { return model->Number(e) >= first; };
  // Depth first from `e` through the tail: `visit` for each tail entity (once), `outside` for each reference
  // leaving the tail.
  std::vector<char> seen(count + 1, 0);
  std::function<void(const Handle(Standard_Transient)&, const std::function<void(const Handle(Standard_Transient)&)>&,
                     std::vector<int>*)>
      walk = [&](const Handle(Standard_Transient)& e, const std::function<void(const Handle(Standard_Transient)&)>& visit,
                 std::vector<int>* outside) {
        seen[model->Number(e)] = 1;
        visit(e);
        for (Interface_EntityIterator it = graph.Shareds(e); it.More(); it.Next()) {
          const Handle(Standard_Transient)& s = it.Value();
          if (!in_tail(s)) {
            if (outside) outside->push_back(model->Number(s));
          } else if (!seen[model->Number(s)]) {
            walk(s, visit, outside);
          }
        }
      };
  std::vector<std::pair<std::vector<int>, Handle(Standard_Transient)>> keyed;
  for (const Handle(Standard_Transient)& p : presentations) {
    std::vector<int> key;
    walk(p, [](const Handle(Standard_Transient)&) {}, &key);
    std::sort(key.begin(), key.end());
    keyed.emplace_back(key, p);
    std::fill(seen.begin(), seen.end(), 0);
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<Handle(Standard_Transient)> order;
  for (const auto& [key, p] : keyed)
    if (!seen[model->Number(p)]) walk(p, [&](const Handle(Standard_Transient)& e) { order.push_back(e); }, nullptr);
  for (int i = first; i <= count; ++i)
    if (!seen[i]) order.push_back(model->Value(i));
  // Move each into place; ChangeOrder shifts the entities between the two numbers along.
  for (std::size_t k = 0; k < order.size(); ++k) {
    const int now = model->Number(order[k]), wanted = first + static_cast<int>(k);
    if (now != wanted) model->ChangeOrder(now, wanted);
  }
}

}  // namespace

void make_reproducible(const Handle(StepData_StepModel)& model) {
  APIHeaderSection_MakeHeader header(model);
  if (header.HasFn()) header.SetTimeStamp(new TCollection_HAsciiString("2020-01-01T00:00:00"));
  int occurrence = 0;
  for (int i = 1; i <= model->NbEntities(); ++i)
    if (auto usage = Handle(StepRepr_NextAssemblyUsageOccurrence)::DownCast(model->Value(i)))
      usage->SetId(new TCollection_HAsciiString(++occurrence));
  order_presentations(model);
}

}  // namespace steady
