#pragma once
// A scene's contact time (the unit of fraction_of_contact_time) and its
// stable time-step limit: contact/contact_time.hpp and contact/stable_step.hpp
// for the scene's model, materials, pairs and smallest particles.
#include <string>

#include "contact/contact_time.hpp"
#include "contact/stable_step.hpp"
#include "scene/scene.hpp"

namespace gs {

// The parts of `scene` its time step depends on.
ContactScene contact_scene(const SceneSpec& scene);

double critical_contact_time(const SceneSpec& scene);
StableStep stable_time_step(const SceneSpec& scene);

// Sets scene.stable_time_step and stable_step_binding to the scene's limit
// and says what is wrong with scene.time_step against it ("" where nothing
// is): the rule of the scene loader, and of the benchmarks that build their
// scenes in code. Needs scene.contact_time.
std::string time_step_problem(SceneSpec& scene);

}  // namespace gs
