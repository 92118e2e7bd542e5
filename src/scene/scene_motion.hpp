#pragma once
// A wall entry's `motion` and `active` keys (scene_motion.cpp).
#include "scene/scene_yaml.hpp"
#include "walls/timeline.hpp"

namespace gs::scene_yaml {

// `motion:` -> the constant velocity, rotation and start in w; the tables and
// the oscillation in s.
void parse_motion(const Val& v, Wall& w, Timeline& s);
// `active: {from, until}` (from >= 0, default 0; until > from, default never).
ActiveWindow parse_active(const Val& v);

}  // namespace gs::scene_yaml
