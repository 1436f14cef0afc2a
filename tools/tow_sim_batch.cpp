// tow_sim_batch: runs a scenario faster than real time, without roscore.
//   tow_sim_batch --scenario FILE.yaml --out DIR
// Writes DIR/timeseries.csv, DIR/shapes.csv and DIR/scenario.yaml (the scenario with every default
// filled in). Exit codes: 0 done; 2 bad arguments or scenario; 3 the run diverged (the CSV files then
// hold the run up to the last good output and the error says so); 4 cannot write DIR.
#include <sys/stat.h>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <exception>
#include <fstream>
#include <limits>
#include <memory>
#include <string>

#include "tow_sim/core/equilibrium.h"
#include "tow_sim/core/scenario.h"
#include "tow_sim/core/simulator.h"
#include "tow_sim/core/vehicle.h"

namespace
{
using namespace tow_sim;

int usage(const char* why)
{
  std::fprintf(stderr, "tow_sim_batch: %s\nusage: tow_sim_batch --scenario FILE.yaml --out DIR\n", why);
  return 2;
}

class Progress
{
public:
  explicit Progress(double total) : total_(total), start_(std::chrono::steady_clock::now()) {}
  void update(double done)
  {
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const int percent = static_cast<int>(100.0 * done / total_);
    if (wall < 2.0 || percent < next_)
      return;
    next_ = percent + 5;
    std::fprintf(stderr, "\r[%-20s] %3d%%  t = %.0f s  (%.0fx real time)", std::string(percent / 5, '#').c_str(),
                 percent, done, done / wall);
    shown_ = true;
  }
  void finish()
  {
    if (shown_)
      std::fprintf(stderr, "\n");
  }

private:
  double total_;
  std::chrono::steady_clock::time_point start_;
  int next_ = 0;
  bool shown_ = false;
};
}  // namespace

