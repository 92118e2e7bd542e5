#pragma once
// What an edit of a scene file changed, value by value: a restart with an
// edited scene (`grainstorm run --restart ... --edited-scene`) logs it, so
// that the run's log says how the continued run differs from the one that
// wrote the checkpoint.
#include <string>
#include <vector>

namespace gs {

// One line per value that differs between two scene texts, by key path in
// the order of `after` (removed values last): "changed walls[0].cylinder.caps:
// bottom -> both", "added output.fields: [...]", "removed verlet_skin: 0.3".
// A list of scalars ([x, y, z]) is one value. Comments and layout are not
// values: texts that differ only in them give no line. A text that is not
// YAML gives one line saying so.
std::vector<std::string> scene_differences(const std::string& before, const std::string& after);

}  // namespace gs
