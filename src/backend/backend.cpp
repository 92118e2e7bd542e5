#define GS_CUDA_HOST_CODE
#include "backend/backend.hpp"

#include <sched.h>
#include <omp.h>

#include <cstdlib>
#include <stdexcept>

#include "backend/check.hpp"
#include "backend/memory.hpp"

namespace gs {

Backend parse_backend(const std::string& name) {
  if (name == "cpu") return Backend::cpu;
  if (name == "cuda") return Backend::cuda;
  throw std::invalid_argument("unknown backend '" + name + "' (expected cpu or cuda)");
}

const char* backend_name(Backend b) { return b == Backend::cpu ? "cpu" : "cuda"; }

bool cuda_backend_built() {
#ifdef GS_HAVE_CUDA
  return true;
#else
  return false;
#endif
}

bool cuda_device_available() {
#ifdef GS_HAVE_CUDA
  int count = 0;
  return cudaGetDeviceCount(&count) == cudaSuccess && count > 0;
#else
  return false;
#endif
}

// How the host thread waits for the device, from GRAINSTORM_GPU_WAIT; 0 (the
// CUDA runtime's choice: spinning, while the process has fewer contexts than
// the machine has cores) where it is unset.
unsigned gpu_wait_flags() {
  const char* v = std::getenv("GRAINSTORM_GPU_WAIT");
  if (!v) return 0;
  const std::string mode(v);
#ifdef GS_HAVE_CUDA
  if (mode == "spin") return cudaDeviceScheduleSpin;
  if (mode == "yield") return cudaDeviceScheduleYield;
  if (mode == "block") return cudaDeviceScheduleBlockingSync;
#else
  if (mode == "spin" || mode == "yield" || mode == "block") return 0;
#endif
  throw std::invalid_argument("GRAINSTORM_GPU_WAIT must be spin, yield or block, got '" + mode + "'");
}

int force_lanes_setting() {
  const char* v = std::getenv("GRAINSTORM_FORCE_LANES");
  if (!v || !*v || std::string(v) == "auto") return 0;
  const std::string s(v);
  for (int lanes = 1; lanes <= kMaxForceLanes; lanes *= 2)
    if (s == std::to_string(lanes)) return lanes;
  throw std::invalid_argument("GRAINSTORM_FORCE_LANES must be auto, 1, 2, 4, 8, 16 or 32, got '" + s + "'");
}

PairsOnceSetting pairs_once_setting() {
  const char* v = std::getenv("GRAINSTORM_PAIRS_ONCE");
  const std::string s = v ? v : "";
  if (s.empty() || s == "auto") return PairsOnceSetting::automatic;
  if (s == "1") return PairsOnceSetting::always;
  if (s == "0") return PairsOnceSetting::never;
  throw std::invalid_argument("GRAINSTORM_PAIRS_ONCE must be auto, 1 or 0, got '" + s + "'");
}

int force_lanes(long long n, int setting) {
  if (setting != 0) return setting;
  int lanes = 1;
  while (lanes < kMaxForceLanes && n * lanes * 2 <= kForceLaneThreads) lanes *= 2;
  return lanes;
}

bool select_cuda_device(int local_rank) {
#ifdef GS_HAVE_CUDA
  const unsigned wait = gpu_wait_flags();
  force_lanes_setting();  // an unknown setting fails here, not at the first step
  cuda_pool_setting();    // the same
  int count = 0;
  GS_CUDA_CHECK(cudaGetDeviceCount(&count));
  if (count == 0) throw std::runtime_error("no CUDA device to bind local rank " + std::to_string(local_rank) + " to");
  GS_CUDA_CHECK(cudaSetDevice(local_rank % count));
  if (wait != 0) GS_CUDA_CHECK(cudaSetDeviceFlags(wait));
  return local_rank < count;
#else
  (void)local_rank;
  return false;
#endif
}

HostThreads host_threads() {
  HostThreads h;
  h.threads = omp_get_max_threads();
  cpu_set_t set;
  CPU_ZERO(&set);
  h.cores = sched_getaffinity(0, sizeof(set), &set) == 0 ? CPU_COUNT(&set) : h.threads;
  return h;
}

Backend default_backend() { return cuda_device_available() ? Backend::cuda : Backend::cpu; }

}  // namespace gs
