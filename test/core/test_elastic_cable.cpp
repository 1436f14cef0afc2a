// The elastic, tension-only cable (cable.axial_stiffness, physics.md §9; docs/solver.md §8) against
// answers that do not come from the code under test: energy conservation with the strain energy in vacuum,
// the closed-form stretch of a hanging cable, the axial natural period of a body on a cable and its forced
// response from the single-degree-of-freedom model, the rigid chain as EA grows, and a light body heaved at
// resonance: slack, snaps, a converged snap peak. (The tow: test_elastic_tow.cpp.)
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "core/chain_fixtures.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/seabed.h"
#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
namespace
{

Environment vacuum()
{
  Environment env;
  env.water_density = 0.0;
  return env;
}

// Kinetic, gravity and strain energy of an elastic chain in vacuum (its segments uniform rods whose
// velocity is linear between their joints: 1/2 m |v_G|^2 + m/24 |v_a - v_f|^2) ending in a rigid body.
double elasticEnergy(const ChainModel& model, const EndElementParams& end, const ShipEndState& ship,
                     const ChainState& state)
{
  const CableParams& cable = model.cable();
  const double g = model.environment().gravity;
  double energy = 0.0;
  Eigen::Vector3d x_f = ship.p_W, v_f = ship.v_W;
  for (int e = 0; e < model.elementCount(); ++e)
  {
    const Eigen::Vector3d x_a = state.x.col(e), v_a = state.v.col(e);
    if (e < model.segments())
    {
      const double d0 = cable.segmentLength(), m = cable.mass_per_length * d0;
      const double stretch = std::max(0.0, (x_a - x_f).norm() - d0);
      energy += 0.5 * m * (0.5 * (v_f + v_a)).squaredNorm() + m / 24.0 * (v_a - v_f).squaredNorm() +
                m * g * 0.5 * (x_f + x_a).z() + 0.5 * *cable.axial_stiffness / d0 * stretch * stretch;
    }
    else
    {
      const double gamma = end.cg_from_bail / end.length;
      const Eigen::Vector3d s = (x_a - x_f).normalized();
      const Eigen::Vector3d w = s.cross((v_a - v_f) / end.length);
      energy += 0.5 * end.mass * (v_f + gamma * (v_a - v_f)).squaredNorm() +
                0.5 * end.transverseInertia() * w.squaredNorm() + end.mass * g * (x_f + gamma * (x_a - x_f)).z();
    }
    x_f = x_a;
    v_f = v_a;
  }
  return energy;
}

// The penalty energy of a frictionless, undamped flat seabed: 1/2 k delta^2 at each joint below it, k the
// stiffness of the cable the joint stands for (half of each neighbouring segment; the bail half the last
// one) or the end body's at its tail point.
double seabedEnergy(const ChainModel& model, const SeabedParams& bottom, const ChainState& state)
{
  double energy = 0.0;
  const double d = model.cable().segmentLength();
  for (int j = 0; j < model.jointCount(); ++j)
  {
    const double below = std::max(0.0, -bottom.depth - state.x(2, j));
    const double k = j + 1 < model.segments()
                         ? bottom.stiffness * d
                         : (j + 1 == model.segments() ? bottom.stiffness * 0.5 * d : bottom.vehicle_stiffness);
    energy += 0.5 * k * below * below;
  }
  return energy;
}

// A released elastic chain in vacuum, no damping: a 3-D swing that stretches and slackens its segments
// (released from its rest length, it falls until gravity stretches it), over a frictionless, undamped
// seabed when one is given. Returns the largest relative drift of its energy (kinetic plus gravity plus
// strain plus the seabed's penalty) over 20 s and the range of the segments' strains.
double releasedEnergyDrift(const SeabedParams* bottom, double& largest_strain, double& smallest_strain)
{
  CableParams cable;
  cable.segments = 8;
  cable.length = 8.0;
  cable.mass_per_length = 1.5;
  cable.axial_stiffness = 2.0e3;  // soft: strains of tens of per cent
  EndElementParams end = test::endLikeSegment(cable);
  end.mass = 4.0;
  end.cg_from_bail = 0.7;
  end.transverse_inertia = 0.6;
  NumericsParams num;
  num.stepper = StepperType::kDopri5;
  num.abs_tol = num.rel_tol = 1e-11;
  auto model = test::makeModel(cable, end, vacuum(), num, bottom ? std::make_shared<const Seabed>(*bottom) : nullptr);
  const ShipMotion fixed = constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  Simulator sim(model, fixed);
  ChainState start =
      straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.0, -0.577), Eigen::Vector3d::Zero());
  for (int j = 0; j < model->jointCount(); ++j)
    start.v.col(j) = Eigen::Vector3d(0.0, 0.3 * j / model->jointCount(), 0.0);
  sim.reset(0.0, start);
  auto energy = [&]
  {
    return elasticEnergy(*model, end, fixed(0.0), sim.state()) +
           (bottom ? seabedEnergy(*model, *bottom, sim.state()) : 0.0);
  };
  const double e0 = energy();
  double worst = 0.0;
  largest_strain = 0.0;
  smallest_strain = 1.0;
  for (int i = 1; i <= 200; ++i)
  {
    sim.advanceTo(0.1 * i);
    worst = std::max(worst, std::abs(energy() / e0 - 1.0));
    for (double eps : segmentStrains(sim.geometry(), sim.jointPositions()))
    {
      largest_strain = std::max(largest_strain, eps);
      smallest_strain = std::min(smallest_strain, eps);
    }
  }
  EXPECT_LT(sim.lengthError(), 1e-9);  // the end body keeps its length
  return worst;
}

