#pragma once
// Whether a scene run in precision fp32_full can resolve its contacts: fp32
// positions are spaced 2^-23 of their magnitude apart, so a bed far from the
// origin cannot tell its spheres' overlaps apart (the seed rescaled its
// geometry for this reason). fp32 and fp64 keep positions in fp64 and always pass.
#include <string>

#include "scene/scene.hpp"

namespace gs {

// The coarsest fp32 spacing allowed, as a fraction of the smallest radius.
constexpr double kFp32SpacingOfRadius = 1e-3;

// Spacing of adjacent fp32 values near |x|.
double fp32_spacing(double x);

// Why fp32 state cannot resolve the scene, or empty when it can.
std::string fp32_state_problem(const SceneSpec& scene);

}  // namespace gs
