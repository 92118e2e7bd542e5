#include "backend/cuda/cuda_exec.cuh"
#include "engine/particle_router_impl.hpp"

namespace gs {

std::unique_ptr<ParticleRouter> make_particle_router_cuda() { return std::make_unique<ParticleRouterImpl<CudaExec>>(); }

}  // namespace gs
