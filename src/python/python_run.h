// A tow run driven from Python (tow_sim.Run, docs/python.md): a scenario's run as the batch runs it, or a
// configuration's behind a ship on a straight course or on a track given sample by sample. Stepping releases
// the GIL, so runs in several threads advance in parallel.
#pragma once

#include <pybind11/pybind11.h>

#include <memory>
#include <string>
#include <vector>

#include "tow_sim/scenario/batch_run.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim::python
{
class PythonRun
{
public:
  // The scenario's run, started as tow_sim_batch starts it (its first output at first_output).
  explicit PythonRun(const Scenario& scenario);
  // The configuration behind the scripted ship on a straight course at `speed` [m/s] and `heading` [rad] for
  // `duration` [s], the tow point at tow_point_S [m] in the ship frame, with the commands scheduled.
  PythonRun(const SimulationConfig& config, double speed, double heading, double duration,
            const Eigen::Vector3d& tow_point_S, const std::vector<CommandEvent>& commands);
  // The configuration behind a ship given as tow-point samples (world): times t [s], positions [m], velocities
  // [m/s] and headings [rad], started at the first time; add_ship_sample() extends the track.
  PythonRun(const SimulationConfig& config, const std::vector<double>& t, const Eigen::MatrixX3d& position,
            const Eigen::MatrixX3d& velocity, const std::vector<double>& heading,
            const std::vector<CommandEvent>& commands);

  void addShipSample(double t, const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, double heading);
  // Integrates to t; std::invalid_argument past the ship's track (the scenario's duration, the newest sample).
  void advanceTo(double t);
  TowSnapshot snapshot();
  // The timeseries rows at the output times every `every` [s] after the last one written (the first call: from
  // the run's start) up to `until` [s], as tow_sim_batch writes them.
  std::vector<std::vector<double>> run(double until, double every);
  std::string header() const { return timeseriesHeader(config().bodies.size()); }

  TowRun& tow() { return *run_.run; }
  const SimulationConfig& config() const { return run_.run->config(); }
  const std::string& startWarning() const { return run_.start_warning; }
  double end() const { return end_; }

private:
  void requireWithinTrack(double t) const;

  StartedScenario run_;
  double end_ = 0.0;           // [s] the ship's track ends here (the newest sample)
  double last_output_ = -1.0;  // [s] the last output time run() wrote (< 0: none)
};

// Registers tow_sim.Run.
void bindRun(pybind11::module_& m);

}  // namespace tow_sim::python
