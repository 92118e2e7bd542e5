// `marking:` -> SceneSpec::marking (docs/SCENES.md).
#include "scene/scene_sections.hpp"

namespace gs::scene_yaml {

void parse_marking(const Map& top, SceneSpec& s) {
  if (!top.has("marking")) return;
  const Map m(top.get("marking"), {"time", "plane", "front", "back"});
  MarkingSpec k;
  k.time = nonnegative(m.get("time"));
  if (!(k.time <= s.duration)) fail(m.get("time"), "must not exceed the duration " + str(s.duration) + " s, got " + str(k.time));
  const Map plane(m.get("plane"), {"point", "normal"});
  k.point = vec3(plane.get("point"));
  k.normal = unit_vector(plane.get("normal"));
  k.front = std::uint8_t(integer(m.get("front"), 0, 255));
  k.back = std::uint8_t(integer(m.get("back"), 0, 255));
  s.marking = k;
}

}  // namespace gs::scene_yaml
