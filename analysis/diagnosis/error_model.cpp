#include "analysis/diagnosis/error_model.h"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "analysis/diagnosis/text_format.h"
#include "engine/errors.h"

namespace kneesim::diagnosis {

const std::vector<std::string>& error_model_names() {
  static const std::vector<std::string> names = {"white", "correlated", "instrument"};
  return names;
}

ErrorModel select_error_model(const ErrorModel& full, const std::string& name,
                              const std::map<std::string, double>& params,
                              const std::string& case_name) {
  const auto& names = error_model_names();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    throw InputError("command line: --noise-model '" + name + "' does not exist; allowed: "
                     "white, correlated, instrument.");
  }
  ErrorModel m = full;
  m.name = name;
  if (name == "white") {
    m.correlation = Correlation::none;
    m.specimen_offset = false;
    m.nuisance.clear();
  } else if (name == "correlated") {
    m.nuisance.clear();
  }
  for (const auto& [key, value] : params) {
    std::string allowed = "ou, specimen_offset";
    bool known = false;
    if (key == "ou" || key == "specimen_offset") {
      if (value != 0.0 && value != 1.0) {
        throw InputError("command line: --noise-param " + key + " = " + fmt("%g", value) +
                         " is not allowed; use 0 (off) or 1 (on).");
      }
      if (key == "ou") m.correlation = value != 0.0 ? Correlation::ou : Correlation::none;
      if (key == "specimen_offset") m.specimen_offset = value != 0.0;
      known = true;
    }
    for (const auto& t : full.nuisance) {
      if (t.prior_key.empty()) continue;
      if (allowed.find(t.prior_key) == std::string::npos) allowed += ", " + t.prior_key;
      if (key != t.prior_key) continue;
      known = true;
      if (!(value >= 0.0 && value <= 1e6)) {
        throw InputError("command line: --noise-param " + key + " = " + fmt("%g", value) +
                         " is outside the allowed range [0, 1e6] (0: a free term).");
      }
      for (auto& own : m.nuisance) {
        if (own.prior_key == key) own.prior_sd = value * own.prior_scale;
      }
    }
    if (!known) {
      throw InputError("command line: --noise-param '" + key + "' is not a key of the " +
                       case_name + " error model; allowed: " + allowed + ".");
    }
  }
  return m;
}

Whitener::Whitener(const std::vector<std::vector<int>>& clusters, const CovarianceRows& rows,
                   const CovarianceParams& p) {
  const Eigen::VectorXd& w = *rows.w;
  Eigen::Index at = 0;
  for (const auto& cl : clusters) {
    Block b;
    b.at = at;
    b.n = static_cast<Eigen::Index>(cl.size());
    at += b.n;
    Eigen::VectorXd g = Eigen::VectorXd::Zero(b.n), h = Eigen::VectorXd::Zero(b.n);
    for (Eigen::Index i = 0; i < b.n; ++i) {
      const int r = cl[static_cast<size_t>(i)];
      if (rows.dg && p.rho > 0.0) g[i] = (*rows.dg)[r] * w[r];
      if (rows.offset && p.rho_offset > 0.0 && (*rows.offset)[static_cast<size_t>(r)]) h[i] = w[r];
    }
    bool correlated = false;
    if (p.ell > 0.0 && rows.series && b.n > 1) {
      for (Eigen::Index i = 0; i < b.n && !correlated; ++i) {
        for (Eigen::Index j = i + 1; j < b.n && !correlated; ++j) {
          correlated = (*rows.series)[static_cast<size_t>(cl[static_cast<size_t>(i)])] ==
                       (*rows.series)[static_cast<size_t>(cl[static_cast<size_t>(j)])];
        }
      }
    }
    const bool rank_one = (b.n > 1) && (g.squaredNorm() > 0.0 || h.squaredNorm() > 0.0);
    b.diagonal = !correlated && !rank_one;
    if (b.diagonal) {
      b.d.resize(b.n);
      for (Eigen::Index i = 0; i < b.n; ++i) {
        b.d[i] = std::sqrt(1.0 + p.rho * g[i] * g[i] + p.rho_offset * h[i] * h[i]);
        log_det_ += 2.0 * std::log(b.d[i]);
      }
    } else {
      Eigen::MatrixXd c = p.rho * g * g.transpose() + p.rho_offset * h * h.transpose();
      for (Eigen::Index i = 0; i < b.n; ++i) {
        c(i, i) += 1.0;
        if (!correlated) continue;
        const int ri = cl[static_cast<size_t>(i)];
        for (Eigen::Index j = 0; j < i; ++j) {
          const int rj = cl[static_cast<size_t>(j)];
          if ((*rows.series)[static_cast<size_t>(ri)] != (*rows.series)[static_cast<size_t>(rj)]) {
            continue;
          }
          const double a = (1.0 - p.nugget) *
                           std::exp(-std::abs((*rows.x)[static_cast<size_t>(ri)] -
                                              (*rows.x)[static_cast<size_t>(rj)]) / p.ell);
          c(i, j) += a;
          c(j, i) += a;
        }
      }
      Eigen::LLT<Eigen::MatrixXd> llt(c);
      b.l = llt.matrixL();
      for (Eigen::Index i = 0; i < b.n; ++i) log_det_ += 2.0 * std::log(b.l(i, i));
    }
    blocks_.push_back(std::move(b));
  }
  size_ = at;
}