// Kept to 1e-6. Leaving out the stretch inertia or the strain energy's force breaks this by orders of
// magnitude.
TEST(ElasticCable, ConservesEnergyInVacuum)
{
  double largest = 0.0, smallest = 0.0;
  const double drift = releasedEnergyDrift(nullptr, largest, smallest);
  std::printf("energy drift %.2e over 20 s; strains %.4f .. %.4f\n", drift, smallest, largest);
  EXPECT_LT(drift, 1e-6);
  EXPECT_GT(largest, 0.01);    // it did stretch
  EXPECT_LT(smallest, -0.01);  // and went slack
}

// The same chain swinging onto a frictionless, undamped flat seabed 5 m down (the penalty a spring): the
// energy with the penalty's is kept to 1e-6. The seabed's force at a joint must act on that joint alone:
// through the rigid projection's moment arm, half of its component along the segment would land on the
// forward joint and do work on the stretch.
TEST(ElasticCable, ConservesEnergyOnAFrictionlessSeabed)
{
  SeabedParams bottom;
  bottom.type = SeabedParams::Type::kFlat;
  bottom.depth = 5.0;
  bottom.damping = bottom.vehicle_damping = bottom.friction = 0.0;
  bottom.vehicle_stiffness = 1.0e4;
  double largest = 0.0, smallest = 0.0;
  const double drift = releasedEnergyDrift(&bottom, largest, smallest);
  std::printf("energy drift on the seabed %.2e over 20 s; strains %.4f .. %.4f\n", drift, smallest, largest);
  EXPECT_LT(drift, 1e-6);
}

// A vertical cable of rest length L hanging from a fixed point with a body of wet weight W: the tension at
// s0 (rest length from the bottom) is W + w s0 and the total stretch int T/EA ds0 = (W L + w L^2/2)/EA.
struct Hanging
{
  CableParams cable;
  EndElementParams end;
  Environment env;
  double wetWeightPerLength() const
  {
    return (cable.mass_per_length - env.water_density * 0.25 * kPi * cable.diameter * cable.diameter) * env.gravity;
  }
  double bodyWetWeight() const { return (end.mass - env.water_density * end.displaced_volume) * env.gravity; }
  double stretch() const
  {
    const double L = cable.length;
    return (bodyWetWeight() * L + 0.5 * wetWeightPerLength() * L * L) / *cable.axial_stiffness;
  }
};

