#include "solver/threads.h"

#include <dlfcn.h>

#include <cstdlib>
#include <mutex>

namespace dform {

void limitLinearAlgebraThreads() {
  // CHOLMOD's supernodal factorisation asks OpenMP for 4 threads in its assembly loops and hands
  // dense blocks to OpenBLAS, which starts one thread per core. On a small shared machine the two
  // pools oversubscribe the cores and spin in futex waits: the pushed-in inverse sample solved in
  // 5.9 s with the defaults and 3.0-3.4 s with one BLAS thread (docs/benchmarks.md). Dynamic
  // OpenMP lets libgomp give CHOLMOD fewer threads than it asks for when the cores are busy.
  // Looked up at run time: the BLAS behind libblas.so.3 need not be OpenBLAS.
  static std::once_flag once;
  std::call_once(once, [] {
    using SetInt = void (*)(int);
    if (!std::getenv("OPENBLAS_NUM_THREADS"))
      if (auto set = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "openblas_set_num_threads"))) set(1);
    if (!std::getenv("OMP_DYNAMIC") && !std::getenv("OMP_THREAD_LIMIT"))
      if (auto set = reinterpret_cast<SetInt>(dlsym(RTLD_DEFAULT, "omp_set_dynamic"))) set(1);
  });
}

}  // namespace dform