int main(int argc, char** argv)
{
  std::string scenario_path, out_dir;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--scenario") && i + 1 < argc)
      scenario_path = argv[++i];
    else if (!std::strcmp(argv[i], "--out") && i + 1 < argc)
      out_dir = argv[++i];
    else
      return usage((std::string("unknown argument '") + argv[i] + "'").c_str());
  }
  if (scenario_path.empty() || out_dir.empty())
    return usage("both --scenario and --out are needed");

  Scenario sc;
  try
  {
    sc = loadScenarioFile(scenario_path);
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tow_sim_batch: bad scenario %s: %s\n", scenario_path.c_str(), e.what());
    return 2;
  }
  ::mkdir(out_dir.c_str(), 0755);
  std::ofstream series(out_dir + "/timeseries.csv"), shapes(out_dir + "/shapes.csv"),
      resolved(out_dir + "/scenario.yaml");
  if (!series || !shapes || !resolved)
  {
    std::fprintf(stderr, "tow_sim_batch: cannot write into %s\n", out_dir.c_str());
    return 4;
  }
  resolved << "# " << scenario_path << " with every default filled in, as run by tow_sim_batch\n" << toYaml(sc) << "\n";
  resolved.close();

  double t_reached = 0.0;
  try
  {
    auto vehicle = std::make_shared<Vehicle>(sc.config.vehicle, sc.config.numerics);
    std::shared_ptr<const Seabed> seabed;
    if (sc.config.seabed.type != SeabedParams::Type::kNone)
      seabed = std::make_shared<Seabed>(sc.config.seabed);
    auto model =
        std::make_shared<ChainModel>(sc.config.cable, vehicle, sc.config.environment, sc.config.numerics, seabed);
    const ShipPath path = buildShipPath(sc);
    Simulator sim(
        model, [&path](double t) { return path.tow_point(t); }, sc.config.winch);
    const ShipEndState ship0 = path.tow_point(0.0);
    const Eigen::Matrix3d R0 = Eigen::AngleAxisd(sc.start_heading, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    size_t next_command = 0;
    while (next_command < sc.commands.size() && sc.commands[next_command].t <= 0.0)
    {
      const CommandEvent& c = sc.commands[next_command++];
      sim.command(c.rudder, c.elevator, c.thrust);
      if (sc.config.winch.enabled)
        sim.setWinchCommand(c.payout_rate);
    }
    ChainState start;
    if (sc.start == Scenario::Start::kEquilibrium)
      start = steadyTowEquilibrium(*model, sim.data(), 0.0, ship0.p_W, ship0.v_W).state;
    else if (sc.start == Scenario::Start::kLine)
      start = straightChain(*model, ship0.p_W, R0 * sc.line_direction_S, ship0.v_W);
    else
    {
      start.x = sc.points;
      start.v = sc.points;
      start.v.colwise() = ship0.v_W;
    }
    if (seabed)
      liftAboveSeabed(*seabed, start);  // the equilibrium and the line know nothing of the bottom
    sim.reset(0.0, start);

    std::unique_ptr<DepthAutopilot> autopilot;
    if (sc.autopilot.enabled)
      autopilot = std::make_unique<DepthAutopilot>(sc.autopilot.params);
    size_t next_setpoint = 0;
    long ticks = 0;
    double max_length_error = 0.0;
    // Everything due up to t_target in time order: commands, autopilot setpoints and autopilot ticks
    // (each at its own time), then the simulation to t_target.
    auto runTo = [&](double t_target)
    {
      const double never = std::numeric_limits<double>::infinity();
      for (;;)
      {
        const double t_command = next_command < sc.commands.size() ? sc.commands[next_command].t : never;
        const double t_setpoint = autopilot && next_setpoint < sc.autopilot.setpoints.size()
                                      ? sc.autopilot.setpoints[next_setpoint].t
                                      : never;
        const double t_tick = autopilot ? ticks / sc.autopilot.rate : never;
        const double t_next = std::min({ t_command, t_setpoint, t_tick });
        if (t_next > t_target)
          break;
        max_length_error = std::max(max_length_error, sim.advanceTo(t_next).max_length_error);
        if (t_next == t_command)
        {
          const CommandEvent& c = sc.commands[next_command++];
          if (!autopilot)
            sim.command(c.rudder, c.elevator, c.thrust);
          if (sc.config.winch.enabled)
            sim.setWinchCommand(c.payout_rate);
        }
        else if (t_next == t_setpoint)
        {
          const AutopilotSetpoint& sp = sc.autopilot.setpoints[next_setpoint++];
          if (sp.altitude)
            autopilot->setAltitudeSetpoint(sp.value);
          else
            autopilot->setSetpoint(sp.value);
        }
        else
        {
          ++ticks;
          const VehicleOutputs o = vehicle->outputs(t_next, sim.elementKinematics(sim.geometry().segments),
                                                    sim.data().environment, sim.data().actuators);
          VehicleMeasurement m;
          m.t = t_next;
          m.p_W = o.p_cg_W;
          m.v_W = o.v_cg_W;
          if (seabed)
            m.altitude = seabed->altitude(o.p_cg_W);
          autopilot->addVehicle(m);
          autopilot->addShip(path.poseAt(t_next).head<2>());
          const AutopilotCommand c = autopilot->update(t_next);
          sim.command(c.rudder, c.elevator, c.thrust);
        }
      }
      max_length_error = std::max(max_length_error, sim.advanceTo(t_target).max_length_error);
    };

    series << "t,ship_x,ship_y,ship_z,ship_speed,vehicle_x,vehicle_y,vehicle_z,vehicle_roll,vehicle_pitch,"
              "vehicle_yaw,depth,layback,diversion,diversion_rate,tension_ship,tension_vehicle,rudder,elevator,"
              "thrust,max_length_error,cable_length,payout_rate,vehicle_altitude,seabed_contacts,depth_setpoint\n";
    shapes << "t,joint,x,y,z,tension\n";
    series.precision(10);
    shapes.precision(10);
    AttitudeHold attitude;
    Progress progress(sc.duration);
    const long outputs = std::lround(sc.duration / sc.output_interval);
    const long shapes_every = std::max(1L, std::lround(sc.shape_interval / sc.output_interval));
    for (long i = 0; i <= outputs; ++i)
    {
      const double t = std::min(sc.duration, i * sc.output_interval);
      runTo(t);
      const int nu = sim.geometry().segments;  // the winch may have changed it
      const VehicleOutputs o =
          vehicle->outputs(t, sim.elementKinematics(nu), sim.data().environment, sim.data().actuators);
      const Eigen::Vector3d pose = path.poseAt(t);
      const Eigen::Vector3d heading(std::cos(pose.z()), std::sin(pose.z()), 0.0);
      const ShipEndState tow = sim.shipEnd();
      const Diversion d = lateralDiversion(o.p_cg_W, o.v_cg_W, tow, heading);
      const Eigen::Quaterniond q = attitude.update(o.q_WB * Eigen::Vector3d::UnitX());
      const Eigen::Vector3d x_b = q * Eigen::Vector3d::UnitX();
      const double pitch = -std::asin(std::clamp(x_b.z(), -1.0, 1.0));
      const Eigen::Vector3d y_b = q * Eigen::Vector3d::UnitY();
      const double yaw = std::atan2(-y_b.x(), y_b.y());
      const Eigen::Matrix3Xd joints = sim.jointPositions();
      const Eigen::Matrix3Xd& T = sim.tensions();
      if (!joints.allFinite() || !T.allFinite())
        throw std::runtime_error("non-finite state at t = " + std::to_string(t) + " s");
      series << t << ',' << pose.x() << ',' << pose.y() << ",0," << path.speedAt(t) << ',' << o.p_cg_W.x() << ','
             << o.p_cg_W.y() << ',' << o.p_cg_W.z() << ",0," << pitch << ',' << yaw << ',' << o.depth << ','
             << (tow.p_W - o.p_cg_W).dot(heading) << ',' << d.offset << ',' << d.rate << ',' << T.col(0).norm() << ','
             << T.col(nu).norm() << ',' << o.rudder << ',' << o.elevator << ',' << o.thrust << ',' << max_length_error
             << ',' << sim.cableLength() << ',' << sim.payoutRate() << ',';
      int contacts = 0;
      if (seabed)
      {
        series << seabed->altitude(o.p_cg_W);  // blank without a seabed
        for (int j = 1; j < joints.cols(); ++j)
          contacts += seabed->altitude(joints.col(j)) < 0.0 ? 1 : 0;
      }
      series << ',' << contacts << ',';
      if (autopilot && autopilot->hasSetpoint())
        series << autopilot->setpoint();  // blank without an autopilot
      series << '\n';
      max_length_error = 0.0;
      if (i % shapes_every == 0 || i == outputs)
        for (int j = 0; j < joints.cols(); ++j)
          shapes << t << ',' << j + 1 << ',' << joints(0, j) << ',' << joints(1, j) << ',' << joints(2, j) << ','
                 << (j <= nu ? T.col(j).norm() : 0.0) << '\n';
      t_reached = t;
      progress.update(t);
    }
    progress.finish();
    std::printf("tow_sim_batch: %.0f s simulated; wrote %s/timeseries.csv (%ld rows), shapes.csv, scenario.yaml\n",
                sc.duration, out_dir.c_str(), outputs + 1);
    return 0;
  }
  catch (const std::exception& e)
  {
    series.flush();
    shapes.flush();
    std::fprintf(stderr,
                 "\ntow_sim_batch: the run stopped: %s\ntow_sim_batch: the CSV files in %s are INCOMPLETE: they hold "
                 "the run up to t = %.3f s of %.3f s\n",
                 e.what(), out_dir.c_str(), t_reached, sc.duration);
    return 3;
  }
}
