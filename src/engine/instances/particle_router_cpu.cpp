#include "backend/cpu/cpu_exec.hpp"
#include "engine/particle_router_impl.hpp"

namespace gs {

std::unique_ptr<ParticleRouter> make_particle_router_cpu() { return std::make_unique<ParticleRouterImpl<CpuExec>>(); }

}  // namespace gs
