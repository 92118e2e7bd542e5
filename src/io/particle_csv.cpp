#include "io/particle_csv.hpp"

#include <cstdio>
#include <stdexcept>

namespace gs {

std::string snapshot_file_name(long long step) {
  char name[64];
  std::snprintf(name, sizeof(name), "particles_%010lld.csv", step);
  return name;
}

void write_particles_csv(const std::string& path, const ParticleSnapshot& s) {
  const std::string tmp = path + ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "w");
  if (!f) throw std::runtime_error("cannot write " + tmp);
  std::fprintf(f, "# grainstorm particles, time %.17g s, step %lld\n", s.time, s.step);
  std::fprintf(f, "id,material,marker,radius,x,y,z,vx,vy,vz,wx,wy,wz\n");
  for (std::size_t i = 0; i < s.size(); ++i) {
    const Vec3d &x = s.position[i], &v = s.velocity[i], &w = s.angular_velocity[i];
    std::fprintf(f, "%u,%d,%d,%.9g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n", s.id[i],
                 int(s.material[i]), int(s.marker[i]), double(s.radius[i]), x.x, x.y, x.z, v.x, v.y, v.z, w.x, w.y,
                 w.z);
  }
  const bool ok = std::ferror(f) == 0;
  if (std::fclose(f) != 0 || !ok) throw std::runtime_error("error writing " + tmp);
  if (std::rename(tmp.c_str(), path.c_str()) != 0) throw std::runtime_error("cannot rename " + tmp + " to " + path);
}

}  // namespace gs