// The bail's depth below the tow point once a hanging elastic cable, released at its rest length, has
// settled (axial damping and the water's drag take the oscillation out).
TEST(ElasticCable, AHangingCableStretchesByTheIntegralOfTOverEA)
{
  Hanging h;
  h.cable.length = 100.0;
  h.cable.segments = 20;
  h.cable.axial_stiffness = 1.0e6;
  h.cable.axial_damping = 1.5e5;
  auto model = test::makeModel(h.cable, h.end, h.env);
  const ShipMotion fixed = constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  Simulator sim(model, fixed);
  sim.reset(0.0, straightChain(*model, Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero()));
  sim.advanceTo(60.0);
  const double bail_depth = -sim.jointPositions().col(h.cable.segments).z();
  const double stretch = bail_depth - h.cable.length;
  std::printf("stretch %.6f m, closed form %.6f m\n", stretch, h.stretch());
  EXPECT_NEAR(stretch, h.stretch(), 1e-3 * h.stretch());
  EXPECT_LT(sim.state().v.cwiseAbs().maxCoeff(), 1e-4);  // settled
  // The tension at the top, against W + w L (the joint force there carries half the top segment's weight
  // besides the segment's own tension).
  const double top = sim.tensions().col(0).norm();
  EXPECT_NEAR(top, h.bodyWetWeight() + h.wetWeightPerLength() * h.cable.length, 1e-3 * top);
}

// A heavy body on an elastic cable in vacuum, its joints started in the closed-form static stretch and given
// a downward velocity growing linearly along the cable (mostly the first axial mode). The period of the
// body's bobbing against 2 pi sqrt((M + m_c/3) L / EA).
struct Bobbing
{
  CableParams cable;
  EndElementParams end;
  double L() const { return cable.length; }
  double estimatePeriod() const
  {
    const double m_c = cable.mass_per_length * L();
    return 2.0 * kPi * std::sqrt((end.mass + m_c / 3.0) * L() / *cable.axial_stiffness);
  }
  // The static shape (vacuum): the joint at rest length s0 from the top lies at -(s0 + int_0^s0 T/EA).
  ChainState staticState(double kick) const
  {
    const double g = 9.81, EA = *cable.axial_stiffness, w = cable.mass_per_length * g, W = end.mass * g;
    const int n = cable.segments;
    ChainState s;
    s.x.setZero(3, n + 1);
    s.v.setZero(3, n + 1);
    for (int j = 1; j <= n; ++j)
    {
      const double s0 = L() * j / n;
      const double z = -(s0 + ((W + w * L()) * s0 - 0.5 * w * s0 * s0) / EA);
      s.x(2, j - 1) = z;
      s.v(2, j - 1) = -kick * s0 / L();
    }
    s.x(2, n) = s.x(2, n - 1) - end.length;
    s.v(2, n) = s.v(2, n - 1);
    return s;
  }
};

