#pragma once
// Manufactured linear-elasticity problems solved through the real Newton driver and the
// lu-mumps backend, for convergence and basis-equivalence tests.
//
// u_i(X) = a_i prod_k sin(pi (X_k + s_k)) on the unit square/cube, Dirichlet data u on the
// whole boundary, body force f = -div sigma(u) = mu d pi^2 a phi - (lambda + mu) grad(div u).
#include <memory>
#include <vector>

#include "fem/field_space.hpp"
#include "fem/error_norms.hpp"
#include "mesh/mesh.hpp"
#include "nonlinear/problem.hpp"

namespace stiction::test {

struct ManufacturedSolution {
  int dim;
  double lambda, mu;
  void value(const double* X, double* u) const;
  void gradient(const double* X, double* g) const;  // g[i*dim+J] = du_i/dX_J
  void body_force(const double* X, double* f) const;
};

ManufacturedSolution manufactured(int dim);  // E = 1, nu = 0.3

struct SolvedProblem {
  mesh::Mesh mesh;
  std::unique_ptr<fem::FieldSpace> space;
  std::vector<double> u;
  fem::ErrorNorms errors;
};

// The displacement of a (linear) problem after one load step with lu-mumps, Newton to a
// relative 1e-10 in at most 3 iterations; a failure to converge is a test failure.
std::vector<double> solve_in_one_step(const nonlinear::ElasticityProblem& problem);

// Structured unit box with `n` cells per side, refined `level` times, solved with `kind`.
SolvedProblem solve_manufactured(int dim, int n, int level, fem::BasisKind kind);

}  // namespace stiction::test
