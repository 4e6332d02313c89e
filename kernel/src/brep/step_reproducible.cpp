#include "brep/step_reproducible.hpp"

#include <APIHeaderSection_MakeHeader.hxx>
#include <Interface_EntityIterator.hxx>
#include <Interface_GTool.hxx>
#include <Interface_GeneralModule.hxx>
#include <StepRepr_NextAssemblyUsageOccurrence.hxx>
#include <StepVisual_MechanicalDesignGeometricPresentationRepresentation.hxx>
#include <TCollection_HAsciiString.hxx>

#include <algorithm>
#include <functional>
#include <stdexcept>
#include <vector>

namespace steady {

namespace {

// The entities `e` refers to, as the model's protocol lists them. A graph of the whole model gives the same, but it
// lists every entity's references (a tenth of the main job's export) for the few entities walked here.
Interface_EntityIterator shareds_of(const Handle(StepData_StepModel)& model, const Handle(Standard_Transient)& e) {
  Interface_EntityIterator shareds;
  Handle(Interface_GeneralModule) module;
  Standard_Integer case_number = 0;
  if (model->GTool()->Select(e, module, case_number)) module->FillShared(model, case_number, e, shareds);
  return shareds;
}

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
        for (Interface_EntityIterator it = shareds_of(model, e); it.More(); it.Next()) {
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
  // The model's list rebuilt once in the new order (ChangeOrder rebuilds it for every move: a seventh of the main
  // job's export).
  bool moved = false;
  for (std::size_t k = 0; k < order.size(); ++k) moved = moved || model->Number(order[k]) != first + static_cast<int>(k);
  if (!moved) return;
  if (static_cast<int>(order.size()) != count - first + 1)
    throw std::logic_error("make_reproducible: the presentations' order lost or repeated an entity");
  std::vector<Handle(Standard_Transient)> all;
  all.reserve(count);
  for (int i = 1; i < first; ++i) all.push_back(model->Value(i));
  all.insert(all.end(), order.begin(), order.end());
  model->ClearEntities();
  for (const Handle(Standard_Transient)& e : all) model->AddEntity(e);
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
