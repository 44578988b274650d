// Hertz contact in plane strain: an elastic cylinder of radius R on a rigid frictionless
// plane (built-in scene hertz-cylinder-2d) and two identical cylinders, both deformable
// (hertz-cylinders-2d), and their 3D counterparts. Hertz's half-width a and peak pressure
// p0 for the computed force (reference/hertz: formulas, Johnson's Contact Mechanics, and
// each scene's R*, E* and symmetry factor). The computed pressure is |lambda| at
// the slave nodes (frictionless: lambda = lambda_n n); the test reads a and p0 off the computed profile and compares them with the values
// Hertz gives for the computed force, so the load need not be known in advance.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>

#include "contact/contact_pair.hpp"
#include "analytic_reference.hpp"
#include "support/solve_scene.hpp"

namespace stiction::test {
namespace {

struct HertzFigures {
  double a_hertz = 0, p0_hertz = 0;
  double p0 = 0;                  // lambda_n at the contact point (x = 0)
  double last_active = 0;         // x of the outermost node in contact
  double first_inactive = 0;      // x of the nearest node out of contact beyond it
  double a_fit = 0;               // from p^2 = p0^2 (1 - x^2 / a^2) fitted by least squares
  double p0_fit = 0;              // p0 of that fit
};

// A Hertz scene (its case: reference/hertz) and the backend that solves it.
struct HertzCase {
  const char* scene;
  const char* backend = "lu-mumps";
};
const HertzCase kCylinderOnPlane{"hertz-cylinder-2d"};
const HertzCase kTwoCylinders{"hertz-cylinders-2d"};
const HertzCase kSphereOnPlane{"hertz-sphere-3d", "schur-amg"};
const HertzCase kTwoSpheres{"hertz-spheres-3d", "schur-amg"};

HertzFigures hertz_figures(const HertzCase& c, int level) {
  const auto hertz = harness::hertz_case(c.scene);
  EXPECT_TRUE(hertz.has_value()) << c.scene << " is not in reference/hertz/hertz-cases.csv";
  if (!hertz) return {};
  const SolvedScene s = solve_builtin(c.scene, level, c.backend);
  EXPECT_TRUE(s.converged());
  const auto& pair = dynamic_cast<const contact::ContactPair&>(*s.scene->contacts.at(0));
  const int d = hertz->dim;
  // Distance of a slave node from the axis of symmetry (x in 2D, hypot(x, z) in 3D).
  auto radius = [&](int i) {
    const auto& X = pair.slave().reference_position[i];
    return d == 2 ? X[0] : std::hypot(X[0], X[2]);
  };
  HertzFigures h;
  h.first_inactive = 1e9;
  std::vector<std::pair<double, double>> in_contact;
  for (int i = 0; i < pair.slave().n_nodes(); ++i) {
    double p2 = 0;
    for (int k = 0; k < d; ++k) p2 += s.lambda[d * i + k] * s.lambda[d * i + k];
    const double x = radius(i), p = std::sqrt(p2);
    if (pair.state(i) == contact::NodeState::Inactive) continue;
    h.last_active = std::max(h.last_active, x);
    if (x < 1e-12) h.p0 = p;
    in_contact.emplace_back(x, p);
  }
  for (int i = 0; i < pair.slave().n_nodes(); ++i)
    if (pair.state(i) == contact::NodeState::Inactive && radius(i) > h.last_active)
      h.first_inactive = std::min(h.first_inactive, radius(i));
  const double force = s.steps.back().contact.at(0).force[1];
  const harness::HertzComparison fit = harness::compare_with_hertz(*hertz, force, in_contact);
  h.a_fit = fit.a_fit, h.p0_fit = fit.p0_fit;
  // Hertz's figures for the computed force written out here, not taken from the harness
  // (the formulas of reference/hertz/README.md, from Johnson's Contact Mechanics; R*, E* and
  // the symmetry factor from reference/hertz/hertz-cases.csv); the harness must agree.
  const double P = hertz->force_factor * std::abs(force);
  if (d == 2) {
    h.a_hertz = std::sqrt(4 * P * hertz->R_star / (M_PI * hertz->E_star));
    h.p0_hertz = 2 * P / (M_PI * h.a_hertz);
  } else {
    h.a_hertz = std::cbrt(3 * P * hertz->R_star / (4 * hertz->E_star));
    h.p0_hertz = 3 * P / (2 * M_PI * h.a_hertz * h.a_hertz);
  }
  EXPECT_NEAR(fit.a_hertz, h.a_hertz, 1e-12 * h.a_hertz);
  EXPECT_NEAR(fit.p0_hertz, h.p0_hertz, 1e-12 * h.p0_hertz);
  return h;
}

// Relative agreement with Hertz below which a level counts as converged (check_hertz).
constexpr double kHertzFloor = 3e-3;

// Which peak pressure the refinement trend is asserted on: the multiplier at the node on the
// axis, or p0 of the least-squares fit over every node in contact.
enum class PeakEstimate { AxisNode, Fit };

void check_hertz(const HertzCase& c, int finest, PeakEstimate trend_on = PeakEstimate::AxisNode) {
  std::vector<HertzFigures> levels;
  for (int level = 0; level <= finest; ++level) {
    levels.push_back(hertz_figures(c, level));
    const auto& h = levels.back();
    std::printf("%s level %d: a Hertz %.5f, fit %.5f, bracket [%.5f, %.5f]; p0 Hertz %.5e, node %.5e, fit %.5e\n",
                c.scene, level, h.a_hertz, h.a_fit, h.last_active, h.first_inactive, h.p0_hertz, h.p0, h.p0_fit);
  }
  const auto& fine = levels.back();
  // The edge of the contact zone lies between the last node in contact and the next one.
  EXPECT_LE(fine.last_active, fine.a_hertz * 1.02);
  EXPECT_GE(fine.first_inactive, fine.a_hertz * 0.98);
  EXPECT_NEAR(fine.a_fit / fine.a_hertz, 1.0, 0.02);
  EXPECT_NEAR(fine.p0 / fine.p0_hertz, 1.0, 0.02);
  EXPECT_NEAR(fine.p0_fit / fine.p0_hertz, 1.0, 0.02);
  // Converging under refinement: the finest level is closer to Hertz than the coarsest; or,
  // where the coarsest already agrees with it within kHertzFloor (the agreement Hertz's
  // small-strain half-space theory can give for these finite bodies and loads), every level
  // stays within that floor. With curved P2 cells the 2D cylinders are in the second case
  // from level 0 (errors of a_fit and of p0 at the axis node near 0.1-0.2% at every level).
  auto err_p0 = [&](const HertzFigures& h) {
    return std::abs((trend_on == PeakEstimate::AxisNode ? h.p0 : h.p0_fit) / h.p0_hertz - 1);
  };
  auto err_a = [](const HertzFigures& h) { return std::abs(h.a_fit / h.a_hertz - 1); };
  using Deviation = std::function<double(const HertzFigures&)>;
  for (const Deviation& err : {Deviation(err_p0), Deviation(err_a)}) {
    if (err(levels.front()) >= kHertzFloor) {
      EXPECT_LT(err(fine), err(levels.front())) << "not converging: " << err(levels.front()) << " -> " << err(fine);
      continue;
    }
    for (size_t level = 0; level < levels.size(); ++level)
      EXPECT_LT(err(levels[level]), kHertzFloor) << "level " << level;
  }
}

TEST(Hertz2D, CylinderOnRigidPlaneConvergesToHertz) { check_hertz(kCylinderOnPlane, 2); }

TEST(Hertz2D, TwoDeformableCylindersConvergeToHertz) { check_hertz(kTwoCylinders, 2); }

// 3D, levels 0-2 (170 000 unknowns at level 2, solved with schur-amg: LU takes minutes
// there). Measured: a_fit error 0.36% / 1.25% / 0.32%, p0 of the fit 1.64% / 0.21% / 0.27%,
// p0 at the pole node 2.74% / 0.01% / 0.23%. The pole node's multiplier is one value of a P1
// field on a graded unstructured mesh and moves with the local mesh, so the trend is asserted
// on the fit (every node in contact) and the node is held to 2% only.
TEST(Hertz3D, SphereOnRigidPlaneConvergesToHertz) { check_hertz(kSphereOnPlane, 2, PeakEstimate::Fit); }

// Two deformable spheres (surface_contact.hpp: the upper sphere's normals crossing the lower
// sphere's P2 triangles), levels 0-2 (340 000 unknowns at level 2, schur-amg, the traction
// rows weighted by the lumped mass as the scene sets it).
// Measured: a_fit error 0.35% / 1.30% / 0.32%, p0 of the fit 1.65% / 0.22% / 0.27%, p0 at
// the pole node 2.96% / 0.03% / 0.21%; the trend is asserted on the fit as on the plane.
TEST(Hertz3D, TwoDeformableSpheresConvergeToHertz) { check_hertz(kTwoSpheres, 2, PeakEstimate::Fit); }

}  // namespace
}  // namespace stiction::test
