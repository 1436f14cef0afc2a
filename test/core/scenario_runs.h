// A shipped scenario run to its outputs, for the tests that compare steppers on it (test_implicit_stepping,
// test_tow_point_frame).
#pragma once

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/scenario.h"
#include "tow_sim/scenario/ship_path.h"

namespace tow_sim
{
namespace test
{
// dopri5 at absolute and relative tolerance `tol`: the tight reference the steppers are compared with.
inline NumericsParams dopri5(double tol)
{
  NumericsParams n;
  n.stepper = StepperType::kDopri5;
  n.abs_tol = n.rel_tol = tol;
  return n;
}

// scenarios/NAME.yaml of the source tree.
inline Scenario shippedScenario(const std::string& name)
{
  return loadScenarioFile(std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/" + name + ".yaml");
}

// The scenario's outputs (its commands and autopilot in the loop) with its numerics replaced, on `ship` when
// given (else its scripted ship).
inline std::vector<TowSnapshot> scenarioOutputs(Scenario sc, const NumericsParams& numerics,
                                                std::shared_ptr<ShipHistory> ship = nullptr)
{
  sc.config.numerics = numerics;
  if (!ship)
    ship = std::make_shared<ShipHistory>(buildShipPath(sc));
  TowRun tow(sc.config, ship, sc.initial);
  tow.schedule(sc.commands);
  if (sc.autopilot.enabled)
    tow.setAutopilot(sc.autopilot);
  tow.start(0.0);
  std::vector<TowSnapshot> out;
  const long outputs = std::lround(sc.duration / sc.output_interval);
  for (long i = 0; i <= outputs; ++i)
  {
    tow.advanceTo(std::min(sc.duration, i * sc.output_interval));
    out.push_back(tow.snapshot());
  }
  return out;
}
}  // namespace test
}  // namespace tow_sim
