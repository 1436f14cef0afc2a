#include "tow_sim/core/integration/implicit_stepper.h"

#include <algorithm>
#include <cmath>

namespace tow_sim
{
// (S16)-(S17) for one chain at the tow point: beginLinearisation and lineariseChain with a single block.
void ImplicitStepper::linearise(const ChainModel& model, const ChainGeometry& geometry, const ChainData& data, double t,
                                const ShipEndState& ship, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                                const Eigen::Ref<const Eigen::Matrix3Xd>& v,
                                const Eigen::Ref<const Eigen::Matrix3Xd>& a, const std::vector<ElementTerms>& terms,
                                const std::vector<double>& multipliers, double winch_d_length, double winch_d_rate)
{
  beginLinearisation(1, winch_d_length, winch_d_rate);
  lineariseChain(0, StateLayout{ static_cast<int>(terms.size()) }, model, geometry, data, t, ship, x, v, a, terms,
                 multipliers);
}

// One block of W per chain (W is block-diagonal over them, docs/solver.md §9); the winch's dL''/dL and
// dL''/dL' of its 2 x 2 block (§7).
void ImplicitStepper::beginLinearisation(std::size_t chains, double winch_d_length, double winch_d_rate)
{
  blocks_.resize(chains);
  winch_d_length_ = winch_d_length;
  winch_d_rate_ = winch_d_rate;
  h_ = 0.0;  // factor() must follow
}

// (S16) per element: D = dh_dv and K = dh_dx, the derivatives of the projected loads w_f, w_a; M_XY and the
// axes s frozen at this state (S17). For a free first joint (S27) the force on it from outside as a load on
// the first element's forward joint.
void ImplicitStepper::lineariseChain(std::size_t index, const StateLayout& layout, const ChainModel& model,
                                     const ChainGeometry& geometry, const ChainData& data, double t,
                                     const ShipEndState& first, const Eigen::Ref<const Eigen::Matrix3Xd>& x,
                                     const Eigen::Ref<const Eigen::Matrix3Xd>& v,
                                     const Eigen::Ref<const Eigen::Matrix3Xd>& a,
                                     const std::vector<ElementTerms>& terms, const std::vector<double>& multipliers,
                                     const Eigen::Matrix3d& first_dF_dx, const Eigen::Matrix3d& first_dF_dv,
                                     const Eigen::Vector2d& end_roll)
{
  Block& block = blocks_.at(index);
  const size_t n = terms.size();
  block.layout = layout;
  block.inertia = terms;
  block.jacobians.resize(n);
  block.stage.resize(n);
  for (size_t i = 0; i < n; ++i)
  {
    const int e = static_cast<int>(i);
    const Eigen::Vector3d x_f = e == 0 ? first.p_W : Eigen::Vector3d(x.col(e - 1));
    const Eigen::Vector3d v_f = e == 0 ? first.v_W : Eigen::Vector3d(v.col(e - 1));
    ElementKinematics k = ElementKinematics::fromJoints(x_f, x.col(e), v_f, v.col(e));
    if (layout.roll && i + 1 == n)  // a rolling end body's loads at its roll (physics.md §5b)
    {
      k.roll = end_roll.x();
      k.roll_rate = end_roll.y();
    }
    Vector6d a_joints;
    a_joints << (e == 0 ? first.a_W : Eigen::Vector3d(a.col(e - 1))), a.col(e);
    // (S16): the loads' D and K, with the geometric stiffness of the multiplier mu (and, elastic, of T: §8).
    ElementJacobian& jacobian = block.jacobians[i];
    elementJacobian(model, e, t, k, geometry, data, multipliers[i], jacobian, &a_joints);
    if (model.bends())
      addBendingStiffness(model, geometry, first.p_W, x, e, jacobian);  // the springs' kappa_b B^T B in K (§11)
    // (S17)-(S18): the stage keeps the axis s (and whether the element is constrained) of this state.
    block.stage[i].s = terms[i].s;
    block.stage[i].constrained = terms[i].constrained;
  }
  if (layout.free && n > 0)
  {
    // (S27): dF/dx_1 and dF/dv_1 join the first element's K_ff and D_ff.
    block.jacobians[0].dh_dx.topLeftCorner<3, 3>() += first_dF_dx;
    block.jacobians[0].dh_dv.topLeftCorner<3, 3>() += first_dF_dv;
  }
  h_ = 0.0;
}

void ImplicitStepper::lineariseChain(std::size_t index, const Chain& chain, const ChainModel& model,
                                     const ChainData& data, double t, const ShipEndState& ship,
                                     const std::vector<double>& y, const std::vector<double>& dydt)
{
  const StateLayout& L = chain.layout();
  ShipEndState first = chain.firstJoint(ship, y);
  Eigen::Matrix3d dF_dx = Eigen::Matrix3d::Zero(), dF_dv = Eigen::Matrix3d::Zero();
  if (L.free)
  {
    // (S27): a free first joint's acceleration a_1 from dydt, and the seabed's dF/dx_1, dF/dv_1.
    first.a_W = L.freeVelocity(dydt);
    chain.freeEndContactJacobian(model, first, dF_dx, dF_dv);
  }
  lineariseChain(index, L, model, chain.geometry(), data, t, first, L.positions(y), L.velocities(y),
                 chain.accelerations(), chain.terms(), chain.axialMultipliers(), dF_dx, dF_dv, L.rollState(y));
  if (L.roll)  // (S29): the spin's acceleration's derivatives in the roll angle and the spin
  {
    const Eigen::Vector2d d = chain.spinAccelerationDerivatives(model, data, t, ship, y, dydt);
    blocks_.at(index).roll_d_angle = d.x();
    blocks_.at(index).roll_d_rate = d.y();
  }
}

// (S19): the stage matrix N_XY = M_XY - gamma h D_XY - (gamma h)^2 K_XY per element, with D = dh_dv and
// K = dh_dx of (S16) (the locals D and K are those of (S16); M holds the projected inertia M_XY, N the stage's
// N_XY, both ElementTerms); the sweep's matrix pass then factors (S18) as it does (S3)-(S6).
void ImplicitStepper::factor(double h)
{
  const double gh = gamma_ * h, gh2 = gh * gh;
  for (Block& block : blocks_)
  {
    for (size_t i = 0; i < block.stage.size(); ++i)
    {
      const ElementTerms& M = block.inertia[i];
      const Matrix6d& D = block.jacobians[i].dh_dv;
      const Matrix6d& K = block.jacobians[i].dh_dx;
      ElementTerms& N = block.stage[i];
      // (S19) block by block, X, Y in {f, a}: N_ff, N_fa, N_af, N_aa.
      N.M_ff = M.M_ff - gh * D.topLeftCorner<3, 3>() - gh2 * K.topLeftCorner<3, 3>();
      N.M_fa = M.M_fa - gh * D.topRightCorner<3, 3>() - gh2 * K.topRightCorner<3, 3>();
      N.M_af = M.M_af - gh * D.bottomLeftCorner<3, 3>() - gh2 * K.bottomLeftCorner<3, 3>();
      N.M_aa = M.M_aa - gh * D.bottomRightCorner<3, 3>() - gh2 * K.bottomRightCorner<3, 3>();
    }
    block.sweep.factor(block.stage);  // (S8)-(S13) over N_XY: Lambda, Phi, A', b, sigma, xi
  }
  h_ = h;
}

// (S18)-(S19) block by block of W (block-diagonal over the chains). K here is the stage k, not the load
// stiffness K of (S16).
void ImplicitStepper::solve(const std::vector<double>& r, const TowPointRates& tow, std::vector<double>& K)
{
  K.resize(r.size());
  for (Block& block : blocks_)
    solveBlock(block, r, tow, K);
}

// One block's stage (S18)-(S19), (S27). Names here: K is the stage k = (k_x, k_v), Kx the load stiffness K of
// (S16), stage.h_f and h_a are w~_f and w~_a, stage.c is Psi~ (docs/solver.md §7's table).
void ImplicitStepper::solveBlock(Block& block, const std::vector<double>& r, const TowPointRates& tow,
                                 std::vector<double>& K)
{
  const StateLayout& L = block.layout;
  const double gh = gamma_ * h_;
  const auto r_x = L.positions(r);
  const auto r_v = L.velocities(r);
  // The first joint: the tow point, whose k = (k_t v_1, k_t a_1) is known: the same form holds with r_v = k_v
  // (its acceleration increment is not an unknown: delta a = (k_v - r_v)/(gamma h) = 0) and
  // r_x = k_x - gamma h k_v (§7). A free first joint (S27): its own rows of r.
  const Eigen::Vector3d rv_first = L.free ? Eigen::Vector3d(L.freeVelocity(r)) : tow.v;
  const Eigen::Vector3d rx_first = L.free ? Eigen::Vector3d(L.freePosition(r)) : Eigen::Vector3d(tow.x - gh * tow.v);
  for (size_t i = 0; i < block.stage.size(); ++i)
  {
    // (S19): w~_X = sum_Y (M_XY r_v,Y + gamma h K_XY r_x,Y) over the element's two joints (in stage.h_f,
    // h_a) and Psi~ = s.(r_v,a - r_v,f) (in stage.c): the loads and the constraint of (S18), the linearised
    // element (S17) scaled by gamma h.
    const Eigen::Index e = static_cast<Eigen::Index>(i);
    const Eigen::Vector3d rv_f = e == 0 ? rv_first : Eigen::Vector3d(r_v.col(e - 1));
    const Eigen::Vector3d rx_f = e == 0 ? rx_first : Eigen::Vector3d(r_x.col(e - 1));
    const Eigen::Vector3d rv_a = r_v.col(e), rx_a = r_x.col(e);
    const ElementTerms& M = block.inertia[i];
    const Matrix6d& Kx = block.jacobians[i].dh_dx;
    ElementTerms& stage = block.stage[i];
    stage.h_f =
        M.M_ff * rv_f + M.M_fa * rv_a + gh * (Kx.topLeftCorner<3, 3>() * rx_f + Kx.topRightCorner<3, 3>() * rx_a);
    stage.h_a =
        M.M_af * rv_f + M.M_aa * rv_a + gh * (Kx.bottomLeftCorner<3, 3>() * rx_f + Kx.bottomRightCorner<3, 3>() * rx_a);
    stage.c = stage.s.dot(rv_a - rv_f);
  }
  block.K_v.resize(3, L.joints);
  if (L.free)
  {
    // (S27): nothing outside the chain moves with the stage (the contact's derivatives are in the first
    // element's loads): T~_1 = 0 at the free joint, k_v,1 = -Lambda~_1^-1 tau~_1, k_x,1 = r_x,1 + gamma h k_v,1.
    const Eigen::Vector3d K_first = block.sweep.solveFree(block.stage, block.K_v);
    L.freeVelocity(K) = K_first;
    L.freePosition(K) = rx_first + gh * K_first;
  }
  else  // (S9)-(S13) over w~_X, Psi~, then (S14) from the tow point's k_v = k_t a_1
    block.sweep.solve(block.stage, tow.v, block.K_v);
  L.velocities(K) = block.K_v;
  L.positions(K) = r_x + gh * block.K_v;  // k_x = r_x + gamma h k_v (docs/solver.md §7)
  // The winch (§7): [1, -gamma h; -gamma h dL''/dL, 1 - gamma h dL''/dL'] (k_L, k_L') = (r_L, r_L'), with
  // dL''/dL = winch_d_length_, dL''/dL' = winch_d_rate_; k_L' after eliminating k_L = r_L + gamma h k_L'. A rolling
  // end body's (S29) has the same form in (phi, p).
  auto pair = [gh](double r_value, double r_rate, double d_value, double d_rate)
  {
    const double k_rate = (r_rate + gh * d_value * r_value) / ((1.0 - gh * d_rate) - gh * gh * d_value);
    return Eigen::Vector2d(r_value + gh * k_rate, k_rate);
  };
  if (L.winch)
  {
    const Eigen::Vector2d k = pair(L.cableOut(r), L.payoutRate(r), winch_d_length_, winch_d_rate_);
    L.cableOut(K) = k.x();
    L.payoutRate(K) = k.y();
  }
  if (L.roll)
    L.setRollState(K, pair(L.rollAngle(r), L.rollRate(r), block.roll_d_angle, block.roll_d_rate));
}

namespace
{
using Stages = std::vector<std::vector<double>>;

// (S15)'s stage point: k_t,i = 1 + sum_{j<i} c_ij k_t,j into K_t[i], stage_y = y + h sum_{j<i} a_ij k_j;
// returns t + c_i h, c_i = sum_{j<i} a_ij k_t,j.
double stagePoint(const RosenbrockTableau& rw, int i, double t, double h, const std::vector<double>& y, const Stages& k,
                  double* K_t, std::vector<double>& stage_y)
{
  double t_stage = t;
  K_t[i] = 1.0;
  stage_y = y;
  for (int j = 0; j < i; ++j)
  {
    t_stage += h * rw.a[i][j] * K_t[j];
    K_t[i] += rw.c[i][j] * K_t[j];
    if (rw.a[i][j] != 0.0)
      for (size_t q = 0; q < y.size(); ++q)
        stage_y[q] += h * rw.a[i][j] * k[j][q];
  }
  return t_stage;
}

// + sum_{j<i} c_ij k_j on the stage's right-hand side.
void addStageHistory(const RosenbrockTableau& rw, int i, const Stages& k, std::vector<double>& stage_f)
{
  for (int j = 0; j < i; ++j)
    for (size_t q = 0; q < stage_f.size(); ++q)
      stage_f[q] += rw.c[i][j] * k[j][q];
}

// y_next = y + h sum m_i k_i, err = h sum e_i k_i.
void combineStages(const RosenbrockTableau& rw, double h, const std::vector<double>& y, const Stages& k,
                   std::vector<double>& y_next, std::vector<double>& error)
{
  y_next = y;
  error.assign(y.size(), 0.0);
  for (int i = 0; i < rw.stages; ++i)
    for (size_t q = 0; q < y.size(); ++q)
    {
      y_next[q] += h * rw.m[i] * k[i][q];
      error[q] += h * rw.e[i] * k[i][q];
    }
}
}  // namespace

void ImplicitStepper::stages(const RosenbrockTableau& rw, double t, double h, const std::vector<double>& y,
                             const std::vector<double>& f0, const ShipMotion& ship, Actuators& actuators,
                             const Derivative& f, std::vector<double>& y_next, std::vector<double>& error)
{
  if (tow_point_frame_)
    stagesTowPoint(rw, t, h, y, f0, ship, actuators, f, y_next, error);
  else
    stagesWorld(rw, t, h, y, f0, ship(t), f, y_next, error);
}

// (S15): W k_i = f(t + c_i h, y + h sum_{j<i} a_ij k_j) + sum_{j<i} c_ij k_j (+ the tow point's k_t,i (v_1, a_1)
// for the gamma h k_t,i f_t term), each solved in O(nu) by solve(); y_next = y + h sum m_i k_i, error (err) =
// h sum e_i k_i. Names here: stage_k_[i] is k_i, K_t[i] is k_t,i.
void ImplicitStepper::stagesWorld(const RosenbrockTableau& rw, double t, double h, const std::vector<double>& y,
                                  const std::vector<double>& f0, const ShipEndState& ship, const Derivative& f,
                                  std::vector<double>& y_next, std::vector<double>& error)
{
  stage_k_.resize(rw.stages);
  stage_f_.resize(y.size());
  double K_t[RosenbrockTableau::kMaxStages];
  for (int i = 0; i < rw.stages; ++i)
  {
    const double t_stage = stagePoint(rw, i, t, h, y, stage_k_, K_t, stage_y_);
    if (i == 0)
      stage_f_ = f0;
    else
      f(t_stage, stage_y_, stage_f_);
    addStageHistory(rw, i, stage_k_, stage_f_);
    solve(stage_f_, TowPointRates{ K_t[i] * ship.v_W, K_t[i] * ship.a_W }, stage_k_[i]);  // W k_i = ...
  }
  combineStages(rw, h, y, stage_k_, y_next, error);
}

namespace
{
// The frame of a step from t (docs/solver.md (S28)): the tow point's state at t continued with its
// acceleration at t, S(t + tau) = (p + v tau + a tau^2 / 2, v + a tau), and S' = (v + a tau, a).
ShipEndState frameAt(const ShipEndState& at_t, double tau)
{
  ShipEndState s;
  s.p_W = at_t.p_W + tau * at_t.v_W + 0.5 * tau * tau * at_t.a_W;
  s.v_W = at_t.v_W + tau * at_t.a_W;
  s.a_W = at_t.a_W;
  return s;
}
}  // namespace

// Adds to the joints of the chains that hang from the tow point the change of the frame's position and
// velocity from `from` to `to`: S(to) - S(from), S repeated at every joint.
void ImplicitStepper::shift(std::vector<double>& y, const ShipEndState& from, const ShipEndState& to) const
{
  const Eigen::Vector3d dp = to.p_W - from.p_W, dv = to.v_W - from.v_W;
  for (const Block& block : blocks_)
  {
    if (block.layout.free)
      continue;
    block.layout.positions(y).colwise() += dp;
    block.layout.velocities(y).colwise() += dv;
  }
}

// dydt - S': the frame's velocity and acceleration taken from the joints' rates (f_z from f).
void ImplicitStepper::subtractFrameRate(std::vector<double>& dydt, const ShipEndState& frame) const
{
  for (const Block& block : blocks_)
  {
    if (block.layout.free)
      continue;
    block.layout.positions(dydt).colwise() -= frame.v_W;
    block.layout.velocities(dydt).colwise() -= frame.a_W;
  }
}

// f_z(t + tau, z) = f(t + tau, z + S(t + tau)) - S'(t + tau) for z = y - S(t), the frame of the step from t:
// f evaluated at y + S(t + tau) - S(t).
void ImplicitStepper::relativeDerivative(const Derivative& f, const ShipEndState& at_t, double t, double tau,
                                         const std::vector<double>& y, std::vector<double>& out)
{
  const ShipEndState s = frameAt(at_t, tau);
  shifted_y_ = y;
  shift(shifted_y_, at_t, s);
  out.resize(y.size());
  f(t + tau, shifted_y_, out);
  subtractFrameRate(out, s);
}

// (S15) in the tow point's frame, z = y - S(t), S the tow point's state at the step's start continued with its
// acceleration then (frameAt; docs/solver.md (S28)): W k_i = f_z(t + c_i h, z + h sum_{j<i} a_ij k_j) +
// sum_{j<i} c_ij k_j + gamma h k_t,i df_z/dt, each solved in O(nu) by solve() with the tow point's increments
// zero (its velocity and acceleration relative to S are zero at t); df_z/dt by a forward difference in t;
// y_next = y + h sum m_i k_i + S(t + h) - S(t), error (err) = h sum e_i k_i. Names here: stage_k_[i] is k_i,
// K_t[i] is k_t,i.
void ImplicitStepper::stagesTowPoint(const RosenbrockTableau& rw, double t, double h, const std::vector<double>& y,
                                     const std::vector<double>& f0, const ShipMotion& ship, Actuators& actuators,
                                     const Derivative& f, std::vector<double>& y_next, std::vector<double>& error)
{
  const size_t n = y.size();
  const ShipEndState at_t = ship(t);
  stage_k_.resize(rw.stages);
  stage_y_.resize(n);
  stage_f_.resize(n);
  // df_z/dt at (t, z): a forward difference over delta from f_z(t, z) = f(t, y) - S'(t), one more evaluation
  // of f (its error, delta/2 d2f_z/dt2, is 1e-5 of the step's own O(h) change in f_z), with the fin servos
  // held as at t: a servo that slews at t may stop within the step (an autopilot's tick), and its slew taken
  // for the whole step cost accuracy (docs/solver.md (S28)).
  const double delta = kTimeDerivativeStep * std::max(1.0, h);
  {
    const HeldServos held(actuators, t);
    relativeDerivative(f, at_t, t, delta, y, f_t_);
  }
  stage_f_ = f0;
  subtractFrameRate(stage_f_, at_t);
  for (size_t q = 0; q < n; ++q)
    f_t_[q] = (f_t_[q] - stage_f_[q]) / delta;
  double K_t[RosenbrockTableau::kMaxStages];
  for (int i = 0; i < rw.stages; ++i)
  {
    const double t_stage = stagePoint(rw, i, t, h, y, stage_k_, K_t, stage_y_);  // z + h sum_{j<i} a_ij k_j
    if (i > 0)  // at i = 0, stage_f_ holds f_z(t, z) = f(t, y) - S'(t) from above
      relativeDerivative(f, at_t, t, t_stage - t, stage_y_, stage_f_);
    addStageHistory(rw, i, stage_k_, stage_f_);
    for (size_t q = 0; q < n; ++q)  // + gamma h k_t,i df_z/dt
      stage_f_[q] += gamma_ * h * K_t[i] * f_t_[q];
    solve(stage_f_, TowPointRates(), stage_k_[i]);  // W k_i = ..., the tow point fixed in this frame
  }
  combineStages(rw, h, y, stage_k_, y_next, error);  // y_next = y + h sum m_i k_i, err = h sum e_i k_i,
  shift(y_next, at_t, frameAt(at_t, h));             // + S(t + h) - S(t)
}

// (S24): ||err|| over the chains, positions relative to the chain's first joint x_1, velocities as they are.
// `error` is err, the result ||err||; atol_x, atol_v, rtol are num.implicit_position_tol, implicit_velocity_tol,
// implicit_rel_tol.
double implicitErrorNorm(const NumericsParams& num, const std::vector<Chain>& chains, bool winch,
                         const std::vector<double>& error, const std::vector<double>& y,
                         const std::vector<double>& y_next, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1)
{
  double sum = 0.0, count = 0.0;
  // (S24)'s squared ratio of one component's error to its scale, atol + rtol max(|value0|, |value1|); a
  // position and its velocity are summed as a pair.
  auto ratio = [&](double e, double value0, double value1, double atol)
  { return std::pow(e / (atol + num.implicit_rel_tol * std::max(std::abs(value0), std::abs(value1))), 2); };
  for (const Chain& chain : chains)
  {
    const StateLayout& L = chain.layout();
    // Measured from the chain's first joint x_1 (q0, q1): the tow point, or a parted vehicle side's free end
    // (which drifts away from the ship without limit, §9), whose own position error is taken against the
    // absolute tolerance.
    const Eigen::Vector3d q0 = L.free ? Eigen::Vector3d(L.freePosition(y)) : p0;
    const Eigen::Vector3d q1 = L.free ? Eigen::Vector3d(L.freePosition(y_next)) : p1;
    const auto e_x = L.positions(error), e_v = L.velocities(error);
    const auto x0 = L.positions(y), x1 = L.positions(y_next);
    const auto v0 = L.velocities(y), v1 = L.velocities(y_next);
    for (int j = 0; j < L.joints; ++j)
      for (int i = 0; i < 3; ++i)
        sum += ratio(e_x(i, j), x0(i, j) - q0[i], x1(i, j) - q1[i], num.implicit_position_tol) +
               ratio(e_v(i, j), v0(i, j), v1(i, j), num.implicit_velocity_tol);
    count += 6.0 * L.joints;  // n_c
    if (L.winch && winch)
    {
      sum += ratio(L.cableOut(error), L.cableOut(y), L.cableOut(y_next), num.implicit_position_tol) +
             ratio(L.payoutRate(error), L.payoutRate(y), L.payoutRate(y_next), num.implicit_velocity_tol);
      count += 2.0;
    }
    if (L.roll)  // (S24): the roll angle as the arc it turns at 1 m, the spin as a velocity there
    {
      sum += ratio(L.rollAngle(error), L.rollAngle(y), L.rollAngle(y_next), num.implicit_position_tol) +
             ratio(L.rollRate(error), L.rollRate(y), L.rollRate(y_next), num.implicit_velocity_tol);
      count += 2.0;
    }
    if (L.free)
    {
      for (int i = 0; i < 3; ++i)
        sum +=
            ratio(L.freePosition(error)[i], 0.0, 0.0, num.implicit_position_tol) +
            ratio(L.freeVelocity(error)[i], L.freeVelocity(y)[i], L.freeVelocity(y_next)[i], num.implicit_velocity_tol);
      count += 6.0;
    }
  }
  return std::sqrt(sum / count);  // ||err|| = sqrt((1/n_c) sum ...)
}

}  // namespace tow_sim
