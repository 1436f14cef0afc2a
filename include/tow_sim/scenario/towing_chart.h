// Towing charts (tow_sim_chart): the steady tow of a configuration over a grid of ship speeds and lengths
// of cable out, each point the steady-tow equilibrium a tow run starts from (TowRun, the batch runner's
// start). (Library tow_sim_scenario.)
#pragma once

#include <Eigen/Core>
#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "tow_sim/config/config.h"
#include "tow_sim/core/analysis/modes.h"
#include "tow_sim/core/analysis/strumming.h"
#include "tow_sim/core/run/tow_run.h"

namespace tow_sim
{
// One point of a chart. Where no equilibrium was found the values are NaN and `error` says why.
struct ChartPoint
{
  double speed = 0.0;            // [m/s] ship, through the ground, along +x
  double cable_out = 0.0;        // [m]
  double current = 0.0;          // [m/s] magnitude of the uniform current
  bool converged = false;        // an equilibrium was found
  double depth = 0.0;            // [m] vehicle CG below the surface
  double layback = 0.0;          // [m] vehicle CG behind the tow point
  double tension_ship = 0.0;     // [N] |T_1|
  double tension_vehicle = 0.0;  // [N] |T_{nu+1}|
  double ship_angle = 0.0;       // [deg] the first segment below the horizontal
  double max_tension = 0.0;      // [N] the largest |T| along the cable
  std::string error;
};

// `config` with cable_out [m] of cable: the first section (the whole cable without sections) paid out or
// hauled in to it, in segments of its length (at least one), the bodies aft of it moving with the cable. Throws
// std::invalid_argument for a cable out not longer than the sections aft of the first, or a body inside it.
void payOutTo(SimulationConfig& config, double cable_out);

// The steady tow of `config` with cable_out [m] of cable (as chartPoint below) as the tow run starts it: its
// snapshot at t = 0. Throws std::invalid_argument for a cable out payOutTo refuses or a configuration the run
// refuses, std::runtime_error when no equilibrium was found (the reason in what()).
TowSnapshot steadyTow(const SimulationConfig& config, double speed, double cable_out, const Eigen::Vector3d& current_W);
// The run that holds that steady tow (calm water, no winch, no seabed), for analyses of its state.
std::unique_ptr<TowRun> steadyTowRun(const SimulationConfig& config, double speed, double cable_out,
                                     const Eigen::Vector3d& current_W);
// The natural modes about that steady tow (modes.h; tow_sim_modes), in ascending natural frequency: every one
// (naturalModes, dense) with count 0, else the `count` lowest (lowestModes, O(nu) per iteration). Throws as
// steadyTow.
std::vector<Mode> steadyTowModes(const SimulationConfig& config, double speed, double cable_out,
                                 const Eigen::Vector3d& current_W, std::size_t count = 0);
// The steady response about that steady tow to the tow point moving harmonically along `input` (a translation
// [m] per unit input), at each of `periods` [s] (modes.h, motionResponse; tow_sim_response). Throws as
// steadyTowModes, and std::invalid_argument for a period outside (0, 1e5] s or a zero input.
std::vector<MotionResponse> steadyTowResponse(const SimulationConfig& config, double speed, double cable_out,
                                              const Eigen::Vector3d& current_W, const Eigen::Vector3d& input,
                                              const std::vector<double>& periods);
// The same for several inputs: one steady tow and one linearisation; [input][period].
std::vector<std::vector<MotionResponse>> steadyTowResponses(const SimulationConfig& config, double speed,
                                                            double cable_out, const Eigen::Vector3d& current_W,
                                                            const std::vector<Eigen::Vector3d>& inputs,
                                                            const std::vector<double>& periods);

// Where that steady tow's cable sheds vortices and which string modes the shedding can lock into, with the
// lock-in band f_s (1 +- bandwidth) (strumming.h; tow_sim_strumming). Throws as steadyTow, and
// std::invalid_argument for a bandwidth outside [0, 1).
StrummingAnalysis steadyTowStrumming(const SimulationConfig& config, double speed, double cable_out,
                                     const Eigen::Vector3d& current_W, double bandwidth);

// The tow point's translation [m] per unit of the ship's motion `input`, world at heading 0: heave (0, 0, 1), surge
// (1, 0, 0), sway (0, 1, 0) per metre, or pitch (REP-103, bow down positive) y x tow_point_S per radian,
// tow_point_S [m] the tow point in the ship frame from its reference point. std::invalid_argument otherwise.
Eigen::Vector3d towPointMotion(const std::string& input, const Eigen::Vector3d& tow_point_S);

// The steady tow of `config` with cable_out [m] of cable (segments of the configuration's length, at least
// one), the ship at speed [m/s] along +x and the uniform current current_W [m/s] (world), the tow point
// at the surface.
ChartPoint chartPoint(const SimulationConfig& config, double speed, double cable_out, const Eigen::Vector3d& current_W);

// Every point of speeds x cable_outs (speed varying fastest).
std::vector<ChartPoint> towingChart(const SimulationConfig& config, const std::vector<double>& speeds,
                                    const std::vector<double>& cable_outs, const Eigen::Vector3d& current_W);

// The cable out that puts the vehicle at target_depth [m] at `speed` [m/s] (with current_W), between
// min_length and max_length [m] (the winch's limits): bisection on the chart's depth, which grows with the
// cable out, to `tolerance` [m] of depth. Unreachable (no equilibrium at an end, or the target outside
// the depths of the two limits) is reported with the reachable range in `reason`.
struct CableOutPlan
{
  bool reachable = false;
  double cable_out = 0.0;  // [m]
  ChartPoint point;        // the steady tow with that cable out
  std::string reason;      // why not, when unreachable
};
CableOutPlan planCableOut(const SimulationConfig& config, double target_depth, double speed,
                          const Eigen::Vector3d& current_W, double min_length, double max_length,
                          double tolerance = 0.01);

// The ship speeds [m/s] within [slowest_allowed, fastest_allowed] that keep the vehicle on cable_out [m]
// between depth_min and depth_max [m]: the depth falls as the speed rises, so the window's ends are where
// it crosses depth_max (slowest) and depth_min (fastest), found by bisection to 1e-4 m/s.
struct SpeedWindow
{
  bool found = false;
  double slowest = 0.0, fastest = 0.0;  // [m/s]
  std::string reason;
};
SpeedWindow speedWindow(const SimulationConfig& config, double cable_out, double depth_min, double depth_max,
                        const Eigen::Vector3d& current_W, double slowest_allowed = 0.1, double fastest_allowed = 10.0);

// FROM:TO:STEP [the unit's] as a list (TO included within STEP/1000); throws std::invalid_argument naming
// `option` for a malformed range, STEP <= 0, FROM > TO or more than 10000 values.
std::vector<double> parseRange(const std::string& text, const std::string& option);
// One number: parseRange's errors, and a range (FROM:TO:STEP) refused, naming `option`.
double parseSingle(const std::string& text, const std::string& option);

const char* chartHeader();
void writeChartRow(std::ostream& out, const ChartPoint& p);

}  // namespace tow_sim
