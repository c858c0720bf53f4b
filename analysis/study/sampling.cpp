#include "analysis/study/sampling.h"

#include <numeric>
#include <stdexcept>

namespace kneesim::study {

uint64_t SplitMix64::next() {
  uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

double SplitMix64::uniform() {
  return (static_cast<double>(next() >> 11) + 0.5) * 0x1.0p-53;
}

uint64_t trial_seed(uint64_t study_seed, long index) {
  SplitMix64 a(study_seed);
  SplitMix64 b(a.next() ^ (static_cast<uint64_t>(index) * 0xd1b54a32d192ed03ULL));
  return b.next();
}

LatinHypercubePlan make_latin_hypercube(uint64_t study_seed, long trials, int variables) {
  LatinHypercubePlan plan;
  plan.trials = trials;
  for (int j = 0; j < variables; ++j) {
    // a stream of its own per variable, apart from every trial stream
    SplitMix64 rng(trial_seed(study_seed ^ 0x4c48535f5045524dULL, j));
    std::vector<long> perm(trials);
    std::iota(perm.begin(), perm.end(), 0L);
    for (long i = trials - 1; i > 0; --i) {  // Fisher-Yates
      const long k = static_cast<long>(rng.next() % static_cast<uint64_t>(i + 1));
      std::swap(perm[i], perm[k]);
    }
    plan.strata.push_back(std::move(perm));
  }
  return plan;
}

std::vector<double> sample_unit(Method method, uint64_t study_seed, long index, int variables,
                                const LatinHypercubePlan* lhs) {
  SplitMix64 rng(trial_seed(study_seed, index));
  std::vector<double> u(variables);
  for (int j = 0; j < variables; ++j) {
    const double r = rng.uniform();
    if (method == Method::kLatinHypercube) {
      if (!lhs || index >= lhs->trials) throw std::logic_error("sample_unit: no LHS plan");
      u[j] = (static_cast<double>(lhs->strata[j][index]) + r) / static_cast<double>(lhs->trials);
    } else {
      u[j] = r;
    }
  }
  return u;
}

}  // namespace kneesim::study
