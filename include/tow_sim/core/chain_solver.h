// The right-hand side of the chain: joint accelerations and every joint's tension in O(nu). Derived in
// docs/solver.md, whose equation numbers (S1) ... (S14) the code cites.
//
// Three passes (pinocchio's aba.hxx reads the same way):
//   elementTerms   each element's Newton-Euler equations projected onto its two joints (S1)-(S6);
//   backwardSweep  from the end body to the ship, each joint's tension as an affine function of its own
//                  acceleration, T = K a + tau, and the acceleration transfer a_aft = Phi a_fwd + phi
//                  (S7)-(S13): the report's summation of the linear-momentum equations, done recursively;
//   forwardSweep   from the ship's known acceleration, every acceleration and tension (S14).
#pragma once

#include <Eigen/Core>
#include <vector>

#include "tow_sim/core/chain_model.h"

namespace tow_sim
{
// One element's equations on its joints (docs/solver.md §2): M_ff a_f + M_fa a_a - h_f = T_fwd - mu s,
// M_af a_f + M_aa a_a - h_a = -T_aft + mu s, s.(a_a - a_f) = c.
struct ElementTerms
{
  Eigen::Matrix3d M_ff, M_fa, M_af, M_aa;  // projected inertia (S5) [kg]
  Eigen::Vector3d h_f, h_a;                // projected loads (S5) [N]
  Eigen::Vector3d s;                       // the element's axis
  double c = 0.0;                          // [m/s^2] right-hand side of the length constraint (S6)
};

class ChainSolver
{
public:
  // t: time [s]; x, v: joints x_2 .. x_{nu+2} (3 x (nu+1)), world, for the chain's geometry and data at
  // that instant. Writes their accelerations into a and, when tensions is not null, T_1 .. T_{nu+1}
  // (3 x (nu+1)): the force on element lambda at its forward joint, i.e. the pull toward the ship; T_1 is
  // the tow force the ship applies. Only the solver's own workspace changes.
  void solve(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
             const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
             const Eigen::Ref<const Eigen::Matrix3Xd>& v, Eigen::Ref<Eigen::Matrix3Xd> a,
             Eigen::Matrix3Xd* tensions = nullptr);

private:
  void elementTerms(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                    const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                    const Eigen::Ref<const Eigen::Matrix3Xd>& v);
  void backwardSweep();
  void forwardSweep(const Eigen::Vector3d& a_ship, Eigen::Ref<Eigen::Matrix3Xd> a, Eigen::Matrix3Xd* tensions) const;

  // Workspace, one entry per element.
  std::vector<ElementTerms> terms_;
  std::vector<Eigen::Matrix3d> Phi_, K_;  // a_aft = Phi a_fwd + phi (S12); T_fwd = K a_fwd + tau (S13)
  std::vector<Eigen::Vector3d> phi_, tau_;
};

}  // namespace tow_sim
