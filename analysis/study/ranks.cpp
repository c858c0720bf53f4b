#include "analysis/study/ranks.h"

#include <cstdio>
#include <cstdlib>

#include "engine/errors.h"

#ifdef KNEESIM_HAVE_MPI
#define OMPI_SKIP_MPICXX 1  // the C API only
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#endif

namespace kneesim::study {
namespace {

bool launched_by_mpi() {
  for (const char* v : {"OMPI_COMM_WORLD_SIZE", "PMI_SIZE", "PMIX_RANK"}) {
    if (std::getenv(v)) return true;
  }
  return false;
}

}  // namespace

Ranks::Ranks() {
#ifdef KNEESIM_HAVE_MPI
  if (!launched_by_mpi()) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  mpi_ = true;
#else
  if (launched_by_mpi()) {
    std::fprintf(stderr, "warning: launched by mpirun, but this kneesim was built without MPI: "
                         "every rank runs the whole study alone\n");
  }
#endif
}

Ranks::~Ranks() {
#ifdef KNEESIM_HAVE_MPI
  if (mpi_) MPI_Finalize();
#endif
}

void Ranks::require_same(uint64_t hash, const std::string& what) const {
  if (!mpi_) return;
  const std::vector<std::string> all = all_gather(std::to_string(hash));
  for (size_t r = 1; r < all.size(); ++r) {
    if (all[r] != all[0]) {
      throw InputError("the MPI ranks disagree on " + what + ": rank 0 and rank " +
                       std::to_string(r) + " were given different inputs; launch every rank "
                       "with the same config, options and files");
    }
  }
}

std::vector<std::string> Ranks::all_gather(const std::string& mine) const {
  if (!mpi_) return {mine};
#ifdef KNEESIM_HAVE_MPI
  int n = static_cast<int>(mine.size());
  std::vector<int> sizes(size_), offsets(size_);
  MPI_Allgather(&n, 1, MPI_INT, sizes.data(), 1, MPI_INT, MPI_COMM_WORLD);
  int total = 0;
  for (int r = 0; r < size_; ++r) {
    offsets[r] = total;
    total += sizes[r];
  }
  std::string all(static_cast<size_t>(total), '\0');
  MPI_Allgatherv(mine.data(), n, MPI_CHAR, all.data(), sizes.data(), offsets.data(), MPI_CHAR,
                 MPI_COMM_WORLD);
  std::vector<std::string> out;
  for (int r = 0; r < size_; ++r) out.push_back(all.substr(offsets[r], sizes[r]));
  return out;
#else
  return {mine};
#endif
}

void Ranks::abort(int code) const {
#ifdef KNEESIM_HAVE_MPI
  if (mpi_) MPI_Abort(MPI_COMM_WORLD, code);
#endif
  std::exit(code);
}

}  // namespace kneesim::study
