#include "io/particle_csv.hpp"

#include <cstdio>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "io/text_file.hpp"

namespace gs {

std::string snapshot_file_name(long long step) {
  char name[64];
  std::snprintf(name, sizeof(name), "particles_%010lld.csv", step);
  return name;
}

void write_particles_csv(const std::string& path, const ParticleSnapshot& s) {
  write_atomically(path, [&](const std::string& temporary) {
    TextFile f(temporary);
    f.printf("# grainstorm particles, time %.17g s, step %lld\n", s.time, s.step);
    // A periodic run's image counts (the snapshot holds them) follow as ix, iy, iz.
    const bool images = !s.image.empty();
    f.printf("id,material,marker,radius,x,y,z,vx,vy,vz,wx,wy,wz%s\n", images ? ",ix,iy,iz" : "");
    for (std::size_t i = 0; i < s.size(); ++i) {
      const Vec3d &x = s.position[i], &v = s.velocity[i], &w = s.angular_velocity[i];
      f.printf("%u,%d,%d,%.9g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g", s.id[i], int(s.material[i]),
               int(s.marker[i]), double(s.radius[i]), x.x, x.y, x.z, v.x, v.y, v.z, w.x, w.y, w.z);
      if (images) f.printf(",%d,%d,%d", int(s.image[i].x), int(s.image[i].y), int(s.image[i].z));
      f.printf("\n");
    }
    f.close();
  });
}

}  // namespace gs
