// The ranks of a distributed study: the one adapter over MPI (design.md: each third-party
// library in one adapter file, ranks.cpp). `mpirun -np R kneesim study ...` starts R processes;
// each computes the trials whose position in the pending list is congruent to its rank, and
// all finished records are gathered at the end. Without mpirun (or in a build without MPI)
// there is one rank and every call is trivial.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace kneesim::study {

class Ranks {
 public:
  // initializes MPI when the process was started by an MPI launcher (OpenMPI's or PMI
  // environment), else a single rank; finalizes on destruction
  Ranks();
  ~Ranks();
  Ranks(const Ranks&) = delete;
  Ranks& operator=(const Ranks&) = delete;

  int rank() const { return rank_; }
  int size() const { return size_; }
  // every rank passes its hash of what defines the study; InputError on every rank when any
  // differs (the ranks were launched with different configs or options)
  void require_same(uint64_t hash, const std::string& what) const;
  // every rank's string, in rank order, on every rank
  std::vector<std::string> all_gather(const std::string& mine) const;
  // stops every rank (a rank's failure after the trials started)
  [[noreturn]] void abort(int code) const;

 private:
  int rank_ = 0, size_ = 1;
  bool mpi_ = false;
};

}  // namespace kneesim::study
