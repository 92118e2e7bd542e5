#pragma once
#include <string>

namespace gs {

// Where kernels run and memory lives.
enum class Backend { cpu, cuda };

Backend parse_backend(const std::string& name);  // "cpu" | "cuda"; throws on anything else
const char* backend_name(Backend b);
bool cuda_backend_built();     // compiled with the CUDA backend
bool cuda_device_available();  // built with CUDA and a device is present
Backend default_backend();     // cuda when a device is available, else cpu
// Binds this process to device local_rank mod the device count; returns
// true when that leaves it a device of its own (local_rank < count). With
// GRAINSTORM_GPU_WAIT=spin|yield|block the host thread waits for the device
// that way (many processes sharing one GPU and fewer cores: block); an
// unknown value throws std::invalid_argument naming the variable.
bool select_cuda_device(int local_rank);
unsigned gpu_wait_flags();  // GRAINSTORM_GPU_WAIT as CUDA device flags; 0 where unset
// GPU lanes per particle in the force computation (backend/cuda/lane_group.cuh).
// force_lanes_setting: GRAINSTORM_FORCE_LANES (1, 2, 4, 8, 16 or 32), 0 where it
// is unset or auto; any other value throws std::invalid_argument naming the
// variable (select_cuda_device checks it at the start). force_lanes: the
// setting, or where it is 0 as many lanes as keep a scene of n particles
// under kForceLaneThreads threads (1 for a scene that fills the GPU with a
// thread each).
constexpr long long kForceLaneThreads = 1 << 17;
constexpr int kMaxForceLanes = 32;
int force_lanes_setting();
int force_lanes(long long n, int setting);
// Whether the CPU computes each touching pair once for both spheres
// (engine/force_kernel.hpp, pairs_of; engine/pairs_once_policy.hpp):
// GRAINSTORM_PAIRS_ONCE unset or auto: where most list entries touch; 1:
// always; 0: never, each sphere computes its own side, as the GPU does. The
// same bits every way (the tests compare them). Any other value throws
// std::invalid_argument naming the variable.
enum class PairsOnceSetting { automatic, always, never };
PairsOnceSetting pairs_once_setting();

// The host threads this process runs its OpenMP loops on (OMP_NUM_THREADS or
// the default), and the cores its CPU affinity lets them use. mpirun binds
// each rank to one core by default, and every thread then shares that core.
struct HostThreads {
  int threads = 1;
  int cores = 1;
};
HostThreads host_threads();

}  // namespace gs
