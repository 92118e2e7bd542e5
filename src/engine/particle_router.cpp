#include "engine/particle_router.hpp"

#include <stdexcept>

namespace gs {

std::unique_ptr<ParticleRouter> make_particle_router(Backend backend) {
  if (backend == Backend::cpu) return make_particle_router_cpu();
#ifdef GS_HAVE_CUDA
  return make_particle_router_cuda();
#else
  throw std::runtime_error("backend cuda asked for, but this grainstorm was built without the CUDA backend");
#endif
}

}  // namespace gs
