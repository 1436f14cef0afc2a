// The response to ship motion in the frequency domain (modes.h, motionResponse) against small-amplitude runs in
// the time domain: the tow point heaving (or surging) harmonically behind a ship at 2 m/s, the vehicle's heave and
// pitch and the tension at the ship fitted at the input's frequency over whole periods once the start has died out.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <complex>
#include <cstdio>
#include <memory>
#include <vector>

#include "chain_fixtures.h"
#include "tow_sim/config/config.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/towing_chart.h"

namespace tow_sim
{
namespace
{
struct Measured
{
  std::complex<double> heave, pitch, tension_ship;  // per metre of input
};

// The tow point at U t along x plus A r(t) sin(w t) along `input`, r rising smoothly from 0 to 1 over two periods
// (so the run starts from the exact steady tow), sampled every 0.02 s.
std::shared_ptr<ShipHistory> heavingShip(double speed, double period, double amplitude, const Eigen::Vector3d& input,
                                         double until)
{
  const double w = 2.0 * kPi / period, ramp = 2.0 * period;
  auto ship = std::make_shared<ShipHistory>(1.0, static_cast<size_t>(until / 0.02) + 300);
  for (int k = -100; 0.02 * k <= until + 2.0; ++k)
  {
    const double t = 0.02 * k, tau = std::clamp(t / ramp, 0.0, 1.0);
    const double r = tau * tau * (3.0 - 2.0 * tau), dr = t > 0.0 && t < ramp ? 6.0 * tau * (1.0 - tau) / ramp : 0.0;
    const double u = amplitude * r * std::sin(w * t), du = amplitude * (dr * std::sin(w * t) + r * w * std::cos(w * t));
    const Eigen::Vector3d p = Eigen::Vector3d(speed * t, 0.0, 0.0) + u * input;
    ship->add(t, p, Eigen::Vector3d(speed, 0.0, 0.0) + du * input, ShipPose{ p.x(), p.y(), 0.0, speed, p.z() });
  }
  return ship;
}

// y = a + b t + c cos(w t) + d sin(w t) by least squares; the response to A sin(w t) is A Im(H e^{iwt}), so
// H = (d + i c) / A.
std::complex<double> fitted(const std::vector<double>& t, const std::vector<double>& y, double w, double amplitude)
{
  Eigen::MatrixXd basis(t.size(), 4);
  Eigen::VectorXd rhs(t.size());
  for (size_t k = 0; k < t.size(); ++k)
  {
    basis.row(static_cast<Eigen::Index>(k)) << 1.0, t[k], std::cos(w * t[k]), std::sin(w * t[k]);
    rhs(static_cast<Eigen::Index>(k)) = y[k];
  }
  const Eigen::Vector4d c = basis.colPivHouseholderQr().solve(rhs);
  return std::complex<double>(c(3), c(2)) / amplitude;
}

Measured timeDomain(const SimulationConfig& config, double speed, double period, const Eigen::Vector3d& input)
{
  const double amplitude = 0.05, settle = 2.0 * period + 60.0, until = settle + 4.0 * period;
  TowRun run(config, heavingShip(speed, period, amplitude, input, until));
  EXPECT_EQ(run.start(0.0), "");
  std::vector<double> t, heave, pitch, tension;
  for (int k = 0; 0.05 * k <= until + 1e-9; ++k)
  {
    run.advanceTo(0.05 * k);
    if (0.05 * k < settle - 1e-9)
      continue;
    const TowSnapshot s = run.snapshot();
    t.push_back(s.t);
    heave.push_back(s.vehicle.p_cg_W.z());
    pitch.push_back(s.pitch);
    tension.push_back(s.tension_ship);
  }
  const double w = 2.0 * kPi / period;
  return { fitted(t, heave, w, amplitude), fitted(t, pitch, w, amplitude), fitted(t, tension, w, amplitude) };
}
}  // namespace

TEST(MotionResponse, HeaveAndSurgeResponsesAgreeWithSmallAmplitudeRunsInTheTimeDomain)
{
  const SimulationConfig config = test::shortTightTow();
  const double speed = 2.0;
  const Eigen::Vector3d heave = Eigen::Vector3d::UnitZ(), surge = Eigen::Vector3d::UnitX();
  for (const Eigen::Vector3d& input : { heave, surge })
  {
    const std::vector<double> periods = { 5.0, 10.0, 20.0 };
    const std::vector<MotionResponse> fd =
        steadyTowResponse(config, speed, config.cable.length, Eigen::Vector3d::Zero(), input, periods);
    for (size_t k = 0; k < periods.size(); ++k)
    {
      const Measured td = timeDomain(config, speed, periods[k], input);
      std::printf(
          "%s at %4.1f s: vehicle heave %.4f at %6.1f deg (time domain %.4f at %6.1f deg); tension at the "
          "ship %8.1f N/m at %6.1f deg (%8.1f at %6.1f)\n",
          input.z() > 0.0 ? "heave" : "surge", periods[k], std::abs(fd[k].heave), std::arg(fd[k].heave) * 180.0 / kPi,
          std::abs(td.heave), std::arg(td.heave) * 180.0 / kPi, std::abs(fd[k].tension_ship),
          std::arg(fd[k].tension_ship) * 180.0 / kPi, std::abs(td.tension_ship),
          std::arg(td.tension_ship) * 180.0 / kPi);
      std::printf("  vehicle pitch %.4f rad/m at %6.1f deg (time domain %.4f at %6.1f deg)\n", std::abs(fd[k].pitch),
                  std::arg(fd[k].pitch) * 180.0 / kPi, std::abs(td.pitch), std::arg(td.pitch) * 180.0 / kPi);
      // Amplitude and phase at once: the complex difference within 2 % of the amplitude.
      EXPECT_LT(std::abs(td.heave - fd[k].heave), 0.02 * std::abs(fd[k].heave)) << periods[k];
      EXPECT_LT(std::abs(td.pitch - fd[k].pitch), 0.02 * std::abs(fd[k].pitch)) << periods[k];
      EXPECT_LT(std::abs(td.tension_ship - fd[k].tension_ship), 0.02 * std::abs(fd[k].tension_ship)) << periods[k];
    }
  }
}

// motionResponses (the joints' displacements, each element linearised alone, a sparse solve per period) against
// motionResponsesDense (angle coordinates that keep every length, each differenced through the whole solve, a
// dense solve): two formulations of the same small motions, on a tow in a cross current and on a two-part tow
// with sections, a clump, a float and a winged depressor; heave, surge, sway and pitch inputs.
TEST(MotionResponse, TheSparsePathAgreesWithTheDenseLinearisation)
{
  SimulationConfig cross = test::shortTightTow();
  cross.cable.segments = 30;
  const SimulationConfig two_part = loadConfig(YAML::Load(test::kSmallTwoPartTow));
  const std::vector<double> periods = { 2.0, 5.0, 12.0, 30.0, 80.0 };
  const std::vector<Eigen::Vector3d> inputs = { Eigen::Vector3d::UnitZ(), Eigen::Vector3d::UnitX(),
                                                Eigen::Vector3d::UnitY(),
                                                towPointMotion("pitch", Eigen::Vector3d(-30.0, 0.0, -3.0)) };
  const std::pair<const SimulationConfig*, Eigen::Vector3d> cases[] = { { &cross, Eigen::Vector3d(0.1, 0.3, 0.0) },
                                                                        { &two_part, Eigen::Vector3d::Zero() } };
  double worst = 0.0;
  for (const auto& [config, current] : cases)
  {
    const std::unique_ptr<TowRun> run = steadyTowRun(*config, 1.5, config->cable.length, current);
    const Simulator& sim = run->simulator();
    const ChainState state = sim.state();
    const auto response = [&](auto path)
    {
      return path(run->model(), sim.geometry(), sim.data(), sim.time(), sim.firstJoint(), state.x, state.v, inputs,
                  periods, 0.5, 1e-6);
    };
    const auto sparse = response(motionResponses), dense = response(motionResponsesDense);
    using Field = std::complex<double> MotionResponse::*;
    for (Field field : { &MotionResponse::surge, &MotionResponse::sway, &MotionResponse::heave, &MotionResponse::pitch,
                         &MotionResponse::tension_ship, &MotionResponse::tension_vehicle })
      for (size_t i = 0; i < inputs.size(); ++i)
      {
        // Against the largest of that output over the inputs and periods (the differencing's noise is of it),
        // and for the motions at least the input's own 1 m (or 1 rad) per unit.
        const bool tension = field == &MotionResponse::tension_ship || field == &MotionResponse::tension_vehicle;
        double scale = tension ? 0.0 : 1.0;
        for (const std::vector<MotionResponse>& by_period : dense)
          for (const MotionResponse& r : by_period)
            scale = std::max(scale, std::abs(r.*field));
        for (size_t k = 0; k < periods.size(); ++k)
          worst = std::max(worst, std::abs(sparse[i][k].*field - dense[i][k].*field) / scale);
        for (size_t k = 0; k < periods.size(); ++k)
          EXPECT_LT(std::abs(sparse[i][k].*field - dense[i][k].*field), 1e-6 * scale)
              << "input " << i << ", period " << periods[k] << " s: " << sparse[i][k].*field << " against "
              << dense[i][k].*field;
      }
  }
  std::printf("the sparse path's largest difference from the dense one: %.1e of its scale\n", worst);
}

TEST(MotionResponse, BadPeriodsAndInputsAreRefused)
{
  SimulationConfig config;
  config.cable.length = 100.0;
  config.cable.segments = 10;
  EXPECT_THROW(steadyTowResponse(config, 2.0, 100.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::UnitZ(), { 0.0 }),
               std::invalid_argument);
  EXPECT_THROW(steadyTowResponse(config, 2.0, 100.0, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), { 5.0 }),
               std::invalid_argument);
}

}  // namespace tow_sim
