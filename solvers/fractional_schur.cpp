#include "fractional_schur.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <vector>

#include "common/error.hpp"

namespace stiction::solvers {
namespace {

// The rows of the nodes (blocks of `dim` rows) with a positive diagonal entry in `mass`, every
// rank's, on each rank.
PetscIS constrained_node_rows(Mat mass, int dim) {
  PetscVec diagonal;
  STICTION_PETSC(MatCreateVecs(mass, nullptr, diagonal.out()));
  STICTION_PETSC(MatGetDiagonal(mass, diagonal));
  PetscInt first, last;
  STICTION_PETSC(VecGetOwnershipRange(diagonal, &first, &last));
  const PetscScalar* d;
  std::vector<PetscInt> rows;
  STICTION_PETSC(VecGetArrayRead(diagonal, &d));
  for (PetscInt node = first; node < last; node += dim) {
    bool constrained = false;
    for (int c = 0; c < dim; ++c) constrained = constrained || d[node + c - first] > 0;
    for (int c = 0; c < dim && constrained; ++c) rows.push_back(node + c);
  }
  STICTION_PETSC(VecRestoreArrayRead(diagonal, &d));
  PetscIS local, all;
  STICTION_PETSC(ISCreateGeneral(PetscObjectComm(reinterpret_cast<PetscObject>(mass)),
                                 static_cast<PetscInt>(rows.size()), rows.data(), PETSC_COPY_VALUES, local.out()));
  STICTION_PETSC(ISAllGather(local, all.out()));
  return all;
}

Eigen::MatrixXd dense_submatrix(Mat matrix, IS rows) {
  Mat* sub;
  STICTION_PETSC(MatCreateSubMatrices(matrix, 1, &rows, &rows, MAT_INITIAL_MATRIX, &sub));
  PetscInt n;
  STICTION_PETSC(ISGetSize(rows, &n));
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(n, n);
  for (PetscInt i = 0; i < n; ++i) {
    PetscInt ncols;
    const PetscInt* cols;
    const PetscScalar* values;
    STICTION_PETSC(MatGetRow(sub[0], i, &ncols, &cols, &values));
    for (PetscInt k = 0; k < ncols; ++k) dense(i, cols[k]) = values[k];
    STICTION_PETSC(MatRestoreRow(sub[0], i, &ncols, &cols, &values));
  }
  STICTION_PETSC(MatDestroySubMatrices(1, &sub));
  return dense;
}

// G = (M V) diag(g) (M V)^T on the rows `rows` of a matrix laid out like `like`.
PetscMat scatter_dense(Mat like, IS rows, const Eigen::MatrixXd& G) {
  PetscInt first, last, n_c;
  STICTION_PETSC(MatGetOwnershipRange(like, &first, &last));
  STICTION_PETSC(ISGetSize(rows, &n_c));
  const PetscInt* idx;
  STICTION_PETSC(ISGetIndices(rows, &idx));
  const PetscInt local_cols = static_cast<PetscInt>(
      std::count_if(idx, idx + n_c, [&](PetscInt c) { return c >= first && c < last; }));
  std::vector<PetscInt> d_nnz(last - first, 0), o_nnz(last - first, 0);
  for (PetscInt k = 0; k < n_c; ++k)
    if (idx[k] >= first && idx[k] < last) d_nnz[idx[k] - first] = local_cols, o_nnz[idx[k] - first] = n_c - local_cols;
  PetscMat out;
  STICTION_PETSC(MatCreate(PetscObjectComm(reinterpret_cast<PetscObject>(like)), out.out()));
  STICTION_PETSC(MatSetSizes(out, last - first, last - first, PETSC_DETERMINE, PETSC_DETERMINE));
  STICTION_PETSC(MatSetType(out, MATAIJ));
  STICTION_PETSC(MatSeqAIJSetPreallocation(out, 0, d_nnz.data()));
  STICTION_PETSC(MatMPIAIJSetPreallocation(out, 0, d_nnz.data(), 0, o_nnz.data()));
  std::vector<PetscScalar> row(n_c);
  for (PetscInt k = 0; k < n_c; ++k) {
    if (idx[k] < first || idx[k] >= last) continue;
    for (PetscInt l = 0; l < n_c; ++l) row[l] = G(k, l);
    STICTION_PETSC(MatSetValues(out, 1, &idx[k], n_c, idx, row.data(), INSERT_VALUES));
  }
  STICTION_PETSC(ISRestoreIndices(rows, &idx));
  STICTION_PETSC(MatAssemblyBegin(out, MAT_FINAL_ASSEMBLY));
  STICTION_PETSC(MatAssemblyEnd(out, MAT_FINAL_ASSEMBLY));
  return out;
}

// The constrained directions as columns (Pi T = T, T^T T = I), node by node.
Eigen::MatrixXd constrained_directions(const Eigen::MatrixXd& M, int dim) {
  const Eigen::Index n = M.rows();
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(n, n);
  Eigen::Index columns = 0;
  for (Eigen::Index node = 0; node < n; node += dim) {
    const Eigen::MatrixXd directions = node_constrained_directions(M.block(node, node, dim, dim));
    T.block(node, columns, dim, directions.cols()) = directions;
    columns += directions.cols();
  }
  return T.leftCols(columns);
}

}  // namespace

Eigen::MatrixXd node_constrained_directions(const Eigen::MatrixXd& block) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(block);
  const double largest = eig.eigenvalues().cwiseAbs().maxCoeff();
  Eigen::MatrixXd directions(block.rows(), 0);
  for (Eigen::Index k = 0; k < block.rows(); ++k) {
    if (!(eig.eigenvalues()[k] > 1e-10 * largest)) continue;
    directions.conservativeResize(Eigen::NoChange, directions.cols() + 1);
    directions.col(directions.cols() - 1) = eig.eigenvectors().col(k);
  }
  return directions;
}

