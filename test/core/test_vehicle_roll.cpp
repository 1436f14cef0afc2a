// A vehicle that rolls (vehicle.roll: free, physics.md §5b): its roll period against the closed form of a body
// on its metacentric height, its heel under a rudder whose centre of pressure is above the axis against the
// moment balance, and the free roll left at zero reproducing the fixed one.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <vector>

#include "core/chain_fixtures.h"
#include "tow_sim/core/analysis/equilibrium.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace
{
using Tow = test::VehicleTow;

// Starts the vehicle rolled by `roll` [rad] and spinning at `rate` [rad/s], through a saved state.
void setRoll(Tow& tow, double roll, double rate)
{
  SimulatorState s = tow.sim->saveState();
  s.y[s.y.size() - 2] = roll;  // a rolling vehicle's two states come last (StateLayout)
  s.y[s.y.size() - 1] = rate;
  tow.sim->restoreState(s);
}

// 2 m/s along +x until t0 [s], then round a circle of radius r [m] to port.
ShipMotion turningShip(double t0, double r)
{
  const double u = 2.0;
  return [=](double t)
  {
    ShipEndState s;
    if (t <= t0)
    {
      s.p_W = Eigen::Vector3d(u * t, 0.0, 0.0);
      s.v_W = Eigen::Vector3d(u, 0.0, 0.0);
      return s;
    }
    const double a = u * (t - t0) / r;
    s.p_W = Eigen::Vector3d(u * t0 + r * std::sin(a), r - r * std::cos(a), 0.0);
    s.v_W = u * Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
    s.a_W = (u * u / r) * Eigen::Vector3d(-std::sin(a), std::cos(a), 0.0);
    return s;
  };
}

// 100 m of the default cable in 20 segments at 2 m/s, from the steady-tow equilibrium.
Tow steadyTow(const VehicleParams& p, StepperType stepper, ShipMotion ship = nullptr,
              const WinchParams& winch = WinchParams())
{
  Tow tow;
  CableParams cable;
  cable.length = 100.0;
  cable.segments = 20;
  NumericsParams num;
  num.stepper = stepper;
  tow.vehicle = std::make_shared<Vehicle>(p, num);
  tow.model = std::make_shared<ChainModel>(cable, tow.vehicle, Environment(), num);
  const Eigen::Vector3d u(2.0, 0.0, 0.0);
  tow.sim =
      std::make_unique<Simulator>(tow.model, ship ? ship : constantVelocityShip(Eigen::Vector3d::Zero(), u), winch);
  tow.sim->reset(0.0, steadyTowEquilibrium(*tow.model, 0.0, Eigen::Vector3d::Zero(), u).state);
  return tow;
}

VehicleParams rollingVehicle()
{
  VehicleParams p;
  p.roll = VehicleRoll::kFree;
  p.cb_above_cg = 0.05;
  p.roll_added_inertia = 1.0;
  return p;
}

// The mean period [s] between the upward zero crossings of roll(t) sampled every dt from t0.
double meanPeriod(const std::vector<double>& roll, double dt)
{
  std::vector<double> crossings;
  for (size_t i = 1; i < roll.size(); ++i)
    if (roll[i - 1] < 0.0 && roll[i] >= 0.0)
      crossings.push_back(dt * (static_cast<double>(i - 1) + roll[i - 1] / (roll[i - 1] - roll[i])));
  if (crossings.size() < 2)
    return NAN;
  return (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
}

class RollPeriod : public ::testing::TestWithParam<StepperType>
{
};

// Nothing on the axis rolls the vehicle (hull, fins at the axis: no elevator span, tension at the bail): a small
// roll swings on the buoyancy's arm alone, T = 2 pi sqrt((I_xx + I_a) / (rho g V h_BG cos theta)), theta the
// axis' pitch.
TEST_P(RollPeriod, IsTheMetacentricClosedForm)
{
  VehicleParams p = rollingVehicle();
  p.elevator_span = 0.0;  // fins at the axis: the spin does not move them (P57b)
  Tow tow = steadyTow(p, GetParam());
  tow.sim->advanceTo(30.0);
  setRoll(tow, 0.05, 0.0);
  const double dt = 0.005;
  std::vector<double> roll;
  for (int i = 0; i <= 1600; ++i)
  {
    tow.sim->advanceTo(30.0 + i * dt);
    roll.push_back(tow.out().roll);
  }
  const Environment& env = tow.sim->data().environment;
  const double theta = tow.out().pitch;
  const double stiffness = env.water_density * env.gravity * p.displaced_volume * p.cb_above_cg * std::cos(theta);
  const double expected = 2.0 * kPi * std::sqrt((p.inertia_B(0, 0) + p.roll_added_inertia) / stiffness);
  const double period = meanPeriod(roll, dt);
  std::printf("roll period %.5f s, closed form %.5f s (pitch %.3f deg)\n", period, expected, theta * 180.0 / kPi);
  EXPECT_NEAR(period, expected, 2e-3 * expected);
  // Undamped: the amplitude stays (within the integration's dissipation).
  double late = 0.0;
  for (size_t i = roll.size() - 300; i < roll.size(); ++i)
    late = std::max(late, std::abs(roll[i]));
  EXPECT_NEAR(late, 0.05, 2.5e-3);
}

INSTANTIATE_TEST_SUITE_P(Steppers, RollPeriod, ::testing::Values(StepperType::kDopri5, StepperType::kImplicit),
                         [](const auto& info) { return info.param == StepperType::kDopri5 ? "dopri5" : "implicit"; });

// In still water, a vehicle hung at its CG (bail, CG and CB at one station: no pitching moment, so its axis stays
// level) swings in roll at T = 2 pi sqrt((I_xx + I_a) / (rho g V h_BG)), the submerged body's metacentric form.
TEST(VehicleRoll, InStillWaterItSwingsOnItsMetacentricHeight)
{
  VehicleParams p = rollingVehicle();
  p.cg_from_bail = p.cb_from_bail = 0.0;
  Tow tow;
  CableParams cable;
  cable.length = 50.0;
  cable.segments = 10;
  NumericsParams num;
  tow.vehicle = std::make_shared<Vehicle>(p, num);
  tow.model = std::make_shared<ChainModel>(cable, tow.vehicle, Environment(), num);
  tow.sim =
      std::make_unique<Simulator>(tow.model, constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()));
  ChainState start =
      straightChain(*tow.model, Eigen::Vector3d::Zero(), -Eigen::Vector3d::UnitZ(), Eigen::Vector3d::Zero());
  const int tail = cable.segments;
  start.x.col(tail) = start.x.col(tail - 1) - p.tail_from_bail * Eigen::Vector3d::UnitX();  // level, nose to +x
  tow.sim->reset(0.0, start);
  setRoll(tow, 0.05, 0.0);
  const double dt = 0.005;
  std::vector<double> roll;
  for (int i = 1; i <= 1600; ++i)
  {
    tow.sim->advanceTo(i * dt);
    roll.push_back(tow.out().roll);
  }
  const Environment& env = tow.sim->data().environment;
  const double stiffness = env.water_density * env.gravity * p.displaced_volume * p.cb_above_cg;
  const double expected = 2.0 * kPi * std::sqrt((p.inertia_B(0, 0) + p.roll_added_inertia) / stiffness);
  const double period = meanPeriod(roll, dt);
  std::printf("still water: roll period %.5f s, closed form %.5f s; pitch now %.2e rad\n", period, expected,
              tow.out().pitch);
  EXPECT_NEAR(tow.out().pitch, 0.0, 1e-6);  // stays level
  EXPECT_NEAR(period, expected, 2e-3 * expected);
}

// A rudder whose centre of pressure is rudder_height above the axis heels the vehicle until the buoyancy's
// moment balances it: rho g V h_BG sin(phi) cos(theta) = -rudder_height F_y (F_y the rudder's side force, body
// axes): a side force to port above the axis rolls the vehicle port side down (phi < 0).
TEST(VehicleRoll, RudderHeelIsBalancedByTheBuoyancyMoment)
{
  VehicleParams p = rollingVehicle();
  p.rudder_height = 0.2;
  p.roll_damping = 20.0;
  for (StepperType stepper : { StepperType::kDopri5, StepperType::kImplicit })
  {
    Tow tow = steadyTow(p, stepper);
    tow.sim->command(0.15, 0.0, 0.0);
    tow.sim->advanceTo(200.0);
    const VehicleOutputs o = tow.out();
    const Environment& env = tow.sim->data().environment;
    const double side = (o.rudder_loads.lift_B + o.rudder_loads.drag_B).y();
    const double buoyancy_arm = env.water_density * env.gravity * p.displaced_volume * p.cb_above_cg;
    const double expected = std::asin(-p.rudder_height * side / (buoyancy_arm * std::cos(o.pitch)));
    std::printf("heel %.5f deg, moment balance %.5f deg (rudder side force %.2f N, yaw %.3f deg)\n",
                o.roll * 180.0 / kPi, expected * 180.0 / kPi, side, o.yaw * 180.0 / kPi);
    EXPECT_GT(std::abs(side), 1.0);  // the rudder pushes
    EXPECT_LT(o.roll * side, 0.0);   // to port above the axis: port side down
    EXPECT_NEAR(o.roll, expected, 1e-3 * std::abs(expected));
    EXPECT_NEAR(o.omega_B.x(), 0.0, 1e-6);  // settled
  }
}

// In a steady turn the whole tow turns at the ship's rate r = U/R about the vertical, so the pitched body spins
// about its own axis at p = omega . x_b = -r sin(theta) while its roll stays constant; the roll damping's
// moment -c p then stands against the buoyancy's: rho g V h_BG sin(phi) cos(theta) = c r sin(theta) (nothing else
// on the axis rolls it; the gyroscopic moment of an axisymmetric body in a steady turn is about y_b). A nose-up
// vehicle (theta < 0) turning to port (r > 0) heels to port (phi < 0).
TEST(VehicleRoll, ASteadyTurnHeelsItByTheRollDampingOfItsSpin)
{
  VehicleParams p = rollingVehicle();
  p.roll_damping = 300.0;
  p.elevator_span = 0.0;  // the fins' own damping (P57b) left out: the hull's c alone
  const double radius = 150.0, rate = 2.0 / radius;
  for (StepperType stepper : { StepperType::kDopri5, StepperType::kImplicit })
  {
    Tow tow = steadyTow(p, stepper, turningShip(5.0, radius));
    tow.sim->advanceTo(900.0);
    const VehicleOutputs o = tow.out();
    const Environment& env = tow.sim->data().environment;
    const double buoyancy_arm = env.water_density * env.gravity * p.displaced_volume * p.cb_above_cg;
    const double expected = std::asin(p.roll_damping * rate * std::sin(o.pitch) / (buoyancy_arm * std::cos(o.pitch)));
    std::printf(
        "steady turn (R %.0f m): heel %.5f deg, balance %.5f deg; spin %.6f rad/s, -r sin(theta) %.6f; "
        "yaw rate %.6f rad/s\n",
        radius, o.roll * 180.0 / kPi, expected * 180.0 / kPi, o.omega_B.x(), -rate * std::sin(o.pitch), o.omega_W.z());
    EXPECT_NEAR(o.omega_W.z(), rate, 1e-3 * rate);  // the turn is steady
    EXPECT_LT(o.roll, 0.0);
    EXPECT_NEAR(o.roll, expected, 0.01 * std::abs(expected));
  }
}

// The fins' own roll damping (P57b). In a flow along the axis (each fin's inflow angle zero) the spin p moves an
// elevator fin at span b by -+p b z_b: its angle of attack changes by +-p b / V and its force normal to the axis
// by (C/2) (F_L'(0) + F_D(0)) V p b (half the pair's constants C5, C6 each), so the pair's roll moment is
// -(C5 F_L'(0) + C6 F_D(0)) V b^2 p and its net force zero; the rudder at h_r above the axis likewise gives
// -(C3 F_L'(0) + C4 F_D(0)) V h_r^2 p, with a side force (C3 F_L'(0) + C4 F_D(0)) V h_r p along y_b. With the
// default tables F_L'(0) = 1 and F_D(0) = 0.02 (the drag's own slope at zero multiplies the inflow angle, zero).
double finRollDamping(const VehicleParams& p, double speed)
{
  return (p.elevator.lift_constant + 0.02 * p.elevator.drag_constant) * speed * p.elevator_span * p.elevator_span +
         (p.rudder.lift_constant + 0.02 * p.rudder.drag_constant) * speed * p.rudder_height * p.rudder_height;
}

// The fins' loads on a level vehicle moving at 2 m/s along its axis (+x), spinning at p and not: the roll
// moment's change per unit spin against the linearisation above, for the elevator at its span and the rudder
// above the axis.
TEST(VehicleRoll, TheFinsRollMomentOfASpinIsTheirLinearisedLiftAndDrag)
{
  struct Case
  {
    double span, rudder_height;
  };
  for (const Case& fins : { Case{ 0.25, 0.0 }, Case{ 0.0, 0.15 }, Case{ 0.3, -0.2 } })
  {
    VehicleParams p = rollingVehicle();
    p.elevator_span = fins.span;
    p.rudder_height = fins.rudder_height;
    const Vehicle vehicle(p);
    const Environment env;
    const Eigen::Vector3d v(2.0, 0.0, 0.0);
    auto at = [&](double spin)
    {
      ElementKinematics k =
          ElementKinematics::fromJoints(Eigen::Vector3d::Zero(), Eigen::Vector3d(-p.tail_from_bail, 0.0, 0.0), v, v);
      k.roll_rate = spin;
      return vehicle.outputs(0.0, k, env, vehicle.restingActuators(0.0));
    };
    const VehicleOutputs still = at(0.0);
    const double spin = 1e-4;
    const VehicleOutputs spinning = at(spin);
    auto roll_moment = [](const VehicleOutputs& o)
    { return (o.rudder_loads.moment_cg_W + o.elevator_loads.moment_cg_W).x(); };
    const double per_spin = (roll_moment(spinning) - roll_moment(still)) / spin;
    const double side = (spinning.rudder_loads.lift_W + spinning.rudder_loads.drag_W).y() / spin;
    const double expected_side = (p.rudder.lift_constant + 0.02 * p.rudder.drag_constant) * 2.0 * p.rudder_height;
    std::printf(
        "span %.2f m, rudder height %.2f m: roll moment per unit spin %.5f N m s/rad, linearised %.5f; "
        "side force per unit spin %.5f N s/rad, linearised %.5f\n",
        fins.span, fins.rudder_height, per_spin, -finRollDamping(p, 2.0), side, expected_side);
    EXPECT_NEAR(per_spin, -finRollDamping(p, 2.0), 1e-4 * finRollDamping(p, 2.0));
    EXPECT_NEAR(side, expected_side, 1e-4 * std::abs(expected_side) + 1e-9);
    // The elevator fins' forces normal to the axis cancel (along it both fins' drag grows with |alpha|: the
    // default drag table's kink at zero).
    const Eigen::Vector3d elevator_change = spinning.elevator_loads.lift_W + spinning.elevator_loads.drag_W -
                                            still.elevator_loads.lift_W - still.elevator_loads.drag_W;
    EXPECT_LT(elevator_change.tail<2>().norm() / spin, 1e-3);
  }
}

// The same damping in motion. A vehicle hung at its CG (bail, CG and CB at one station) tows level with its axis
// along the flow, so each fin's inflow angle is zero at rest, and the elevator's forces from a spin cancel: a
// small roll decays as the damped oscillator (I_xx + I_a) phi'' + c phi' + rho g V h_BG phi = 0 with c above,
// phi = phi_0 exp(-sigma t) (cos(w_d t) + sigma / w_d sin(w_d t)), sigma = c / (2 I), w_d^2 = k / I - sigma^2.
// (The rudder's side force yaws the vehicle, which that oscillator leaves out: the moment test above covers it.)
TEST(VehicleRoll, TheElevatorsSpanDampsASmallRollAsTheDampedOscillator)
{
  for (StepperType stepper : { StepperType::kDopri5, StepperType::kImplicit })
  {
    VehicleParams p = rollingVehicle();
    p.cg_from_bail = p.cb_from_bail = 0.0;
    p.elevator_span = 0.1;
    Tow tow = steadyTow(p, stepper);
    tow.sim->advanceTo(30.0);
    const double speed = tow.out().v_cg_W.norm();
    EXPECT_NEAR(tow.out().pitch, 0.0, 1e-4);  // level: the fins' inflow angle is zero
    const double phi0 = 0.02;
    setRoll(tow, phi0, 0.0);
    const Environment& env = tow.sim->data().environment;
    const double inertia = p.inertia_B(0, 0) + p.roll_added_inertia;
    const double stiffness = env.water_density * env.gravity * p.displaced_volume * p.cb_above_cg;
    const double damping = finRollDamping(p, speed);
    const double sigma = damping / (2.0 * inertia), w_d = std::sqrt(stiffness / inertia - sigma * sigma);
    double worst = 0.0;
    for (int i = 1; i <= 1200; ++i)
    {
      const double t = i * 0.005;
      tow.sim->advanceTo(30.0 + t);
      const double expected = phi0 * std::exp(-sigma * t) * (std::cos(w_d * t) + sigma / w_d * std::sin(w_d * t));
      worst = std::max(worst, std::abs(tow.out().roll - expected));
    }
    std::printf(
        "elevator span 0.1 m: c = %.3f N m s/rad, damping ratio %.3f; largest difference from the damped "
        "oscillator over 6 s %.2e rad (%.3f %% of the initial roll)\n",
        damping, damping / (2.0 * std::sqrt(stiffness * inertia)), worst, 100.0 * worst / phi0);
    EXPECT_LT(worst, 1e-3 * phi0);
  }
}

// The elevator's differential delta_a (starboard fin +, port fin -) in the fins' linear range gives the roll moment
// -b C_L |v_p|^2 delta_a about x_b (each fin half the pair's lift constant C_L, b = elevator_span): the vehicle
// heels to port until rho g V h_BG sin(phi) cos(theta) balances it. |v_p| here: the vehicle's speed through the
// (still) water; the inflow angle's cosine (about 6 degrees) is the estimate's error.
TEST(VehicleRoll, TheDifferentialElevatorRollsItToPort)
{
  VehicleParams p = rollingVehicle();
  p.roll_damping = 20.0;
  for (StepperType stepper : { StepperType::kDopri5, StepperType::kImplicit })
  {
    Tow tow = steadyTow(p, stepper);
    EXPECT_FALSE(tow.sim->command(0.0, 0.0, 0.0, 0.05));
    tow.sim->advanceTo(120.0);
    const VehicleOutputs o = tow.out();
    const Environment& env = tow.sim->data().environment;
    const double moment = -p.elevator_span * p.elevator.lift_constant * o.v_cg_W.squaredNorm() * 0.05;
    const double buoyancy_arm = env.water_density * env.gravity * p.displaced_volume * p.cb_above_cg;
    const double expected = std::asin(moment / (buoyancy_arm * std::cos(o.pitch)));
    std::printf("differential 0.05 rad: heel %.4f deg, hand estimate %.4f deg\n", o.roll * 180.0 / kPi,
                expected * 180.0 / kPi);
    EXPECT_DOUBLE_EQ(o.differential, 0.05);
    EXPECT_LT(o.roll, 0.0);
    EXPECT_NEAR(o.roll, expected, 0.015 * std::abs(expected));
  }
  // A differential that is not a number is refused.
  EXPECT_THROW(steadyTow(p, StepperType::kDopri5).sim->command(0.0, 0.0, 0.0, NAN), std::invalid_argument);
}

// The autopilot's roll hold with roll_kp alone adds kp b C_L |v|^2 to the roll's stiffness (the differential's
// moment per radian in the fins' linear range), ticking at 200 Hz. On the level vehicle of the test above (the
// fins' inflow angle zero) the fins also damp the spin by c (finRollDamping): a small roll swings at
// 2 pi / sqrt((rho g V h_BG + kp b C_L |v|^2) / (I_xx + I_a) - sigma^2), sigma = c / (2 (I_xx + I_a)).
TEST(VehicleRoll, TheAutopilotsRollHoldStiffensTheRollByItsGain)
{
  SimulationConfig c;
  c.cable.length = 100.0;
  c.cable.segments = 20;
  c.vehicle = rollingVehicle();
  c.vehicle.cg_from_bail = c.vehicle.cb_from_bail = 0.0;
  auto ship = test::steamingShip(Eigen::Vector2d::Zero(), 0.0, 100);
  AutopilotLoop loop;
  loop.enabled = true;
  loop.rate = 200.0;
  loop.params.track_keeping = false;
  loop.params.roll_hold = true;
  loop.params.roll_kp = 1.0;
  loop.params.roll_kd = 0.0;
  TowRun run(c, ship);
  run.setAutopilot(loop);
  run.start(0.0);
  run.advanceTo(30.0);
  RunState state = run.saveState();
  state.sim.y[state.sim.y.size() - 2] = 0.01;  // rolled 0.01 rad (the roll angle, then the spin, come last)
  run.restore(state);
  const double dt = 0.005;
  std::vector<double> roll;
  for (int i = 1; i <= 500; ++i)  // 2.5 s: the damped swing's first three periods
  {
    run.advanceTo(30.0 + i * dt);
    roll.push_back(run.snapshot().roll);
  }
  const TowSnapshot s = run.snapshot();
  const VehicleParams& p = c.vehicle;
  EXPECT_NEAR(s.pitch, 0.0, 1e-4);  // level
  const double restoring = c.environment.water_density * c.environment.gravity * p.displaced_volume * p.cb_above_cg;
  const double speed = s.vehicle.v_cg_W.norm(), inertia = p.inertia_B(0, 0) + p.roll_added_inertia;
  const double held = loop.params.roll_kp * p.elevator_span * p.elevator.lift_constant * speed * speed;
  const double sigma = finRollDamping(p, speed) / (2.0 * inertia);
  const double expected = 2.0 * kPi / std::sqrt((restoring + held) / inertia - sigma * sigma);
  const double period = meanPeriod(roll, dt);
  std::printf("roll hold: period %.5f s, closed form %.5f s (without the hold %.5f s, undamped %.5f s)\n", period,
              expected, 2.0 * kPi / std::sqrt(restoring / inertia - sigma * sigma),
              2.0 * kPi * std::sqrt(inertia / (restoring + held)));
  EXPECT_NEAR(period, expected, 0.015 * expected);
}

// With nothing to roll it (no restoring, heel or damping moment; an axisymmetric inertia), the vehicle keeps
// its spin p = 0 through a turn while its zero-roll frame turns under it: by Euler's angles (yaw psi, then pitch
// theta nose down, then roll phi) p = dphi/dt - dpsi/dt sin(theta), so phi gains the integral of dpsi sin(theta)
// (a nose-up vehicle turning to port rolls to port), which the outputs' own yaw and pitch give here.
TEST(VehicleRoll, WithoutRollMomentsTheFrameTurnsUnderTheBodyInATurn)
{
  VehicleParams p = rollingVehicle();
  p.cb_above_cg = 0.0;
  for (StepperType stepper : { StepperType::kDopri5, StepperType::kImplicit })
  {
    Tow tow = steadyTow(p, stepper, turningShip(5.0, 80.0));
    const double dt = 0.02;
    VehicleOutputs last = tow.out();
    const double roll0 = last.roll;
    double integral = 0.0, largest_spin = 0.0;
    for (int i = 1; i <= 3000; ++i)
    {
      tow.sim->advanceTo(i * dt);
      const VehicleOutputs o = tow.out();
      integral += std::remainder(o.yaw - last.yaw, 2.0 * kPi) * std::sin(0.5 * (o.pitch + last.pitch));
      largest_spin = std::max(largest_spin, std::abs(o.omega_B.x()));
      last = o;
    }
    std::printf("roll gained %.6f rad, Euler-angle integral %.6f rad; yaw now %.2f deg; largest spin %.2e rad/s\n",
                last.roll - roll0, integral, last.yaw * 180.0 / kPi, largest_spin);
    EXPECT_LT(largest_spin, 1e-9);
    EXPECT_GT(std::abs(integral), 0.02);
    EXPECT_NEAR(last.roll - roll0, integral, 2e-4 * std::abs(integral));
  }
}

// Released in vacuum, a chain with a rolling vehicle whose inertia couples roll to pitch and yaw (products of
// inertia, unequal transverse inertias), spinning and rolled at the start, keeps its energy: the segments'
// 1/2 m v_G^2 + 1/2 (m d^2/12) |w|^2 and the vehicle's 1/2 m v_G^2 + 1/2 w^T I_W w (w with the spin) plus
// their weight's potential. This checks the spin's elimination (P59), its bias -p ds/dt, the gyroscopic term
// and (P58) together: drop any of them and the energy drifts.
TEST(VehicleRoll, AReleasedChainWithARollingVehicleKeepsItsEnergyInVacuum)
{
  VehicleParams p;
  p.roll = VehicleRoll::kFree;
  p.inertia_B << 2.0, 0.0, 0.6, 0.0, 40.0, 0.0, 0.6, 0.0, 61.0;
  CableParams cable;
  cable.segments = 8;
  cable.length = 8.0;
  cable.mass_per_length = 1.5;
  Environment env;
  env.water_density = 0.0;
  NumericsParams num;
  num.stepper = StepperType::kDopri5;
  num.abs_tol = num.rel_tol = 1e-11;
  auto vehicle = std::make_shared<Vehicle>(p, num);
  auto model = std::make_shared<ChainModel>(cable, vehicle, env, num);
  const ShipMotion fixed = constantVelocityShip(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  Tow tow{ vehicle, model, std::make_unique<Simulator>(model, fixed) };
  ChainState start =
      straightChain(*model, Eigen::Vector3d::Zero(), Eigen::Vector3d(1.0, 0.0, -0.577), Eigen::Vector3d::Zero());
  const int n = model->jointCount();
  for (int j = 0; j < n; ++j)
    start.v.col(j) = Eigen::Vector3d(0.0, 0.3 * j / n, 0.0);
  tow.sim->reset(0.0, start);
  setRoll(tow, 0.3, 0.8);
  auto energy = [&]
  {
    const ChainState st = tow.sim->state();
    double e = 0.0;
    Eigen::Vector3d x_f = Eigen::Vector3d::Zero(), v_f = Eigen::Vector3d::Zero();
    for (int i = 0; i < cable.segments; ++i)
    {
      const double d = cable.length / cable.segments, m = cable.mass_per_length * d;
      const Eigen::Vector3d x_a = st.x.col(i), v_a = st.v.col(i);
      const Eigen::Vector3d w = (x_a - x_f).normalized().cross((v_a - v_f) / d);
      e += 0.5 * m * (0.5 * (v_f + v_a)).squaredNorm() + 0.5 * (m * d * d / 12.0) * w.squaredNorm() +
           m * env.gravity * 0.5 * (x_f + x_a).z();
      x_f = x_a;
      v_f = v_a;
    }
    const VehicleOutputs o = tow.out();
    const Eigen::Matrix3d R = o.q_WB.toRotationMatrix();
    return e + 0.5 * p.mass * o.v_cg_W.squaredNorm() +
           0.5 * o.omega_W.dot(R * p.inertia_B * R.transpose() * o.omega_W) + p.mass * env.gravity * o.p_cg_W.z();
  };
  const double e0 = energy();
  double worst = 0.0, largest_roll = 0.0;
  for (int i = 1; i <= 200; ++i)
  {
    tow.sim->advanceTo(0.1 * i);
    worst = std::max(worst, std::abs(energy() - e0) / std::abs(e0));
    largest_roll = std::max(largest_roll, std::abs(tow.out().roll));
  }
  std::printf(
      "released in vacuum with a rolling vehicle: largest relative energy drift over 20 s %.3g (largest "
      "roll %.2f rad)\n",
      worst, largest_roll);
  EXPECT_LT(worst, 1e-7);
  EXPECT_GT(largest_roll, 0.5);  // it did roll
}

// The roll's two states ride through the winch's re-meshing (joints added ahead of them), a saved state (which
// then goes on bit-identically) and a parting (the vehicle side keeps them). Paying out changes the swing (the
// vehicle slows through the water); the same payout with the first segment left to grow instead of split (no
// re-mesh in 20 s) swings alike.
TEST(VehicleRoll, TheRollSurvivesARemeshASavedStateAndAParting)
{
  auto payout = [](double split_above, std::unique_ptr<Tow>& keep)
  {
    WinchParams winch;
    winch.enabled = true;
    winch.max_length = 300.0;
    winch.segment_max_fraction = split_above;
    VehicleParams p = rollingVehicle();
    p.elevator_span = 0.0;  // undamped: it keeps swinging (P57b)
    keep = std::make_unique<Tow>(steadyTow(p, StepperType::kImplicit, nullptr, winch));
    setRoll(*keep, 0.05, 0.0);
    keep->sim->setWinchCommand(1.5);
    double late = 0.0;
    for (int i = 1; i <= 2000; ++i)
    {
      keep->sim->advanceTo(0.01 * i);
      if (i > 1700)
        late = std::max(late, std::abs(keep->out().roll));
    }
    std::printf("after 20 s of payout: %d segments, roll amplitude %.6f rad\n", keep->sim->geometry().segments, late);
    return late;
  };
  std::unique_ptr<Tow> unsplit, remeshed;
  const double reference = payout(10.0, unsplit), late = payout(1.5, remeshed);
  Tow& tow = *remeshed;
  EXPECT_EQ(unsplit->sim->geometry().segments, 20);
  EXPECT_GE(tow.sim->geometry().segments, 23);  // re-meshed
  EXPECT_GT(late, 0.03);                        // still swinging
  EXPECT_NEAR(late, reference, 2e-4);

  const SimulatorState saved = tow.sim->saveState();
  tow.sim->advanceTo(25.0);
  const double roll_a = tow.out().roll, rate_a = tow.out().omega_B.x();
  tow.sim->restoreState(saved);
  tow.sim->advanceTo(25.0);
  EXPECT_EQ(tow.out().roll, roll_a);
  EXPECT_EQ(tow.out().omega_B.x(), rate_a);

  const ElementKinematics before = tow.sim->elementKinematics(tow.sim->geometry().segments);
  tow.sim->part(5);
  const ElementKinematics after = tow.sim->elementKinematics(tow.sim->geometry().segments);
  EXPECT_EQ(after.roll, before.roll);
  EXPECT_EQ(after.roll_rate, before.roll_rate);
  tow.sim->advanceTo(30.0);
  EXPECT_TRUE(std::isfinite(tow.out().roll));
}

// Left level, nothing rolls a symmetric vehicle in a straight tow: roll: free runs as roll: fixed (the spin's
// elimination removes only the moment the fixed body's constraint discards).
TEST(VehicleRoll, LevelInAStraightTowItRunsAsTheFixedVehicle)
{
  VehicleParams free_p = rollingVehicle();
  VehicleParams fixed_p = free_p;
  fixed_p.roll = VehicleRoll::kFixed;
  Tow free_tow = steadyTow(free_p, StepperType::kDopri5), fixed_tow = steadyTow(fixed_p, StepperType::kDopri5);
  for (Tow* tow : { &free_tow, &fixed_tow })
  {
    tow->sim->command(0.0, 0.1, 0.0);  // the elevator pitches it: the axis turns, in its own plane
    tow->sim->advanceTo(60.0);
  }
  const VehicleOutputs a = free_tow.out(), b = fixed_tow.out();
  EXPECT_EQ(a.roll, 0.0);
  EXPECT_NEAR(a.depth, b.depth, 1e-8);
  EXPECT_NEAR(a.pitch, b.pitch, 1e-10);
  EXPECT_LT((free_tow.sim->tensions() - fixed_tow.sim->tensions()).cwiseAbs().maxCoeff(), 1e-6);
}

}  // namespace
}  // namespace tow_sim
