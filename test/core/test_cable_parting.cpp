// The cable parting at its breaking load (cable.break_at_breaking_load), through the run: it parts where
// the tension first exceeds the load, the ship feels nothing after it, and the vehicle side goes on from a
// free end. Against closed forms: in vacuum the parted chain falls at g (½ g t² below where it was going);
// in water a simple body (no fins, CG, CB and drag centre at its middle) hanging on a buoyant cable parts
// from it at the bail and sinks at its terminal velocity sqrt((W - B) / (c1 L)) (tail first, the Pode
// tangential drag). Without the option the cable holds whatever the tension.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"

namespace tow_sim
{
namespace
{
// A ship at `speed` [m/s] along +x, sampled each second for 400 s.
std::shared_ptr<ShipHistory> steaming(double speed)
{
  auto ship = std::make_shared<ShipHistory>(1.0, 1000);
  for (int i = 0; i <= 400; ++i)
  {
    ShipPose pose;
    pose.x = speed * i;
    pose.speed = speed;
    ship->add(i, Eigen::Vector3d(speed * i, 0.0, 0.0), Eigen::Vector3d(speed, 0.0, 0.0), pose);
  }
  return ship;
}

// Each closed-form test runs on dopri5 and on the implicit stepper (which steps a parted cable's chains
// too: docs/solver.md (S27)), at tolerances far inside the tests' bounds.
const StepperType kSteppers[] = { StepperType::kDopri5, StepperType::kImplicit };

std::string stepperName(StepperType stepper)
{
  return stepper == StepperType::kDopri5 ? "dopri5" : "implicit";
}

void tighten(NumericsParams& numerics, StepperType stepper)
{
  numerics.stepper = stepper;
  numerics.abs_tol = numerics.rel_tol = 1e-10;
  numerics.implicit_position_tol = numerics.implicit_velocity_tol = numerics.implicit_rel_tol = 1e-10;
}

// 100 m of cable in 10 segments in vacuum that parts at its breaking load (set by the test), on `stepper`.
SimulationConfig partingInVacuum(StepperType stepper)
{
  SimulationConfig c;
  c.environment.water_density = 0.0;
  c.cable.length = 100.0;
  c.cable.segments = 10;
  c.cable.break_at_breaking_load = true;
  tighten(c.numerics, stepper);
  return c;
}

TEST(CableParting, InVacuumTheCablePartsAtTheTowPointAndFallsAtG)
{
  for (StepperType stepper : kSteppers)
  {
    SCOPED_TRACE(stepperName(stepper));
    SimulationConfig c = partingInVacuum(stepper);
    c.cable.breaking_load = 1.0;  // below the hanging weight at the top: parts at the first step
    InitialShape hanging;
    hanging.type = InitialShape::Type::kHanging;
    TowRun run(c, steaming(2.0), hanging);
    run.start(0.0);
    const TowSnapshot before = run.snapshot();
    EXPECT_FALSE(before.parting);
    const double top = before.tension_ship;  // the chain's weight below the tow point
    run.advanceTo(2.0);
    const TowSnapshot after = run.snapshot();
    ASSERT_TRUE(after.parting);
    EXPECT_EQ(after.parting->joint, 1);
    EXPECT_LT(after.parting->t, 0.1);
    EXPECT_NEAR(after.parting->tension, top, 1e-6 * top);
    EXPECT_TRUE(run.simulator().parted());
    EXPECT_EQ(run.simulator().stepper(), stepper);                // no fallback to another stepper once parted
    EXPECT_EQ(after.segments, 10);                                // the whole cable left with the vehicle
    EXPECT_EQ(after.tension_ship, 0.0);                           // the ship feels nothing
    EXPECT_LT(after.tensions.cwiseAbs().maxCoeff(), 1e-6 * top);  // a free fall carries no tension
    // Every joint fell ½ g τ² from where it hung (moving on at the ship's 2 m/s), τ from the parting.
    const double tau = 2.0 - after.parting->t;
    for (Eigen::Index j = 0; j < after.joints.cols(); ++j)
    {
      const Eigen::Vector3d expected = before.joints.col(j) + Eigen::Vector3d(2.0 * 2.0, 0.0, -0.5 * 9.81 * tau * tau);
      EXPECT_LT((after.joints.col(j) - expected).norm(), 1e-6) << "joint " << j;
    }
    EXPECT_NEAR(after.tow_point.p_W.x(), 4.0, 1e-12);  // the ship's tow point, not the free end
    EXPECT_THROW(run.saveState(), std::logic_error);   // not saved once parted

    // A restart lays the whole cable out again.
    run.start(2.0);
    EXPECT_FALSE(run.simulator().parted());
    EXPECT_FALSE(run.snapshot().parting);
    EXPECT_EQ(run.snapshot().segments, 10);
  }
}

// The centre of mass of the run's chain and vehicle: each cable element's mass at its middle.
Eigen::Vector3d centreOfMass(const TowSnapshot& s, const SimulationConfig& c)
{
  const double element = c.cable.mass_per_length * c.cable.length / c.cable.segments;
  Eigen::Vector3d sum = c.vehicle.mass * s.vehicle.p_cg_W;
  for (int e = 0; e < s.segments; ++e)
    sum += element * 0.5 * (s.joints.col(e) + s.joints.col(e + 1));
  return sum / (c.vehicle.mass + element * s.segments);
}

TEST(CableParting, AnElasticCablePartsAndItsCentreOfMassFallsAtG)
{
  for (StepperType stepper : kSteppers)
  {
    SCOPED_TRACE(stepperName(stepper));
    // Stretched under its weight, the parted elastic chain springs back as it falls: its joints do not fall
    // at g each, but its centre of mass does (nothing but gravity acts on it in vacuum).
    SimulationConfig c = partingInVacuum(stepper);
    c.cable.axial_stiffness = 2e5;  // [N] 1.4 % static strain at the top
    // Laid out unstretched, it drops and stretches; it parts on the way to twice its static top tension.
    const double weight = (c.cable.mass_per_length * c.cable.length + c.vehicle.mass) * c.environment.gravity;
    c.cable.breaking_load = 1.5 * weight;
    InitialShape hanging;
    hanging.type = InitialShape::Type::kHanging;
    TowRun run(c, steaming(2.0), hanging);
    run.start(0.0);
    const auto cableLength = [](const TowSnapshot& s)
    {
      return (s.joints.leftCols(s.segments + 1).rightCols(s.segments) - s.joints.leftCols(s.segments))
          .colwise()
          .norm()
          .sum();
    };
    Eigen::Vector3d com[3];
    for (int i = 0; i < 3; ++i)
    {
      run.advanceTo(2.0 + 0.5 * i);
      const TowSnapshot s = run.snapshot();
      ASSERT_TRUE(s.parting);
      ASSERT_EQ(s.segments, 10);
      com[i] = centreOfMass(s, c);
    }
    const PartingEvent parting = *run.snapshot().parting;
    std::printf("parted at joint %d at t = %.3f s under %.0f N; cable %.3f m long at 3 s\n", parting.joint, parting.t,
                parting.tension, cableLength(run.snapshot()));
    EXPECT_EQ(parting.joint, 1);
    EXPECT_GT(parting.t, 0.1);  // stretched first
    EXPECT_LT(parting.t, 2.0);
    // p(t) = p0 + v0 t - ½ g t²: its second difference over 0.5 s steps is -g 0.25 m (and 0 across).
    const Eigen::Vector3d second = com[0] - 2.0 * com[1] + com[2];
    std::printf("centre of mass, second difference: %.3e %.3e %.9f m (closed form -%.9f m)\n", second.x(), second.y(),
                second.z(), 0.25 * 9.81);
    EXPECT_LT((second - Eigen::Vector3d(0.0, 0.0, -0.25 * 9.81)).norm(), 1e-6);
    EXPECT_NEAR(com[2].x() - com[1].x(), 2.0 * 0.5, 1e-6);  // the ship's 2 m/s kept
  }
}

TEST(CableParting, PartedDuringAPayoutTheChainFallsAsOneBody)
{
  for (StepperType stepper : kSteppers)
  {
    SCOPED_TRACE(stepperName(stepper));
    // A hanging chain paid out at 1 m/s in vacuum grows heavier until it parts at the tow point, where the
    // cable was running out at the payout rate: every joint, the free end too, moves with the same velocity
    // then, and the parted chain falls as one rigid body (each joint the same displacement, no tension).
    SimulationConfig c = partingInVacuum(stepper);
    c.winch.enabled = true;
    c.cable.breaking_load = (c.cable.mass_per_length * 104.0 + c.vehicle.mass) * c.environment.gravity;
    InitialShape hanging;
    hanging.type = InitialShape::Type::kHanging;
    TowRun run(c, steaming(2.0), hanging);
    run.start(0.0);
    run.setWinchCommand(1.0);
    run.advanceTo(5.0);
    ASSERT_FALSE(run.snapshot().parting);
    const double rate =
        run.snapshot().payout_rate;  // still rising toward 1 m/s: the rate at the parting is in [rate, 1]
    run.advanceTo(10.0);
    const TowSnapshot first = run.snapshot();
    run.advanceTo(11.0);
    const TowSnapshot second = run.snapshot();
    ASSERT_TRUE(second.parting);
    EXPECT_EQ(second.parting->joint, 1);
    EXPECT_GT(second.parting->t, 2.0);  // paid out first
    EXPECT_LT(second.parting->t, 10.0);
    EXPECT_NEAR(second.cable_length, first.cable_length, 1e-12);  // the winch stopped with the parting
    EXPECT_GT(second.cable_length, 103.0);
    const Eigen::Vector3d moved = second.joints.col(0) - first.joints.col(0);
    std::printf("parted at t = %.3f s with %.3f m out; the free end moved (%.4f, %.4f, %.4f) m in 1 s\n",
                second.parting->t, second.cable_length, moved.x(), moved.y(), moved.z());
    for (Eigen::Index j = 1; j < second.joints.cols(); ++j)
      EXPECT_LT((second.joints.col(j) - first.joints.col(j) - moved).norm(), 1e-6) << "joint " << j;
    EXPECT_LT(second.tensions.colwise().norm().maxCoeff(), 1e-6 * c.cable.breaking_load.value());
    EXPECT_NEAR(moved.x(), 2.0, 1e-9);
    // Falling since the parting from the payout's downward rate r: moved.z = -r - g (10 s - t_p) - g / 2.
    const double g = c.environment.gravity, fallen = g * (10.0 - second.parting->t) + 0.5 * g;
    EXPECT_GT(rate, 0.9);
    EXPECT_LT(moved.z(), -rate - fallen + 1e-6);
    EXPECT_GT(moved.z(), -1.0 - fallen - 1e-6);
  }
}

SimulationConfig simpleBodyOnABuoyantCable(StepperType stepper = StepperType::kDopri5)
{
  SimulationConfig c;
  c.cable.length = 50.0;
  c.cable.segments = 10;
  c.cable.mass_per_length = 0.1;  // 0.32 kg/m of water displaced: it floats, so the bail carries the most
  VehicleParams& v = c.vehicle;
  v.tail_from_bail = 1.2;
  v.cg_from_bail = v.cb_from_bail = 0.6;  // CG, CB and the drag's centre at the middle: no moment
  v.nose_from_bail = 0.0;
  v.horizontal_fin_from_bail = v.vertical_fin_from_bail = 0.6;
  v.rudder.lift_constant = v.rudder.drag_constant = 0.0;  // no fins
  v.elevator.lift_constant = v.elevator.drag_constant = 0.0;
  c.numerics.stepper = stepper;
  return c;
}

TEST(CableParting, ASimpleBodyPartsAtTheBailAndSinksAtItsTerminalVelocity)
{
  for (StepperType stepper : kSteppers)
  {
    SCOPED_TRACE(stepperName(stepper));
    SimulationConfig c = simpleBodyOnABuoyantCable(stepper);
    const VehicleParams& v = c.vehicle;
    const double net_weight = (v.mass - c.environment.water_density * v.displaced_volume) * c.environment.gravity;
    c.cable.breaking_load = 0.9 * net_weight;  // the bail's static tension is the body's net weight
    c.cable.break_at_breaking_load = true;
    InitialShape hanging;
    hanging.type = InitialShape::Type::kHanging;
    TowRun run(c, steaming(0.0), hanging);
    run.start(0.0);
    run.advanceTo(25.0);
    const TowSnapshot s = run.snapshot();
    ASSERT_TRUE(s.parting);
    EXPECT_EQ(s.parting->joint, c.cable.segments + 1);  // the bail
    EXPECT_GT(s.parting->tension, c.cable.breaking_load.value());
    EXPECT_EQ(s.segments, 0);  // the body alone goes on
    const double v_terminal = std::sqrt(net_weight / (v.c1 * v.tail_from_bail));
    std::printf("parted at t = %.4f s under %.1f N; sinking at %.6f m/s (closed form %.6f m/s)\n", s.parting->t,
                s.parting->tension, -s.vehicle.v_cg_W.z(), v_terminal);
    EXPECT_NEAR(s.vehicle.v_cg_W.z(), -v_terminal, 1e-4 * v_terminal);
    EXPECT_LT(s.vehicle.v_cg_W.head<2>().norm(), 1e-9);  // straight down, tail first
    EXPECT_GT(s.depth, 50.0 + 20.0 * v_terminal);        // it did sink, and far
    // The whole cable stays on the ship, hanging straight down (by symmetry) and pushing up on the tow point
    // with its net buoyancy (b - w) L: the force on the ship, -T_1, is that, upward (the rigid chain in
    // compression).
    const double area = 0.25 * kPi * c.cable.diameter * c.cable.diameter;
    const double lift = (c.environment.water_density * area - c.cable.mass_per_length) * c.environment.gravity * 50.0;
    ASSERT_EQ(s.ship_side.cols(), c.cable.segments + 1);
    std::printf("the cable left on the ship: T_1 (%.6f, %.6f, %.6f) N, closed form (0, 0, %.6f) N\n", shipPull(s).x(),
                shipPull(s).y(), shipPull(s).z(), -lift);
    EXPECT_NEAR(s.tension_ship, lift, 1e-6 * lift);
    EXPECT_LT((shipPull(s) + Eigen::Vector3d(0.0, 0.0, lift)).norm(), 1e-6 * lift);
    EXPECT_NEAR(s.ship_side(2, c.cable.segments), -50.0, 1e-9);  // still hanging at full length
  }
}

TEST(CableParting, WithoutTheOptionTheCableHoldsWhateverTheTension)
{
  SimulationConfig c = simpleBodyOnABuoyantCable();
  c.cable.breaking_load = 1.0;
  InitialShape hanging;
  hanging.type = InitialShape::Type::kHanging;
  TowRun run(c, steaming(0.0), hanging);
  run.start(0.0);
  run.advanceTo(5.0);
  EXPECT_FALSE(run.snapshot().parting);
  EXPECT_FALSE(run.simulator().parted());
  EXPECT_GT(run.snapshot().tension_vehicle, 100.0);
  // And the option needs a breaking load.
  c.cable.breaking_load.reset();
  c.cable.break_at_breaking_load = true;
  try
  {
    TowRun bad(c, steaming(0.0));
    ADD_FAILURE() << "break_at_breaking_load accepted without breaking_load";
  }
  catch (const std::invalid_argument& e)
  {
    EXPECT_NE(std::string(e.what()).find("cable.break_at_breaking_load: needs cable.breaking_load"), std::string::npos)
        << e.what();
  }
}

}  // namespace
}  // namespace tow_sim
