#pragma once
// Independent runs of one case at the same time (issue 23: the cores a case is given, used
// by runs instead of by threads inside one small grid). Each job — typically one
// vv::run_case_scene — runs on its own thread with ONE OpenMP thread, at most `workers`
// at once; workers = 0: omp_get_max_threads() (OMP_NUM_THREADS, the cores of the test).
// A run's results do not depend on its thread count (a project rule, tested by
// CellSimulation.IndexFieldArrangementsGiveTheSameBits and the fluid determinism tests), so the
// runs give the same bits as one after the other; the HDF5 library is thread-safe (its
// global lock serialises the run writers). With one worker the jobs run in order on the
// calling thread, unchanged. Jobs start in the given order: put the longest first. The
// caller assembles its record after all have finished, in its own order. The exception of
// the first failing job (by index) is rethrown once every job has finished.
#include <functional>
#include <vector>

namespace erythro::vv {

void run_concurrently(const std::vector<std::function<void()>>& jobs, int workers = 0);

}  // namespace erythro::vv
