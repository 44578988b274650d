#pragma once
// The constraint row c_i of one slave node in the global system (30), shared by every
// master (rigid plane, deformable surface). A node is described by
//   n       its unit contact normal, pointing from the master towards the slave
//   G       its vector weighted gap  int phi_i (x1 - x2)            (normal gap gn = n . G)
//   S       its weighted slip increment against the previous load step (15)-(16)
//   lambda  its multiplier (the traction on the slave; lambda_n = n . lambda >= 0 presses)
// and the row by state:
//   inactive  c = lambda                                                  (R_SC lambda = 0)
//   stick     c = n (n . G) + I_t S                                       (R_A: no slip)
//   slip      c = n (n . G) + lambda_t - mu lambda_n a / |a|,  a = lambda_t - r_t I_t S   (19)
// with I_t = I - n n^T and lambda_t = I_t lambda.
//
// Sign of the augmentation (choice): (19) as printed, lambda_t = -mu lambda_n a/|a| with
// a = lambda_t + r_t gt, is consistent only while r_t |gt| > mu lambda_n (otherwise it asks
// lambda_t to point against itself). Written as the projection of lambda_t - r_t gt on the
// Coulomb disc (Alart & Curnier), the slip row is consistent for every r_t > 0, and r_t only
// steers the Newton path (adapted as in Sec. 4.3).
//
// Linearisation: the paper's (23) is garbled and drops the variation of the normal. Here
// the partial derivatives of c with respect to n, G, S and lambda are exact (forward-mode
// automatic differentiation of the expressions above); the caller chains them with the
// derivatives of n, G and S with respect to the displacement. For a plane (dn = 0) the
// slip blocks reduce to the paper's terms: d c = n n^T dG + r_t K I_t dS +
// (I_t - mu a^ n^T - K I_t) d lambda with K = mu lambda_n (I - a^ a^T)/|a|, i.e. its
// diagonal I_t, elongation E^C (by d lambda_n) and angular correction I^perp_t B_t.
#include <Eigen/Dense>

#include "contact/contact_state.hpp"

namespace stiction::contact {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

struct NodeRow {
  Vec3 c = Vec3::Zero();
  Mat3 d_normal = Mat3::Zero(), d_gap = Mat3::Zero(), d_slip = Mat3::Zero(), d_lambda = Mat3::Zero();
};

NodeRow node_row(NodeState state, const Vec3& n, const Vec3& G, const Vec3& S, const Vec3& lambda, double mu,
                 double r_t);

// The row of a node in state s, normal n, with its traction rows (released: lambda = 0;
// slipping: the tangential part, c - n (n . c)) multiplied by the lumped mass m, chained
// exactly: c' = Q c, Q = m I + (1 - m) n n^T, so dc'/dn picks up (1 - m)((n . c) I + n c^T).
NodeRow weighted_by_mass(NodeRow row, NodeState s, const Vec3& n, double m);

// The quantities the state machine (Sec. 4.5) tests at node i.
NodeQuantities node_quantities(const Vec3& n, const Vec3& G, const Vec3& S, const Vec3& lambda);

}  // namespace stiction::contact
