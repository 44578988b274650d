#include "rational_fractional_schur.hpp"

#include <Eigen/Dense>
#include <Eigen/Sparse>
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.hpp"
#include "zolotarev.hpp"

namespace stiction::solvers {
namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

SparseMatrix to_eigen(Mat m) {
  PetscInt rows, cols;
  STICTION_PETSC(MatGetSize(m, &rows, &cols));
  std::vector<Eigen::Triplet<double>> entries;
  for (PetscInt i = 0; i < rows; ++i) {
    PetscInt n;
    const PetscInt* c;
    const PetscScalar* v;
    STICTION_PETSC(MatGetRow(m, i, &n, &c, &v));
    for (PetscInt k = 0; k < n; ++k) entries.emplace_back(i, c[k], v[k]);
    STICTION_PETSC(MatRestoreRow(m, i, &n, &c, &v));
  }
  SparseMatrix out(rows, cols);
  out.setFromTriplets(entries.begin(), entries.end());
  return out;
}

// The constrained directions as the columns of T (Pi T = T, T^T T = I), as the dense model
// takes them.
SparseMatrix constrained_directions(const SparseMatrix& mass, int dim) {
  std::vector<Eigen::Triplet<double>> entries;
  Eigen::Index columns = 0;
  for (Eigen::Index node = 0; node < mass.rows(); node += dim) {
    const Eigen::MatrixXd directions = node_constrained_directions(Eigen::MatrixXd(mass.block(node, node, dim, dim)));
    for (Eigen::Index k = 0; k < directions.cols(); ++k, ++columns)
      for (int c = 0; c < dim; ++c) entries.emplace_back(node + c, columns, directions(c, k));
  }
  SparseMatrix T(mass.rows(), columns);
  T.setFromTriplets(entries.begin(), entries.end());
  return T;
}

// Ritz values of M^-1 K from a Lanczos run in the M inner product started from q, and the
// Gauss quadrature weights of the start vector on them: q^T M f(M^-1 K) q / q^T M q is
// approximately sum_i weights_i f(values_i). Fully reorthogonalised (the runs are short).
struct Ritz {
  Eigen::VectorXd values, weights;
};

Ritz lanczos(const SparseMatrix& K, const SparseMatrix& M, const Eigen::SimplicialLDLT<SparseMatrix>& M_solver,
             Eigen::VectorXd q, int steps) {
  steps = static_cast<int>(std::min<Eigen::Index>(steps, q.size()));
  std::vector<Eigen::VectorXd> basis;
  std::vector<double> alpha, beta;
  q /= std::sqrt(q.dot(M * q));
  for (int j = 0; j < steps; ++j) {
    basis.push_back(q);
    const Eigen::VectorXd Kq = K * q;
    alpha.push_back(q.dot(Kq));
    Eigen::VectorXd u = M_solver.solve(Kq);
    for (int pass = 0; pass < 2; ++pass) {  // classical Gram-Schmidt twice
      const Eigen::VectorXd Mu = M * u;
      Eigen::VectorXd projection = Eigen::VectorXd::Zero(u.size());
      for (const auto& b : basis) projection += b.dot(Mu) * b;
      u -= projection;
    }
    const double norm = std::sqrt(std::max(0.0, u.dot(M * u)));
    if (j + 1 == steps || !(norm > 1e-12 * std::abs(alpha.front()))) break;  // or an invariant subspace
    beta.push_back(norm);
    q = u / norm;
  }
  const Eigen::Index m = static_cast<Eigen::Index>(alpha.size());
  Eigen::MatrixXd tridiagonal = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index i = 0; i < m; ++i) tridiagonal(i, i) = alpha[i];
  for (Eigen::Index i = 0; i + 1 < m; ++i) tridiagonal(i, i + 1) = tridiagonal(i + 1, i) = beta[i];
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(tridiagonal);
  return {eig.eigenvalues().cwiseMax(0.0), eig.eigenvectors().row(0).transpose().array().square().matrix()};
}

// Whether a row of `rest` lies in a constrained direction (T^T rest != 0): the split of
// S~ x = b needs S0 without such rows.
bool has_constrained_row(const SparseMatrix& T, Mat rest) {
  const SparseMatrix full = to_eigen(rest);
  return SparseMatrix(T.transpose() * full).norm() > 1e-12 * std::max(1.0, full.norm());
}

}  // namespace

struct RationalFractionalCorrection::Factors {
  SparseMatrix T, M, K;
  std::vector<std::unique_ptr<Eigen::SimplicialLDLT<SparseMatrix>>> shifted;  // K + sigma_k M
  Eigen::SimplicialLDLT<SparseMatrix> M_solver;
  std::vector<double> weight;
  double constant = 0, beta = 0, C = 1, s = 1;
};

