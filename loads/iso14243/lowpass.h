// Zero-lag low-pass filtering of a measured signal and the choice of its cutoff (Winter DA,
// Biomechanics and Motor Control of Human Movement, 4th ed., Wiley 2009, section 3.4.4): a
// second-order Butterworth filter run forward and backward (fourth order, no phase lag), its
// cutoff corrected for the double pass (the single-pass cutoff is f_c / 0.802, so that the
// two passes together attenuate f_c by 3 dB), and the cutoff chosen by residual analysis: the
// RMS residual between the signal and its filtered version, plotted against the cutoff, falls
// along a straight line where only noise is removed; that line's intercept at 0 Hz estimates
// the noise RMS, and the cutoff is where the residual equals it (signal distortion and noise
// passed balanced).
//
// Used where a measured load drives a simulation: the rig follows the band the signal lives
// in, not the instrument's noise (analysis/diagnosis/forces_case.h).
#pragma once

#include <vector>

namespace kneesim::loads {

// x sampled at fs [Hz], filtered with cutoff fc [Hz] (0 < fc < fs / 2); the ends are padded
// by odd reflection so that the filter starts settled
std::vector<double> lowpass(const std::vector<double>& x, double fs, double fc);

struct CutoffChoice {
  double cutoff_Hz = 0.0;   // chosen cutoff [Hz]
  double noise_rms = 0.0;   // intercept of the residual line: the noise estimate [signal unit]
};

// residual analysis over cutoffs from 0.5 Hz to 0.45 fs in 0.25 Hz steps; the residual line is
// fitted over the upper third of that range
CutoffChoice residual_analysis_cutoff(const std::vector<double>& x, double fs);

}  // namespace kneesim::loads