double fit_fractional_beta(const Eigen::VectorXd& mu, const Eigen::VectorXd& weights, double mu_max, double s_high,
                           double s_smooth) {
  auto rayleigh = [&](double beta) {
    double sum = 0;
    for (Eigen::Index k = 0; k < mu.size(); ++k) sum += s_high * std::sqrt((mu_max + beta) / (mu[k] + beta)) * weights[k];
    return sum;
  };
  // rayleigh falls from (nearly) s_high sqrt(mu_max / mu_min) to s_high as beta grows.
  double lo = std::log(mu_max * 1e-12), hi = std::log(mu_max * 1e12);
  for (int it = 0; it < 200 && hi - lo > 1e-10; ++it) {
    const double mid = 0.5 * (lo + hi);
    (rayleigh(std::exp(mid)) > s_smooth ? lo : hi) = mid;
  }
  return std::exp(0.5 * (lo + hi));
}

PetscMat fractional_compliance(Mat mass, Mat stiffness, int dim, double s_high, double s_smooth, int max_rows,
                               FractionalFit& fit) {
  fit = {};
  if (!mass || !stiffness || !(s_high > 0) || !(s_smooth > s_high)) return {};
  PetscIS rows = constrained_node_rows(mass, dim);
  PetscInt n_rows;
  STICTION_PETSC(ISGetSize(rows, &n_rows));
  if (n_rows > max_rows) {
    fit.rows = static_cast<int>(n_rows);
    return {};
  }
  const Eigen::MatrixXd M_rows = dense_submatrix(mass, rows);
  const Eigen::MatrixXd T = constrained_directions(M_rows, dim);
  fit.rows = static_cast<int>(T.cols());
  if (T.cols() < 2) return {};
  const Eigen::MatrixXd M = T.transpose() * M_rows * T, K = T.transpose() * dense_submatrix(stiffness, rows) * T;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> eig(K, M);  // K V = M V mu, V^T M V = I
  if (eig.info() != Eigen::Success) return {};
  const Eigen::VectorXd mu = eig.eigenvalues().cwiseMax(0.0);
  fit.mu_max = mu.maxCoeff();
  if (!(fit.mu_max > 0)) return {};
  const Eigen::MatrixXd MV = M * eig.eigenvectors();
  // The smooth probe of the body-end estimate, w_i = (M 1)_i / sum_j |M_ij| on the rows,
  // in the constrained directions.
  const Eigen::VectorXd w_rows =
      (M_rows.rowwise().sum().array() / M_rows.cwiseAbs().rowwise().sum().cwiseMax(1e-300).array()).matrix();
  const Eigen::VectorXd w = T.transpose() * w_rows;
  const Eigen::VectorXd c = MV.transpose() * w;  // w = V c
  fit.beta = fit_fractional_beta(mu, (c.array().square() / w.dot(M * w)).matrix(), fit.mu_max, s_high, s_smooth);
  auto g = [&](double m, double beta) { return s_high * std::sqrt((fit.mu_max + beta) / (m + beta)); };
  Eigen::VectorXd gk(mu.size());
  for (Eigen::Index k = 0; k < mu.size(); ++k) gk[k] = g(mu[k], fit.beta);
  const Eigen::MatrixXd TMV = T * MV;
  const Eigen::MatrixXd G = TMV * gk.asDiagonal() * TMV.transpose();
  fit.fitted = true;
  return scatter_dense(mass, rows, G);
}

}  // namespace stiction::solvers
