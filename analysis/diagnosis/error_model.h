// The error model of a diagnosis fit: what separates a measurement from the model besides the
// model's own error. Three parts, each fitted with every candidate and shared by all of them:
//
//   correlation  residuals of one series (a load-cell record in time, a kinematics channel over
//                the gait cycle, a specimen's repeated weighings) are an Ornstein-Uhlenbeck
//                (continuous AR(1)) process along the series' abscissa plus a white part:
//                corr(x_i, x_j) = (1 - nugget) exp(-|x_i - x_j| / ell) for i != j, ell and the
//                nugget profiled. Instrument errors are not white: load cells drift,
//                fluoroscopic registration errors are smooth over the cycle; and they are not
//                one process: electrical noise adds a white part to a drift.
//   random effects  per specimen (wear): the wear factor scatters multiplicatively (a slope
//                along d prediction / d ln k) and the soak-control correction leaves an offset
//                in every weighing of a specimen (an intercept on the volume rows); their
//                variance ratios are profiled.
//   nuisance terms  linear terms of the instrument added to the prediction (an offset and a
//                drift of a load cell, crosstalk and gain between cells, a registration offset,
//                the coupling of AP to IE through a misplaced rotation centre), profiled out by
//                least squares at every evaluation, free or with a Gaussian prior of stated sd
//                (an instrument's specification: gain and crosstalk of a few percent). They are
//                reported, never named as causes.
//
// The fit is generalized least squares: the weighted residuals z_i = w_i (y_i - f_i) of one
// cluster (rows that are not independent: a specimen, or a series) have covariance sigma^2 C,
// C = A(ell, nugget) + rho g g^T + rho_o h h^T (A the correlation between rows of a series,
// g the specimen slope direction, h the specimen offset direction, in weighted units); every
// cluster is whitened by its Cholesky factor, so the likelihood is exact. The effective sample
// size of AICc's small-sample term follows the correlation: n_eff = sum over series of
// 1 + sum_i (1 - phi_i) / (1 + phi_i), phi_i = exp(-dx_i / ell) (n for white residuals; about
// n (1 - phi) / (1 + phi) for an AR(1) series).
//
// Small pure kernels (no fitting here): covariance assembly and whitening, the nuisance solve,
// n_eff, and correlated draws for the detection-limit simulation.
#pragma once

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <functional>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace kneesim::diagnosis {

// correlation of the residuals along a series' abscissa
enum class Correlation { none, ou };

// a linear term of the measuring instrument, added to every model's prediction and fitted with
// it; reported, never named as a cause
struct NuisanceTerm {
  std::string name;          // with unit, e.g. "offset_N", "medial_gain" (per unit prediction)
  std::string description;   // one line for reports
  double prior_sd = 0.0;     // Gaussian prior sd in the term's unit; 0: free (flat prior)
  std::string prior_key;     // --noise-param key setting prior_sd ("" when fixed)
  // the term's contribution per unit value at the measured rows `rows` (indices into the
  // case's measurements), given the model's prediction at those rows [quantity unit per term
  // unit]; 0 where it does not act
  std::function<Eigen::VectorXd(const std::vector<int>& rows, const Eigen::VectorXd& prediction)>
      column;
  double prior_scale = 1.0;  // prior_sd = prior_scale x the key's value (a term that is the
                             // difference of two terms of the key's sd: sqrt(2))
  // a prior-bound term in a held-out prediction: true, its value fitted on the training rows
  // (a calibration the same over the record); false, its prior mean 0: the held-out score then
  // judges the models without the term, and the term is judged by its prior in the likelihood
  // only (a term whose span holds a candidate's signal: carried, it lets `none` borrow any
  // correction the training rows ask for, unbounded by the prior, and the held-out gate cannot
  // see the candidate; forces_case.cpp)
  bool carried_to_heldout = true;
};

// the error model a case offers (its "instrument" model) and the reduced ones selected by name
struct ErrorModel {
  std::string name = "white";            // white, correlated, instrument
  Correlation correlation = Correlation::none;
  bool specimen_offset = false;          // random offset per specimen on `offset_quantity` rows
  std::vector<NuisanceTerm> nuisance;
};

// the names --noise-model accepts, in order of increasing structure
const std::vector<std::string>& error_model_names();

// `name` ("white", "correlated" or "instrument") reduced from the case's full model `full`
// with --noise-param values applied (keys: the nuisance terms' prior keys, "ou" = 0 or 1 to
// switch the correlation off or on, "specimen_offset" = 0 or 1); throws InputError naming the
// option and the allowed values or keys
ErrorModel select_error_model(const ErrorModel& full, const std::string& name,
                              const std::map<std::string, double>& params,
                              const std::string& case_name);

// One cluster's rows and what its covariance needs, per row: the weight w, the specimen slope
// direction g (unweighted d prediction / d ln k), whether the specimen offset acts (h), the
// series index and abscissa.
struct CovarianceRows {
  const Eigen::VectorXd* w = nullptr;        // weights per measured row
  const Eigen::VectorXd* dg = nullptr;       // slope direction per row (unweighted), or null
  const std::vector<char>* offset = nullptr; // 1 where the specimen offset acts, or null
  const std::vector<int>* series = nullptr;  // series index per row, or null (one per row)
  const std::vector<double>* x = nullptr;    // abscissa per row
};

// noise parameters that set C (the weights are in CovarianceRows)
struct CovarianceParams {
  double rho = 0.0;       // specimen slope variance / sigma^2 (weighted units) [-]
  double rho_offset = 0.0;  // specimen offset variance / sigma^2 (weighted units) [-]
  double ell = 0.0;       // OU correlation length [abscissa unit]; 0: white
  double nugget = 0.0;    // white fraction of a correlated series' variance [-]: C = (1 - nugget)
                          // A(ell) + nugget I within a series
};

// Cholesky factors of the clusters' covariances, for whitening residuals given in the clusters'
// flattened row order (rows may repeat across clusters: bootstrap draws)
class Whitener {
 public:
  Whitener() = default;
  Whitener(const std::vector<std::vector<int>>& clusters, const CovarianceRows& rows,
           const CovarianceParams& p);
  // L^-1 z per cluster; z in flattened cluster order (weighted residuals)
  Eigen::VectorXd whiten(const Eigen::VectorXd& z) const;
  // L^-1 applied to every column of M (rows in flattened cluster order)
  Eigen::MatrixXd whiten(const Eigen::MatrixXd& m) const;
  // L xi per cluster: a draw of weighted residuals with covariance C from white xi
  Eigen::VectorXd color(const Eigen::VectorXd& xi) const;
  double log_det() const { return log_det_; }  // sum over clusters of ln det C
  Eigen::Index size() const { return size_; }

 private:
  struct Block {
    Eigen::Index at = 0, n = 0;
    bool diagonal = true;         // C diagonal: d holds its square roots
    Eigen::VectorXd d;            // sqrt of diag C (diagonal blocks)
    Eigen::MatrixXd l;            // lower Cholesky factor (dense blocks)
  };
  std::vector<Block> blocks_;
  double log_det_ = 0.0;
  Eigen::Index size_ = 0;
};

// effective sample size under the OU correlation: sum over series of 1^T R^-1 1, R the
// series' correlation matrix: 1 + sum_i (1 - phi_i) / (1 + phi_i), phi_i =
// exp(-(x_i - x_{i-1}) / ell) with the series' rows in increasing x, without a nugget; n when
// ell = 0 (the information on a level that the correlated rows carry, in independent rows)
double effective_sample_size(const std::vector<int>& series, const std::vector<double>& x,
                             double ell, double nugget = 0.0);

// Ridge least squares of whitened residuals r on whitened columns X: beta minimises
// |r - X beta|^2 + sum_j lambda_j beta_j^2 (lambda_j = 0: free). Returns beta; `resid` =
// r - X beta. Rank-deficient free columns (a term that does not act on these rows) get 0.
Eigen::VectorXd solve_nuisance(const Eigen::VectorXd& r, const Eigen::MatrixXd& x,
                               const Eigen::VectorXd& lambda, Eigen::VectorXd* resid);

}  // namespace kneesim::diagnosis