namespace {

// mu_max (the largest Ritz value of two Lanczos runs: from the probe and from a rough
// vector) and beta (fit_fractional_beta on the probe's Gauss quadrature), the dense model's
// constants; false when the spectrum is zero.
bool fit_constants(const RationalFractionalCorrection::Factors& f, const Eigen::VectorXd& probe, double s_high,
                   double s_smooth, FractionalFit& fit) {
  constexpr int kLanczosSteps = 40;
  Eigen::VectorXd rough(probe.size());
  for (Eigen::Index i = 0; i < rough.size(); ++i) rough[i] = std::sin(1.0 + 0.7 * static_cast<double>(i));
  const Ritz smooth = lanczos(f.K, f.M, f.M_solver, probe, kLanczosSteps);
  fit.mu_max = std::max(lanczos(f.K, f.M, f.M_solver, rough, kLanczosSteps).values.maxCoeff(), smooth.values.maxCoeff());
  if (!(fit.mu_max > 0)) return false;
  fit.beta = fit_fractional_beta(smooth.values, smooth.weights, fit.mu_max, s_high, s_smooth);
  return true;
}

}  // namespace

RationalFractionalCorrection::RationalFractionalCorrection() = default;
RationalFractionalCorrection::~RationalFractionalCorrection() = default;

bool RationalFractionalCorrection::setup(Mat mass, Mat stiffness, Mat D, Mat slip_coupling, int dim, double s,
                                         double s_high, double s_smooth, double tolerance, FractionalFit& fit) {
  fit = {};
  factors_.reset();
  PetscMPIInt processes;
  MPI_Comm_size(PetscObjectComm(reinterpret_cast<PetscObject>(mass)), &processes);
  if (processes > 1) throw Error("the rational fractional contact model runs on one process only");
  if (!(s_high > 0) || !(s_smooth > s_high)) return false;
  auto f = std::make_unique<Factors>();
  const SparseMatrix full_mass = to_eigen(mass);
  f->T = constrained_directions(full_mass, dim);
  fit.rows = static_cast<int>(f->T.cols());
  if (f->T.cols() < 2) return false;
  if (has_constrained_row(f->T, D) || has_constrained_row(f->T, slip_coupling)) return false;
  f->M = f->T.transpose() * full_mass * f->T;
  f->K = f->T.transpose() * to_eigen(stiffness) * f->T;
  f->M_solver.compute(f->M);
  if (f->M_solver.info() != Eigen::Success) return false;
  // The smooth probe of the body-end estimate, w_i = (M 1)_i / sum_j |M_ij| on the rows of
  // Pi M Pi, in the constrained directions.
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(full_mass.cols());
  const Eigen::VectorXd w_rows =
      ((full_mass * ones).array() / (full_mass.cwiseAbs() * ones).array().max(1e-300)).matrix();
  if (!fit_constants(*f, f->T.transpose() * w_rows, s_high, s_smooth, fit)) return false;

  // X^-1/2 over the spectrum [beta, mu_max + beta], with a margin above: the largest Ritz
  // value is a lower bound of mu_max.
  const InverseSquareRootApproximation q =
      zolotarev_inverse_square_root(fit.beta, 1.1 * fit.mu_max + fit.beta, tolerance);
  for (size_t k = 0; k < q.weight.size(); ++k) {
    const SparseMatrix shifted = f->K + (fit.beta + q.shift[k]) * f->M;
    f->shifted.push_back(std::make_unique<Eigen::SimplicialLDLT<SparseMatrix>>(shifted));
    if (f->shifted.back()->info() != Eigen::Success) return false;
  }
  f->weight = q.weight;
  f->constant = q.constant;
  f->beta = fit.beta;
  f->C = s_high * std::sqrt(fit.mu_max + fit.beta);
  f->s = s;
  fit.rational_terms = static_cast<int>(q.weight.size());
  fit.rational_error = q.error;
  fit.fitted = true;
  factors_ = std::move(f);
  return true;
}

void RationalFractionalCorrection::correct(Vec b, Vec out) const {
  const Factors& f = *factors_;
  PetscInt n;
  STICTION_PETSC(VecGetLocalSize(b, &n));
  const PetscScalar* b_array;
  STICTION_PETSC(VecGetArrayRead(b, &b_array));
  const Eigen::VectorXd r = f.T.transpose() * Eigen::Map<const Eigen::VectorXd>(b_array, n);
  STICTION_PETSC(VecRestoreArrayRead(b, &b_array));
  // a = G^-1 r = C^-1 M^-1 (K + beta M) (w_0 M^-1 + sum_k w_k (K + sigma_k M)^-1) r
  Eigen::VectorXd y = f.constant * f.M_solver.solve(r);
  for (size_t k = 0; k < f.shifted.size(); ++k) y += f.weight[k] * f.shifted[k]->solve(r);
  const Eigen::VectorXd a = f.M_solver.solve(f.K * y + f.beta * (f.M * y)) / f.C;
  const Eigen::VectorXd change = f.T * (f.s * (f.M * a) - r);
  if (out != b) STICTION_PETSC(VecCopy(b, out));
  PetscScalar* o;
  STICTION_PETSC(VecGetArray(out, &o));
  Eigen::Map<Eigen::VectorXd>(o, n) += change;
  STICTION_PETSC(VecRestoreArray(out, &o));
}

}  // namespace stiction::solvers
