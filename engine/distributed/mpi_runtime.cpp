#include "engine/distributed/mpi_runtime.hpp"

#include <fmt/format.h>
#include <mpi.h>

#include <cstdlib>
#include <mutex>
#include <utility>

#include "engine/core/error.hpp"

#if defined(__SANITIZE_ADDRESS__)
#include <sanitizer/lsan_interface.h>
// Open MPI keeps its set-up allocations to the end of the process; they are not Rift's leaks. Those made
// inside MPI_Init are not tracked at all (mpi_runtime_init): some come from plug-ins MPI_Init loads,
// rejects and unloads, which no stack can name afterwards. The rest are named by the library (or the libc
// function) that made them: the allocation stacks are unwound the fast way (frame pointers, ASan's
// default), which names the allocating frame reliably; the DWARF unwinder, which would see further into
// libraries built without frame pointers, made every allocation ten times dearer (CGAL's meshing above
// all).
extern "C" const char* __lsan_default_suppressions() {
  return "leak:libmpi\nleak:libopen-pal\nleak:libopen-rte\nleak:libhwloc\nleak:libevent\nleak:libpmix\n"
         "leak:mca_\nleak:libudev\nleak:libfabric\nleak:libucs\nleak:libucp\nleak:libpsm\nleak:libibverbs\n"
         "leak:__vasprintf_internal\nleak:strdup\n";
}
#endif

namespace rift {
namespace {

void finalise_mpi() {
  int finalised = 0;
  MPI_Finalized(&finalised);
#if defined(__SANITIZE_ADDRESS__)
  // MPI_Finalize unloads Open MPI's plug-ins and leaves their one-off allocations unreachable and
  // unattributable (LeakSanitizer reports them from "<unknown module>"): sanitizer builds skip it in a
  // singleton process, which may exit without it. A rank of an mpirun job must finalise, or mpirun reports
  // the job as failed.
  int size = 1;
  if (!finalised) MPI_Comm_size(MPI_COMM_WORLD, &size);
  if (!finalised && size > 1) MPI_Finalize();
#else
  if (!finalised) MPI_Finalize();
#endif
}

// A non-negative integer from the environment, or -1.
int environment_count(const char* name) {
  const char* text = std::getenv(name);
  if (!text || !*text) return -1;
  char* end = nullptr;
  const long v = std::strtol(text, &end, 10);
  return *end == '\0' && v >= 0 && v < (1L << 30) ? int(v) : -1;
}

}  // namespace

MpiRank launched_rank() {
  for (const auto& [rank, size] : {std::pair{"OMPI_COMM_WORLD_RANK", "OMPI_COMM_WORLD_SIZE"},
                                   std::pair{"PMI_RANK", "PMI_SIZE"}, std::pair{"PMIX_RANK", "PMIX_SIZE"}}) {
    const int r = environment_count(rank), n = environment_count(size);
    if (r >= 0 && n >= 1) return {r, n};
  }
  return {};
}

MpiRank mpi_runtime_init() {
  static std::once_flag once;
  std::call_once(once, [] {
    int initialised = 0;
    MPI_Initialized(&initialised);
    if (initialised) return;  // a host program's MPI: it finalises it too
    // Keep Open MPI's plug-ins loaded until exit so that what they allocate stays attributable (the
    // sanitizer builds suppress those allocations by library name). Does not override the user's choice.
    setenv("OMPI_MCA_mca_base_component_disable_dlclose", "1", 0);
#if defined(__SANITIZE_ADDRESS__)
    __lsan_disable();  // Open MPI's own set-up (see the suppressions above)
#endif
    int provided = 0;
    const int init = MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
#if defined(__SANITIZE_ADDRESS__)
    __lsan_enable();
#endif
    if (init != MPI_SUCCESS) throw Error("MPI_Init_thread failed: MPI could not start");
    std::atexit(finalise_mpi);
    if (provided < MPI_THREAD_FUNNELED)
      throw Error(fmt::format("MPI grants thread level {}, below MPI_THREAD_FUNNELED ({})", provided,
                              int(MPI_THREAD_FUNNELED)));
  });
  MpiRank r;
  MPI_Comm_rank(MPI_COMM_WORLD, &r.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &r.size);
  return r;
}

}  // namespace rift
