// The files of a study, written atomically by rank 0 once every trial is in:
//   trials.csv        one row per trial by index: index, seed, [point], every input (by config
//                     key), every scalar measure, status ("ok" or "failed: <reason>")
//   envelopes.csv     per curve sample: p01 / p50 / p99 of each curve and the nominal trace
//                     (AP and IE over the gait cycle; wear_envelopes.csv against cycles)
//   sensitivity.csv   parameter, measure, abs_corr: |Pearson r| over the successful trials
//                     (AMV: the direction cosine |a_j| / |a| of the mean-value model, which
//                     equals |r| for a linear model of normal inputs)
//   summary.json      per measure mean, sd, p01, p50, p99 (AMV: mean-value and corrected
//                     percentiles per level, with run counts), trials done and failed, seconds
//   measured_kinematics.csv  the measured trace the problem carries (knee: the config's
//                     output.measured_kinematics), drawn over the envelopes
//   plots             envelopes.png, sensitivity.png, wear_envelopes.png (tools/plots/study.py)
// summary.json is written last: its presence marks a complete study.
#pragma once

#include <filesystem>

#include "analysis/study/study.h"

namespace kneesim::study {

void clear_study_outputs(const std::filesystem::path& dir);
void write_study_outputs(const StudyProblem& p, const StudyOptions& o, const StudyResult& r);

}  // namespace kneesim::study
