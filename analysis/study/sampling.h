// Sampling plans of a study: plain Monte Carlo and Latin hypercube. A trial's sample is a pure
// function of (study seed, trial index, number of trials) so that any thread or rank computes
// any trial alone and trials.csv is the same for every split (design.md "Determinism").
//
// The generator is splitmix64 (Steele, Lea & Flood 2014): a 64-bit counter hashed by a fixed
// mixer. It is portable bit for bit (no std:: distributions, whose output is
// implementation-defined), and a trial's stream is seeded by hashing the study seed with the
// trial index. Latin hypercube: variable j of trial i falls in stratum pi_j(i) of N equal
// probability strata, pi_j a permutation drawn from the study seed and j alone (McKay, Beckman
// & Conover 1979), at a uniform position inside the stratum from the trial's own stream.
#pragma once

#include <cstdint>
#include <vector>

namespace kneesim::study {

enum class Method { kMonteCarlo, kLatinHypercube, kAdvancedMeanValue };

class SplitMix64 {
 public:
  explicit SplitMix64(uint64_t seed) : state_(seed) {}
  uint64_t next();
  // uniform in (0, 1), never 0 or 1: (k + 0.5) / 2^53 for a 53-bit k
  double uniform();

 private:
  uint64_t state_;
};

// the seed of trial `index` of a study seeded with `study_seed`
uint64_t trial_seed(uint64_t study_seed, long index);

// one stratum permutation per variable, shared by every trial of a Latin hypercube study
struct LatinHypercubePlan {
  long trials = 0;
  std::vector<std::vector<long>> strata;  // [variable][trial] -> stratum
};
LatinHypercubePlan make_latin_hypercube(uint64_t study_seed, long trials, int variables);

// the probabilities u in (0, 1) of every variable for trial `index` (Monte Carlo: the trial's
// stream; Latin hypercube: the trial's stratum plus a uniform offset from the stream)
std::vector<double> sample_unit(Method method, uint64_t study_seed, long index, int variables,
                                const LatinHypercubePlan* lhs);

}  // namespace kneesim::study
