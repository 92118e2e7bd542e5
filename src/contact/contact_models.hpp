#pragma once
// The contact models a scene can choose, in one list: the loader, the step
// kernels (one compiled set per model), the time step and the wall loads all
// reach a model through it. A new model is its policy type in
// contact/models/ (contact/contact_model.hpp says what it provides), its id in
// core/types.hpp, and its entry here.
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "contact/models/hertz_mindlin.hpp"
#include "contact/models/hysteretic_linear.hpp"
#include "contact/models/linear_spring_dashpot.hpp"

namespace gs {

template <class... Models>
struct ContactModelList {};

using ContactModels = ContactModelList<LinearSpringDashpot, HertzMindlin, HystereticLinear>;

namespace detail {
template <class F, class First, class... Rest>
decltype(auto) visit_model(ContactModel id, F&& f, ContactModelList<First, Rest...>) {
  if constexpr (sizeof...(Rest) == 0) {
    if (id != First::kId) throw std::logic_error("contact model id " + std::to_string(int(id)) + " is not registered");
    return f(First{});
  } else {
    if (id == First::kId) return f(First{});
    return visit_model(id, std::forward<F>(f), ContactModelList<Rest...>{});
  }
}
template <class... Models>
std::vector<std::string> model_names(ContactModelList<Models...>) {
  return {Models::kName...};
}
template <class... Models>
bool find_model(const std::string& name, ContactModel& id, ContactModelList<Models...>) {
  return ((name == Models::kName ? (id = Models::kId, true) : false) || ...);
}
}  // namespace detail

// f(Model{}) for the model with id `id`: compile-time dispatch from a run-time choice.
template <class F>
decltype(auto) with_contact_model(ContactModel id, F&& f) {
  return detail::visit_model(id, std::forward<F>(f), ContactModels{});
}

// The names scenes use, in list order.
inline std::vector<std::string> contact_model_names() { return detail::model_names(ContactModels{}); }

inline const char* contact_model_name(ContactModel id) {
  return with_contact_model(id, [](auto model) { return decltype(model)::kName; });
}

// The model a scene names; std::invalid_argument for a name not in the list.
inline ContactModel contact_model_named(const std::string& name) {
  ContactModel id{};
  if (!detail::find_model(name, id, ContactModels{})) throw std::invalid_argument("unknown contact model " + name);
  return id;
}

// Every history field a run of `Model` with `effects` keeps per contact.
template <class Model>
constexpr unsigned history_fields_kept(unsigned effects) {
  return ((effects & kFriction) != 0 ? unsigned(kTangentialSprings) : 0u) |
         ((effects & kRollingResistance) != 0 ? unsigned(kRollingSprings) : 0u) | Model::kHistoryFields;
}

// The same, for a model chosen at run time.
inline unsigned history_fields_kept(ContactModel id, unsigned effects) {
  return with_contact_model(id, [effects](auto model) { return history_fields_kept<decltype(model)>(effects); });
}

// Whether a run keeps a contact history (partners per slot) at all.
inline bool keeps_history(ContactModel id, unsigned effects) { return history_fields_kept(id, effects) != 0; }

}  // namespace gs