Eigen::VectorXd Whitener::whiten(const Eigen::VectorXd& z) const {
  Eigen::VectorXd out(z.size());
  for (const Block& b : blocks_) {
    if (b.diagonal) {
      out.segment(b.at, b.n) = z.segment(b.at, b.n).cwiseQuotient(b.d);
    } else {
      out.segment(b.at, b.n) = b.l.triangularView<Eigen::Lower>().solve(z.segment(b.at, b.n));
    }
  }
  return out;
}

Eigen::MatrixXd Whitener::whiten(const Eigen::MatrixXd& m) const {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (const Block& b : blocks_) {
    if (b.diagonal) {
      out.middleRows(b.at, b.n) = b.d.cwiseInverse().asDiagonal() * m.middleRows(b.at, b.n);
    } else {
      out.middleRows(b.at, b.n) =
          b.l.triangularView<Eigen::Lower>().solve(m.middleRows(b.at, b.n));
    }
  }
  return out;
}

Eigen::VectorXd Whitener::color(const Eigen::VectorXd& xi) const {
  Eigen::VectorXd out(xi.size());
  for (const Block& b : blocks_) {
    if (b.diagonal) {
      out.segment(b.at, b.n) = xi.segment(b.at, b.n).cwiseProduct(b.d);
    } else {
      out.segment(b.at, b.n) = b.l.triangularView<Eigen::Lower>() * xi.segment(b.at, b.n);
    }
  }
  return out;
}

double effective_sample_size(const std::vector<int>& series, const std::vector<double>& x,
                             double ell, double nugget) {
  if (!(ell > 0.0)) return static_cast<double>(series.size());
  std::map<int, std::vector<double>> by_series;
  for (size_t i = 0; i < series.size(); ++i) by_series[series[i]].push_back(x[i]);
  double n = 0.0;
  for (auto& [s, xs] : by_series) {
    std::sort(xs.begin(), xs.end());
    if (nugget <= 0.0) {
      n += 1.0;
      for (size_t i = 1; i < xs.size(); ++i) {
        const double phi = std::exp(-(xs[i] - xs[i - 1]) / ell);
        n += (1.0 - phi) / (1.0 + phi);
      }
      continue;
    }
    // 1^T R^-1 1 with R = (1 - nugget) A + nugget I
    const auto m = static_cast<Eigen::Index>(xs.size());
    Eigen::MatrixXd r(m, m);
    for (Eigen::Index i = 0; i < m; ++i) {
      r(i, i) = 1.0;
      for (Eigen::Index j = 0; j < i; ++j) {
        r(i, j) = r(j, i) = (1.0 - nugget) * std::exp(-(xs[static_cast<size_t>(i)] - xs[static_cast<size_t>(j)]) / ell);
      }
    }
    n += Eigen::LLT<Eigen::MatrixXd>(r).matrixL().solve(Eigen::VectorXd::Ones(m)).squaredNorm();
  }
  return n;
}

Eigen::VectorXd solve_nuisance(const Eigen::VectorXd& r, const Eigen::MatrixXd& x,
                               const Eigen::VectorXd& lambda, Eigen::VectorXd* resid) {
  const Eigen::Index m = x.cols();
  if (m == 0) {
    if (resid) *resid = r;
    return Eigen::VectorXd();
  }
  // augmented least squares [X; diag(sqrt(lambda))] beta = [r; 0]; the complete orthogonal
  // decomposition gives the minimum-norm solution when free columns are collinear or zero
  Eigen::MatrixXd a(x.rows() + m, m);
  a.topRows(x.rows()) = x;
  a.bottomRows(m) = lambda.cwiseMax(0.0).cwiseSqrt().asDiagonal();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(x.rows() + m);
  rhs.head(r.size()) = r;
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(a);
  cod.setThreshold(1e-10);
  Eigen::VectorXd beta = cod.solve(rhs);
  if (!beta.allFinite()) beta.setZero();
  if (resid) *resid = r - x * beta;
  return beta;
}

}  // namespace kneesim::diagnosis
