#pragma once
// The thin walls of a scene's `walls:` list (scene_sheets.cpp).
#include "scene/scene_yaml.hpp"

namespace gs::scene_yaml {

// `plate: {point, normal, radius, hole: {radius} | {lengths: [a, b], along}}`:
// the proto's material and motion, the plate's geometry; the hole must fit
// inside the plate's radius (unbounded when absent).
Wall parse_plate(const Val& v, const Wall& proto);
// `cone: {base, axis, length, base_radius, half_angle}`: radius base_radius at
// `base`, widening at half_angle (degrees, in (0, 90)) along `axis`.
Wall parse_cone(const Val& v, const Wall& proto);

}  // namespace gs::scene_yaml
