#include "support/manufactured.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "materials/material.hpp"
#include "nonlinear/newton.hpp"
#include "registry.hpp"

namespace stiction::test {

namespace {
constexpr double amplitude[3] = {1.0, 0.5, -0.7};
constexpr double shift[3] = {0.3, 0.2, 0.1};  // non-zero boundary data

double sine(const double* X, int k) { return std::sin(M_PI * (X[k] + shift[k])); }
double cosine(const double* X, int k) { return std::cos(M_PI * (X[k] + shift[k])); }

// d^2 phi / dX_i dX_j for phi = prod_k sin(pi (X_k + s_k)).
double phi_hessian(int dim, const double* X, int i, int j) {
  double p = M_PI * M_PI * (i == j ? -1.0 : 1.0);
  for (int k = 0; k < dim; ++k) {
    if (k == i || k == j) p *= (i == j) ? sine(X, k) : cosine(X, k);
    else p *= sine(X, k);
  }
  return p;
}
}  // namespace

ManufacturedSolution manufactured(int dim) {
  double lambda, mu;
  materials::lame_parameters(1.0, 0.3, lambda, mu);
  return {dim, lambda, mu};
}

void ManufacturedSolution::value(const double* X, double* u) const {
  double phi = 1;
  for (int k = 0; k < dim; ++k) phi *= sine(X, k);
  for (int i = 0; i < dim; ++i) u[i] = amplitude[i] * phi;
}

void ManufacturedSolution::gradient(const double* X, double* g) const {
  for (int J = 0; J < dim; ++J) {
    double d = M_PI;
    for (int k = 0; k < dim; ++k) d *= (k == J) ? cosine(X, k) : sine(X, k);
    for (int i = 0; i < dim; ++i) g[i * dim + J] = amplitude[i] * d;
  }
}

void ManufacturedSolution::body_force(const double* X, double* f) const {
  for (int i = 0; i < dim; ++i) {
    double grad_div = 0;
    for (int j = 0; j < dim; ++j) grad_div += amplitude[j] * phi_hessian(dim, X, i, j);
    // -mu Laplacian(u_i) = -mu a_i sum_k phi_kk, and phi_kk = phi_hessian(k, k).
    double lap = 0;
    for (int k = 0; k < dim; ++k) lap += phi_hessian(dim, X, k, k);
    f[i] = -mu * amplitude[i] * lap - (lambda + mu) * grad_div;
  }
}

std::vector<double> solve_in_one_step(const nonlinear::ElasticityProblem& problem) {
  nonlinear::NewtonSettings settings;
  settings.atol = 0;
  settings.rtol = 1e-10;
  settings.max_iterations = 3;
  auto solver = solvers::create_solver("lu-mumps", PETSC_COMM_WORLD);
  nonlinear::QuasiStaticSolver newton(PETSC_COMM_WORLD, problem, settings, *solver);
  const auto result = newton.solve_step(1);
  EXPECT_TRUE(result.converged()) << nonlinear::to_string(result.reason) << " " << result.detail;
  return newton.displacement();
}

SolvedProblem solve_manufactured(int dim, int n, int level, fem::BasisKind kind) {
  const ManufacturedSolution ms = manufactured(dim);
  SolvedProblem out;
  out.mesh = mesh::refine(mesh::structured_box(dim, {1, 1, 1}, {n, n, n}), level);
  out.space = std::make_unique<fem::FieldSpace>(out.mesh, kind);
  materials::LinearElastic law(1.0, 0.3);
  nonlinear::ElasticityProblem p;
  p.space = out.space.get();
  p.cell_material.assign(out.mesh.n_cells(), &law);
  for (int tag = 1; tag <= 2 * dim; ++tag) {
    nonlinear::DirichletCondition bc;
    bc.name = "side" + std::to_string(tag);
    bc.facet_tag = tag;
    for (int c = 0; c < dim; ++c) bc.components.push_back(c);
    bc.value = [&ms](const double* X, double, double* u) { ms.value(X, u); };
    p.dirichlet.push_back(bc);
  }
  p.body_force = [&ms](const double* X, int, double* f) { ms.body_force(X, f); };
  out.u = solve_in_one_step(p);
  out.errors = fem::compute_errors(
      *out.space, out.u, [&](const double* X, double* u) { ms.value(X, u); },
      [&](const double* X, double* g) { ms.gradient(X, g); }, 6);
  return out;
}

}  // namespace stiction::test
