#pragma once
// A scene's contact time (the unit of fraction_of_contact_time) and its
// stable time-step limit: contact/contact_time.hpp and contact/stable_step.hpp
// for the scene's model, materials, pairs and smallest particles.
#include "contact/contact_time.hpp"
#include "contact/stable_step.hpp"
#include "scene/scene.hpp"

namespace gs {

// The parts of `scene` its time step depends on.
ContactScene contact_scene(const SceneSpec& scene);

double critical_contact_time(const SceneSpec& scene);
StableStep stable_time_step(const SceneSpec& scene);

}  // namespace gs
