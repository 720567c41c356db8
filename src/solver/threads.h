// How many threads the linear algebra under the solver may use.
#pragma once

namespace dform {

/// Once per process, before the first factorisation: OpenBLAS to one thread and OpenMP's
/// dynamic adjustment on, unless the user set OPENBLAS_NUM_THREADS, OMP_DYNAMIC or
/// OMP_THREAD_LIMIT. Why and what it measured: docs/benchmarks.md ("Threads").
void limitLinearAlgebraThreads();

}  // namespace dform
