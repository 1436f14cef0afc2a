// The right-hand side of the chain: joint accelerations and every joint's tension in O(nu). Derived in
// docs/solver.md, whose equation numbers (S1) ... (S23) and symbols the code cites (its §6 maps them to the
// code's names); §11 the cable sections and point bodies.
//
// Three passes (pinocchio's aba.hxx reads the same way):
//   elementTerms   each element's Newton-Euler equations projected onto its two joints (S1)-(S6);
//   backward sweep from the end body to the ship, each joint's tension as an affine function of its own
//                  acceleration, T = Lambda a + tau (Lambda the apparent inertia, Factor::K in the code), and
//                  the acceleration transfer a_aft = Phi a_fwd + phi
//                  (S7)-(S13): the report's summation of the linear-momentum equations, done recursively.
//                  It is split in two: the matrix pass (Lambda, Phi: the inertia and the axes only) and the
//                  vector pass (tau, phi: the loads), so that the implicit stepper factors its stage
//                  matrix once per step and solves each stage with a vector pass (docs/solver.md §7);
//   forward sweep  from the ship's known acceleration, every acceleration and tension (S14).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tow_sim/core/chain/chain_model.h"

namespace tow_sim
{
// One element's equations on its joints (docs/solver.md §2): M_ff a_f + M_fa a_a - w_f = T_fwd - mu s (S3),
// M_af a_f + M_aa a_a - w_a = -T_aft + mu s (S4), s.(a_a - a_f) = Psi (S6); h_f, h_a here are w_f, w_a of (S5),
// c is Psi. The implicit stepper's stage equations have the same form (M_XY -> N_XY, w_X -> w~_X, Psi -> Psi~:
// (S18)-(S19), docs/solver.md §7).
struct ElementTerms
{
  Eigen::Matrix3d M_ff, M_fa, M_af, M_aa;  // projected inertia (S5) [kg]
  Eigen::Vector3d h_f, h_a;                // projected loads w_f, w_a (S5) [N]
  Eigen::Vector3d s;                       // the element's axis
  double c = 0.0;                          // [m/s^2] right-hand side Psi of the length constraint (S6)
  // An elastic segment has no length constraint: its axial force is a load, already in w_f, w_a ((S20'),
  // docs/solver.md §8), and mu = -tension is known.
  bool constrained = true;
  double tension = 0.0;  // [N] the elastic segment's axial tension (unconstrained only)
};

// The backward and forward sweeps over a chain of element equations whose end body's tail is free
// (T = 0 aft of it): (S7)-(S14), and for unconstrained (elastic) elements (S20)-(S21).
class ChainSweep
{
public:
  // The matrix pass: everything that depends on the blocks M_XY and the axes s only (S8)-(S13).
  void factor(const std::vector<ElementTerms>& terms);
  // The vector pass for the loads w_X and constraints Psi of `terms` (the blocks factor() was given), then the
  // forward sweep from the first joint's acceleration a_first: every acceleration (3 x elements) and, when
  // not null, the tension at each element's forward joint and the axial multiplier mu (compression positive).
  void solve(const std::vector<ElementTerms>& terms, const Eigen::Vector3d& a_first, Eigen::Ref<Eigen::Matrix3Xd> a,
             Eigen::Matrix3Xd* tensions = nullptr, std::vector<double>* multipliers = nullptr);
  // The same for a free first joint (the end of a parted cable): T = Lambda a + tau = F there, F the force on
  // it from outside (the seabed's; 0: nothing pulls on it), gives its acceleration (S22), returned; then
  // the forward sweep from it (its tension is F).
  Eigen::Vector3d solveFree(const std::vector<ElementTerms>& terms, Eigen::Ref<Eigen::Matrix3Xd> a,
                            Eigen::Matrix3Xd* tensions = nullptr, std::vector<double>* multipliers = nullptr,
                            const Eigen::Vector3d& first_force = Eigen::Vector3d::Zero());

private:
  void loads(const std::vector<ElementTerms>& terms);  // the vector pass (S9)-(S13)
  void forward(const std::vector<ElementTerms>& terms, const Eigen::Vector3d& a_first, Eigen::Ref<Eigen::Matrix3Xd> a,
               Eigen::Matrix3Xd* tensions, std::vector<double>* multipliers);  // (S14)

  struct Factor
  {
    Eigen::Matrix3d A_inv;            // the aft joint's regularised inertia, inverted (S9)
    Eigen::Matrix3d Phi;              // a_aft = Phi a_fwd + phi (S12)
    Eigen::Matrix3d K;                // Lambda of T_fwd = Lambda a_fwd + tau (S13): the apparent inertia
    Eigen::Vector3d b, b_t, xi;       // A'^-1 s, A'^-T s (S9)-(S10); xi (S11)
    double sigma = 0.0, kappa = 0.0;  // s^T A'^-1 s (S10); the shift kappa of A' = A + kappa s s^T (S9)
  };
  std::vector<Factor> factors_;
  std::vector<Eigen::Vector3d> phi_, tau_;  // phi (S12), tau (S13)
  std::vector<double> eta_;                 // eta (S11)
};

class ChainSolver
{
public:
  // t: time [s]; x, v: joints x_2 .. x_{nu+2} (3 x (nu+1)), world, for the chain's geometry and data at
  // that instant. Writes their accelerations into a and, when not null, T_1 .. T_{nu+1} (3 x (nu+1)): the
  // force on element lambda at its forward joint, i.e. the pull toward the ship (T_1 is the tow force the
  // ship applies), and each element's axial multiplier mu [N] (compression positive: the element's
  // tension is -mu). Only the solver's own workspace changes.
  void solve(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
             const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
             const Eigen::Ref<const Eigen::Matrix3Xd>& v, Eigen::Ref<Eigen::Matrix3Xd> a,
             Eigen::Matrix3Xd* tensions = nullptr, std::vector<double>* multipliers = nullptr);

  // A chain whose first joint is free instead of following the ship (the vehicle side of a parted cable, its
  // geometry's segments those aft of the break, 0 for the end body alone): `first` holds that joint's
  // position and velocity (its acceleration is ignored); x, v, a, tensions and multipliers as solve() for
  // the joints aft of it. Returns the first joint's acceleration (S22); T_1 = first_force, the force on
  // the first joint from outside (the seabed's; zero: nothing pulls on it).
  Eigen::Vector3d solveFree(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                            const ShipEndState& first, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                            const Eigen::Ref<const Eigen::Matrix3Xd>& v, Eigen::Ref<Eigen::Matrix3Xd> a,
                            Eigen::Matrix3Xd* tensions = nullptr, std::vector<double>* multipliers = nullptr,
                            const Eigen::Vector3d& first_force = Eigen::Vector3d::Zero());
  // The element equations of the last solve (the implicit stepper linearises around them).
  const std::vector<ElementTerms>& terms() const { return terms_; }
  // A rolling end body's roll angle [rad] and spin [rad/s] for the solves that follow (ElementKinematics::roll,
  // roll_rate; zero until set). Only a geometry with ChainGeometry::rollingEnd() uses them.
  void setEndRoll(const Eigen::Vector2d& roll) { end_roll_ = roll; }

private:
  void elementTerms(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                    const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                    const Eigen::Ref<const Eigen::Matrix3Xd>& v);

  std::vector<ElementTerms> terms_;  // workspace, one entry per element
  ChainSweep sweep_;
  Eigen::Vector2d end_roll_ = Eigen::Vector2d::Zero();
};

}  // namespace tow_sim