double bobbingPeriod(const Bobbing& b, StepperType stepper)
{
  NumericsParams num;
  num.stepper = stepper;
  num.abs_tol = num.rel_tol = 1e-9;
  num.implicit_position_tol = num.implicit_velocity_tol = num.implicit_rel_tol = 1e-7;
  Environment env = vacuum();
  auto model = test::makeModel(b.cable, b.end, env, num);
  Simulator sim(model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  sim.reset(0.0, b.staticState(0.5));
  // Upward crossings of the body's vertical velocity through zero (its lowest points), linearly interpolated.
  std::vector<double> crossings;
  double t_prev = 0.0, v_prev = sim.state().v(2, b.cable.segments);
  const double dt = 0.002;
  for (int i = 1; i <= 8000 && crossings.size() < 11; ++i)
  {
    sim.advanceTo(i * dt);
    const double v = sim.state().v(2, b.cable.segments);
    if (v_prev < 0.0 && v >= 0.0)
      crossings.push_back(t_prev + dt * (-v_prev) / (v - v_prev));
    t_prev = i * dt;
    v_prev = v;
  }
  if (crossings.size() < 11)
    return 0.0;
  return (crossings.back() - crossings.front()) / 10.0;
}

TEST(ElasticCable, TheAxialPeriodOfABodyOnACableMatchesOneDegreeOfFreedom)
{
  Bobbing b;
  b.cable.length = 100.0;
  b.cable.segments = 20;
  b.cable.axial_stiffness = 1.0e6;
  b.end.mass = 500.0;
  b.end.displaced_volume = 0.0;
  const double estimate = b.estimatePeriod();
  for (StepperType stepper : { StepperType::kDopri5, StepperType::kImplicit })
  {
    const double period = bobbingPeriod(b, stepper);
    std::printf("axial period %.4f s, estimate %.4f s\n", period, estimate);
    EXPECT_NEAR(period, estimate, 0.02 * estimate);
  }
}

// A tow point heaving z = A sin(w t), ship otherwise at rest.
ShipMotion heavingTowPoint(double amplitude, double omega)
{
  return [amplitude, omega](double t)
  {
    ShipEndState s;
    s.p_W.z() = amplitude * std::sin(omega * t);
    s.v_W.z() = amplitude * omega * std::cos(omega * t);
    s.a_W.z() = -amplitude * omega * omega * std::sin(omega * t);
    return s;
  };
}

// The same body and cable with axial damping (5 % of critical in the one-degree-of-freedom model), the tow
// point heaved at 0.6 of the natural frequency, 0.1 m: once the start has died out, the tension at the bail
// swings by M w^2 |X| about its mean, X the body's response to the base motion,
// X / A = (k + i w c') / (k - M_eff w^2 + i w c'), k = EA/L, c' = c/L, M_eff = M + m_c/3. Within 5 %; the
// cable never slackens.
TEST(ElasticCable, TheForcedHeaveTensionFollowsTheLinearResponse)
{
  Bobbing b;
  b.cable.length = 100.0;
  b.cable.segments = 20;
  b.cable.axial_stiffness = 1.0e6;
  b.end.mass = 500.0;
  b.end.displaced_volume = 0.0;
  const double k = *b.cable.axial_stiffness / b.L(), M_eff = b.end.mass + b.cable.mass_per_length * b.L() / 3.0;
  const double omega_n = std::sqrt(k / M_eff), c_prime = 2.0 * 0.05 * std::sqrt(k * M_eff);
  b.cable.axial_damping = c_prime * b.L();
  const double A = 0.1, omega = 0.6 * omega_n;
  const std::complex<double> X =
      A * std::complex<double>(k, omega * c_prime) / std::complex<double>(k - M_eff * omega * omega, omega * c_prime);
  const double expected = b.end.mass * omega * omega * std::abs(X);

  auto model = test::makeModel(b.cable, b.end, vacuum());
  Simulator sim(model, heavingTowPoint(A, omega));
  sim.reset(0.0, b.staticState(0.0));
  double lo = 1e12, hi = 0.0;
  for (int i = 1; i <= 3000; ++i)
  {
    const StepReport r = sim.advanceTo(0.02 * i);
    EXPECT_EQ(r.snaps, 0);
    if (i * 0.02 > 40.0)
    {
      lo = std::min(lo, sim.tensions().col(b.cable.segments).norm());
      hi = std::max(hi, sim.tensions().col(b.cable.segments).norm());
    }
  }
  std::printf("tension at the bail %.1f .. %.1f N: amplitude %.2f N, linear response %.2f N\n", lo, hi, 0.5 * (hi - lo),
              expected);
  EXPECT_NEAR(0.5 * (hi - lo), expected, 0.05 * expected);
  EXPECT_NEAR(0.5 * (hi + lo), b.end.mass * 9.81, 0.01 * b.end.mass * 9.81);
}

// A light body on a soft cable in water, its tow point heaved at the axial resonance: the cable goes slack
// and snaps taut again. Each segment's tension is the law's, never negative (EA eps + c deps/dt is, often),
// snaps are counted, and the largest tension
// at the ship over the run moves by less than 2 % when the tolerances are halved.
struct SnapRun
{
  double peak = 0.0;       // [N] largest |T_1| over the steps
  long snaps = 0;          // slack -> taut
  double worst_law = 0.0;  // [N] largest |tension - max(0, EA eps + c deps/dt)| of any segment at any output
  int clamped = 0;         // segment outputs where EA eps + c deps/dt < 0 (the law's max(0, .) at work)
  int slack_outputs = 0;   // outputs with a slack segment
};

SnapRun heaveAtResonance(double tolerance)
{
  CableParams cable;
  cable.length = 50.0;
  cable.segments = 10;
  cable.axial_stiffness = 2.0e4;
  cable.axial_damping = 2.0e3;
  EndElementParams end;
  end.mass = 50.0;
  end.displaced_volume = 0.02;
  NumericsParams num;
  num.implicit_position_tol = num.implicit_velocity_tol = num.implicit_rel_tol = tolerance;
  auto model = test::makeModel(cable, end, Environment(), num);
  const double omega_n = std::sqrt(*cable.axial_stiffness / cable.length / (end.mass + 50.0 / 3.0));
  Simulator sim(model, heavingTowPoint(1.0, omega_n));
  ChainState start = straightChain(*model, Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero());
  sim.reset(0.0, start);
  SnapRun run;
  const double d0 = cable.segmentLength();
  for (int i = 1; i <= 600; ++i)
  {
    const StepReport r = sim.advanceTo(0.1 * i);
    run.snaps += r.snaps;
    run.peak = std::max(run.peak, r.tension_ship.max);
    // Each segment's tension (minus its multiplier) against the law, from the joints' state.
    const std::vector<double>& mu = sim.axialMultipliers();
    const Eigen::Matrix3Xd x = sim.jointPositions();
    const ChainState state = sim.state();
    bool slack = false;
    for (int e = 0; e < cable.segments; ++e)
    {
      const Eigen::Vector3d dx = x.col(e + 1) - x.col(e);
      const Eigen::Vector3d dv = state.v.col(e) - (e == 0 ? sim.shipEnd().v_W : Eigen::Vector3d(state.v.col(e - 1)));
      const double law =
          *cable.axial_stiffness * (dx.norm() / d0 - 1.0) + cable.axial_damping * dx.normalized().dot(dv) / d0;
      run.clamped += law < 0.0 ? 1 : 0;
      run.worst_law = std::max(run.worst_law, std::abs(-mu[static_cast<size_t>(e)] - std::max(law, 0.0)));
      slack = slack || mu[static_cast<size_t>(e)] >= 0.0;
    }
    run.slack_outputs += slack ? 1 : 0;
  }
  return run;
}

TEST(ElasticCable, ALightBodyHeavedAtResonanceSnapsWithAConvergedPeak)
{
  const SnapRun coarse = heaveAtResonance(1e-5), fine = heaveAtResonance(5e-6);
  std::printf("snap peak %.1f N (tolerance 1e-5), %.1f N (5e-6); %ld / %ld snaps, slack at %d / %d outputs\n",
              coarse.peak, fine.peak, coarse.snaps, fine.snaps, coarse.slack_outputs, fine.slack_outputs);
  EXPECT_GT(coarse.snaps, 10);
  EXPECT_GT(coarse.slack_outputs, 20);
  EXPECT_GT(coarse.clamped, 100);
  EXPECT_LT(coarse.worst_law, 1e-6);
  EXPECT_LT(fine.worst_law, 1e-6);
  EXPECT_NEAR(coarse.peak, fine.peak, 0.02 * fine.peak);
}

}  // namespace
}  // namespace tow_sim
