// A CUDA timeline without Nsight Systems: a CUPTI injection library that
// records every kernel, copy, memset and runtime API call of a process with
// its start and end (ns, one clock for host and device) and writes them, at
// exit, as CSV lines `kind,start,end,name` to $GS_TRACE_FILE (default
// gpu_trace.csv). bench/gpu_trace.sh builds it and runs a command under it
// (CUDA_INJECTION64_PATH); bench/gpu_timeline.py reads what it wrote.
// Tracing costs each API call and kernel a little: read gaps and launch
// costs from it as upper bounds.
#include <cupti.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>

namespace {

constexpr size_t kBufferBytes = 8 << 20;
std::FILE* out = nullptr;
std::mutex out_mutex;

void check(CUptiResult r, const char* what) {
  if (r == CUPTI_SUCCESS) return;
  const char* message = nullptr;
  cuptiGetResultString(r, &message);
  std::fprintf(stderr, "gpu_trace: %s: %s\n", what, message ? message : "unknown CUPTI error");
  std::exit(3);
}

void CUPTIAPI buffer_requested(uint8_t** buffer, size_t* size, size_t* max_records) {
  *buffer = static_cast<uint8_t*>(std::aligned_alloc(8, kBufferBytes));
  *size = kBufferBytes;
  *max_records = 0;
}

void write_record(const CUpti_Activity* record) {
  switch (record->kind) {
    case CUPTI_ACTIVITY_KIND_CONCURRENT_KERNEL:
    case CUPTI_ACTIVITY_KIND_KERNEL: {
      const auto* k = reinterpret_cast<const CUpti_ActivityKernel10*>(record);
      std::fprintf(out, "kernel,%llu,%llu,%s\n", (unsigned long long)k->start, (unsigned long long)k->end, k->name);
      break;
    }
    case CUPTI_ACTIVITY_KIND_MEMCPY: {
      const auto* m = reinterpret_cast<const CUpti_ActivityMemcpy6*>(record);
      std::fprintf(out, "memcpy,%llu,%llu,kind%u %llu B\n", (unsigned long long)m->start, (unsigned long long)m->end,
                   unsigned(m->copyKind), (unsigned long long)m->bytes);
      break;
    }
    case CUPTI_ACTIVITY_KIND_MEMSET: {
      const auto* m = reinterpret_cast<const CUpti_ActivityMemset4*>(record);
      std::fprintf(out, "memset,%llu,%llu,%llu B\n", (unsigned long long)m->start, (unsigned long long)m->end,
                   (unsigned long long)m->bytes);
      break;
    }
    case CUPTI_ACTIVITY_KIND_RUNTIME:
    case CUPTI_ACTIVITY_KIND_DRIVER: {
      const auto* a = reinterpret_cast<const CUpti_ActivityAPI*>(record);
      const char* name = nullptr;
      cuptiGetCallbackName(record->kind == CUPTI_ACTIVITY_KIND_RUNTIME ? CUPTI_CB_DOMAIN_RUNTIME_API
                                                                      : CUPTI_CB_DOMAIN_DRIVER_API,
                           a->cbid, &name);
      std::fprintf(out, "api,%llu,%llu,%s\n", (unsigned long long)a->start, (unsigned long long)a->end,
                   name ? name : "?");
      break;
    }
    default:
      break;
  }
}

void CUPTIAPI buffer_completed(CUcontext, uint32_t, uint8_t* buffer, size_t, size_t valid) {
  {
    std::lock_guard<std::mutex> lock(out_mutex);
    CUpti_Activity* record = nullptr;
    while (out && cuptiActivityGetNextRecord(buffer, valid, &record) == CUPTI_SUCCESS) write_record(record);
  }
  std::free(buffer);
}

void finish() {
  cuptiActivityFlushAll(1);
  std::lock_guard<std::mutex> lock(out_mutex);
  if (out) std::fclose(out);
  out = nullptr;
}

}  // namespace

extern "C" int InitializeInjection(void) {
  const char* path = std::getenv("GS_TRACE_FILE");
  out = std::fopen(path && *path ? path : "gpu_trace.csv", "w");
  if (!out) {
    std::perror("gpu_trace: cannot open the trace file");
    return 0;
  }
  check(cuptiActivityRegisterCallbacks(buffer_requested, buffer_completed), "cuptiActivityRegisterCallbacks");
  check(cuptiActivityEnable(CUPTI_ACTIVITY_KIND_CONCURRENT_KERNEL), "enable kernels");
  check(cuptiActivityEnable(CUPTI_ACTIVITY_KIND_MEMCPY), "enable copies");
  check(cuptiActivityEnable(CUPTI_ACTIVITY_KIND_MEMSET), "enable memsets");
  check(cuptiActivityEnable(CUPTI_ACTIVITY_KIND_RUNTIME), "enable runtime API");
  std::atexit(finish);
  return 1;
}
