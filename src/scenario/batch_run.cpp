#include "tow_sim/scenario/batch_run.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <sstream>

#include "tow_sim/config/config.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/io/saved_state.h"
#include "tow_sim/scenario/ship_path.h"
#include "tow_sim/scenario/towing_chart.h"

namespace tow_sim
{
std::string timeseriesHeader(size_t bodies)
{
  std::string header =
      "t,ship_x,ship_y,ship_z,ship_speed,vehicle_x,vehicle_y,vehicle_z,vehicle_roll,vehicle_pitch,vehicle_yaw,depth,"
      "layback,diversion,diversion_rate,tension_ship,tension_vehicle,rudder,elevator,thrust,max_length_error,"
      "cable_length,payout_rate,vehicle_altitude,seabed_contacts,depth_setpoint,tension_ship_min,tension_ship_max,"
      "tension_vehicle_min,tension_vehicle_max,snap_count,max_strain";
  for (size_t i = 1; i <= bodies; ++i)
    for (const char* column : { "_x", "_y", "_depth", "_tension_above", "_tension_below" })
      header += ",body" + std::to_string(i) + column;
  return header;
}

std::string shapesHeader(bool sections)
{
  return sections ? "t,joint,x,y,z,tension,slack,section" : "t,joint,x,y,z,tension,slack";
}

std::vector<double> timeseriesValues(const TowSnapshot& s)
{
  const double blank = std::numeric_limits<double>::quiet_NaN();
  const VehicleOutputs& o = s.vehicle;
  std::vector<double> v = { s.t,
                            s.ship.x,
                            s.ship.y,
                            s.ship.z,
                            s.ship.speed,
                            o.p_cg_W.x(),
                            o.p_cg_W.y(),
                            o.p_cg_W.z(),
                            s.roll,  // vehicle_roll: 0 unless vehicle.roll is free
                            s.pitch,
                            s.yaw,
                            s.depth,
                            s.layback,
                            s.diversion.offset,
                            s.diversion.rate,
                            s.tension_ship,
                            s.tension_vehicle,
                            o.rudder,
                            o.elevator,
                            o.thrust,
                            s.max_length_error,
                            s.cable_length,
                            s.payout_rate,
                            s.seabed_present ? s.vehicle_altitude : blank,  // blank without a seabed
                            static_cast<double>(s.contacts),
                            s.depth_setpoint ? *s.depth_setpoint : blank,  // blank without an autopilot
                            s.tension_ship_range.min,
                            s.tension_ship_range.max,
                            s.tension_vehicle_range.min,
                            s.tension_vehicle_range.max,
                            static_cast<double>(s.snap_count),
                            s.max_strain };
  for (const BodyOutput& b : s.bodies)
  {
    const bool on = b.joint >= 0;  // blank once a parting took it off the vehicle side
    for (double x : { b.p_W.x(), b.p_W.y(), b.depth, b.tension_above.norm(), b.tension_below.norm() })
      v.push_back(on ? x : blank);
  }
  return v;
}

std::string timeseriesRow(const TowSnapshot& s, int precision)
{
  std::ostringstream row;
  row.precision(precision);
  const std::vector<double> values = timeseriesValues(s);
  for (size_t i = 0; i < values.size(); ++i)
  {
    if (i > 0)
      row << ',';
    if (!std::isnan(values[i]))
      row << values[i];
  }
  return row.str();
}

const char* eventsHeader()
{
  return "t,event,joint,tension";
}

std::string eventsRows(const BatchResult& result)
{
  std::ostringstream rows;
  rows.precision(10);
  if (result.parting)
    rows << result.parting->t << ",parting," << result.parting->joint << ',' << result.parting->tension << '\n';
  return rows.str();
}

std::string shapesRows(const TowSnapshot& s, bool sections, int precision)
{
  std::ostringstream rows;
  rows.precision(precision);
  for (Eigen::Index j = 0; j < s.joints.cols(); ++j)
  {
    rows << s.t << ',' << j + 1 << ',' << s.joints(0, j) << ',' << s.joints(1, j) << ',' << s.joints(2, j) << ','
         << (j <= s.segments ? s.tensions.col(j).norm() : 0.0) << ','
         << (j <= s.segments && s.slack[static_cast<size_t>(j)] ? 1 : 0);
    if (sections)  // the segment aft of the joint's; -1 at the bail and the tail (the vehicle)
      rows << ',' << (j < s.segments ? s.segment_section[static_cast<size_t>(j)] : -1);
    rows << '\n';
  }
  return rows.str();
}

namespace
{
// The run from the scenario's saved state; returns the index of its first output.
long restoreInitialState(const Scenario& sc, const ShipHistory& ship, TowRun& run, std::string& warning)
{
  RunState state = readRunState(sc.initial.path);
  if (!sc.initial.any_configuration)
    requireSameConfiguration(state.configuration, sc.config, "initial_state.any_configuration: true loads it");
  const double t = state.reached;
  if (!(t >= 0.0 && t <= sc.duration))
    throw std::invalid_argument("the state's time " + std::to_string(t) +
                                " s is not within the run's [0, simulation.duration = " + std::to_string(sc.duration) +
                                " s]");
  const ShipEndState tow = ship.towPoint(state.sim.t);
  const double heading = ship.pose(state.sim.t).heading;
  const double moved = (state.tow_point.p_W - tow.p_W).norm();
  const double turned = std::abs(std::remainder(state.heading - heading, 2.0 * kPi));
  if (moved > 1e-9 * std::max(1.0, tow.p_W.norm()) || turned > 1e-12)
  {
    state = relocate(state, state.sim.t, tow, heading);
    std::ostringstream os;
    os << "initial_state: the state was saved with the tow point " << moved << " m away and the heading " << turned
       << " rad off this scenario's ship: placed behind it at t = " << t << " s";
    warning = os.str();
  }
  run.restore(state);
  return static_cast<long>(std::ceil(t / sc.output_interval - 1e-9));
}

// TowRun::advanceTo, and on its failure the parting it may have gone through first (still an event).
void advanceKeepingEvents(TowRun& run, double t, BatchResult& result)
{
  try
  {
    run.advanceTo(t);
  }
  catch (...)
  {
    result.parting = run.simulator().partingEvent();
    throw;
  }
}
}  // namespace

namespace
{
// The scenario's autopilot, with the winch's feed-forward from the towing chart's planner (tow_sim_chart
// --target-depth).
AutopilotLoop autopilotLoop(const Scenario& sc)
{
  AutopilotLoop loop = sc.autopilot;
  const SimulationConfig config = sc.config;
  loop.cable_out_plan = [config](double depth, double speed)
  {
    const CableOutPlan plan = planCableOut(config, depth, speed, config.environment.current_W, config.winch.min_length,
                                           config.winch.max_length);
    return plan.reachable ? plan.cable_out : std::numeric_limits<double>::quiet_NaN();
  };
  return loop;
}
}  // namespace

StartedScenario startScenario(const Scenario& sc)
{
  StartedScenario r;
  r.ship = std::make_shared<ShipHistory>(buildShipPath(sc));
  r.run = std::make_unique<TowRun>(sc.config, r.ship, sc.initial);
  r.run->schedule(sc.commands);
  if (sc.autopilot.enabled)
    r.run->setAutopilot(autopilotLoop(sc));
  if (sc.initial.type != InitialShape::Type::kFile)
  {
    r.start_warning = r.run->start(0.0);
    return r;
  }
  try
  {
    r.first_output = restoreInitialState(sc, *r.ship, *r.run, r.start_warning);
  }
  catch (const std::exception& e)
  {
    throw BadInitialState("initial_state.path " + sc.initial.path + ": " + e.what());
  }
  return r;
}

void runScenario(const Scenario& sc, std::ostream& series, std::ostream& shapes, BatchResult& result,
                 const std::function<void(double t)>& progress, const SaveStateSink& save_state, int precision,
                 const SnapshotSink& observe)
{
  result = BatchResult();
  StartedScenario started = startScenario(sc);
  TowRun& run = *started.run;
  result.start_warning = started.start_warning;
  const long first = started.first_output;

  const bool sections = !sc.config.sections.empty();
  series << timeseriesHeader(sc.config.bodies.size()) << '\n';
  shapes << shapesHeader(sections) << '\n';
  const long outputs = std::lround(sc.duration / sc.output_interval);
  const long shapes_every = std::max(1L, std::lround(sc.shape_interval / sc.output_interval));
  std::size_t next_save = 0;
  for (long i = first; i <= outputs; ++i)
  {
    const double t = std::min(sc.duration, i * sc.output_interval);
    advanceKeepingEvents(run, t, result);
    for (; next_save < sc.save_state_at.size() && sc.save_state_at[next_save] <= t + 1e-9 * std::max(1.0, t);
         ++next_save)
      if (save_state && !run.simulator().parted() && sc.save_state_at[next_save] >= t - 1e-9 * std::max(1.0, t))
      {
        RunState state = run.saveState();
        state.configuration = configurationKeys(sc.config);
        save_state(t, state);
      }
    const TowSnapshot s = run.snapshot();
    result.parting = s.parting;
    series << timeseriesRow(s, precision) << '\n';
    if (observe)
      observe(s);
    if (i % shapes_every == 0 || i == outputs)
      shapes << shapesRows(s, sections, precision);
    result.t_reached = t;
    result.rows = i - first + 1;
    if (progress)
      progress(t);
  }
}

}  // namespace tow_sim
