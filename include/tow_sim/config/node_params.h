// The ROS nodes' own parameters (besides the configuration's sections), with their tables (param_table.h):
// tow_sim_node's and depth_autopilot_node's. ROS-free, so they are validated, documented and tested without
// roscore; the nodes read them from their private namespace through the same YAML reader.
#pragma once

#include <yaml-cpp/yaml.h>
#include <Eigen/Core>
#include <string>
#include <vector>

#include "tow_sim/core/param_table.h"
#include "tow_sim/core/run/depth_autopilot.h"

namespace tow_sim
{
struct NodeParams
{
  std::string world_frame = "odom";                                // frame of ship/odom, current and every output
  std::string vehicle_frame = "tow_vehicle";                       // tf child frame of the vehicle CG
  Eigen::Vector3d tow_point_S = Eigen::Vector3d(-20.0, 0.0, 0.0);  // [m] tow point in the ship frame (FLU)
  double physics_rate = 50.0;                                      // [Hz] integration ticks
  double publish_rate = 10.0;                                      // [Hz] state, markers, odometry, tf
  double odom_delay = 0.2;                                         // [s] the simulation runs this far behind the clock
  double max_command_lag = 0.1;    // [s] cap on an implicit step: commands act within it
  double max_tick_wall = 0.05;     // [s] wall time a physics tick aims to stay within (at least one step)
  double max_extrapolation = 1.0;  // [s] past the newest odometry, then hold
  double max_ship_speed = 25.0;    // [m/s] odometry implying a faster jump is rejected; velocities from positions
                                   // are clamped to it
  int reacquire_after = 5;         // [messages] consistent ones away from the track in a row re-acquire the ship
  double max_odom_age = 10.0;      // [s] odometry stamped earlier than now - this is rejected
  std::string initial_shape = "equilibrium";  // equilibrium | line | hanging
  double initial_angle = 0.5;                 // [rad] below the horizontal for "line" (and the fallback)
  double tension_color_max = 5000.0;          // [N] red end of the cable colour scale
  double force_arrow_scale = 0.01;            // [m/N] length of the tow-force arrow per newton
  double cable_marker_width = 0.5;            // [m] drawn width of the cable line
  double vehicle_diameter = 0.3;              // [m] drawn hull diameter
  double ship_length = 60.0;                  // [m] drawn ship hull outline, about the odometry's reference point
  double ship_beam = 12.0;                    // [m]
  double vehicle_marker_scale = 1.0;          // [-] the vehicle's markers drawn this many times their size
  double label_height = 3.0;                  // [m] the ship's label (the vehicle's: half of it)
  std::string view_frame = "tow_view";        // tf frame midway between tow point and vehicle ("" : none)
  double trail_duration = 300.0;              // [s] drawn tracks of ship and vehicle (0: none)
  bool print_status = false;                  // print a status line each second (headless demo)
};
const ParamTable<NodeParams>& nodeParams();
// The table's ranges and the frames (non-empty, different); names "<prefix><key>".
void validate(const NodeParams& params, const std::string& prefix);

struct AutopilotNodeParams
{
  DepthAutopilotParams controller;
  double rate = 10.0;                // [Hz] fins/command
  std::string world_frame = "odom";  // frame of both odometries
  // tow_sim_node's ~plan_cable_out, asked for the winch's feed-forward at each depth setpoint ("": none).
  std::string plan_service = "tow_sim/plan_cable_out";
  bool setpoint_marker = true;  // an interactive marker in rviz to drag the depth setpoint
};
const ParamTable<AutopilotNodeParams>& autopilotNodeParams();
void validate(const AutopilotNodeParams& params, const std::string& prefix);

// ship_motion_node: a scripted ship (the scenarios' manoeuvre law) publishing ship/odom and tf.
struct ShipMotionParams
{
  std::string manoeuvre = "straight";      // straight | turn | zigzag | speed_change | waypoints
  double speed = 2.0;                      // [m/s] through the water, negative astern
  double speed_2 = 1.0;                    // [m/s] speed_change: the speed after the change
  double change_time = 120.0;              // [s] speed_change: when it begins
  double change_duration = 30.0;           // [s] speed_change: over this time
  double turn_radius = 200.0;              // [m] turn, zigzag, waypoints: positive to port; |.| in [10, 1e5]
  double turn_start = 120.0;               // [s] turn, zigzag: straight until then
  double zigzag_period = 240.0;            // [s] zigzag: one full swing
  double waypoint_radius = 30.0;           // [m] waypoints: reached within this
  std::vector<Eigen::Vector2d> waypoints;  // [m] world x, y (the waypoints manoeuvre needs one at least)
  double heading = 0.0;                    // [rad] at the start, from +x toward +y
  double rate = 20.0;                      // [Hz] ship/odom and tf
  std::string world_frame = "odom";
  std::string ship_frame = "ship";
  bool wave_response = true;  // heave, roll and pitch in the configuration's waves (false: level)
  std::string rao_file;       // the ship's RAOs as CSV ("": the generic vessel's)
};
const ParamTable<ShipMotionParams>& shipMotionParams();
void validate(const ShipMotionParams& params, const std::string& prefix);
// From a YAML mapping (the node's private namespace as YAML): the table's keys and the waypoints, then
// validate(). Errors name "<name>.<key>"; keys of other readers are left alone.
ShipMotionParams readShipMotionParams(const YAML::Node& params, const std::string& name);

// gnss_ship_node: a survey vessel's GNSS (sensor_msgs/NavSatFix and a heading) as ship/odom in the
// local ENU frame about a geodetic origin (docs/own_ship.md).
struct GnssShipParams
{
  bool origin_from_first_fix = true;                    // the first good fix is the origin; else the three keys below
  double origin_latitude = 0.0;                         // [deg] WGS84, north positive
  double origin_longitude = 0.0;                        // [deg] WGS84, east positive
  double origin_altitude = 0.0;                         // [m] above the WGS84 ellipsoid
  Eigen::Vector3d antenna_S = Eigen::Vector3d::Zero();  // [m] the GNSS antenna in the ship frame (FLU)
  double smoothing_time = 2.0;                          // [s] the tracker's time constant (0: none)
  bool use_altitude = false;                            // the ship's z from the altitude; else z = 0
  std::string heading_convention = "enu";  // enu: yaw from east toward north; compass: from north, clockwise
  double max_heading_age = 2.0;            // [s] a fix needs a heading at most this much older or newer
  std::string world_frame = "odom";
  std::string ship_frame = "ship";
  bool publish_tf = true;  // the tf world -> ship
};
const ParamTable<GnssShipParams>& gnssShipParams();
void validate(const GnssShipParams& params, const std::string& prefix);

// tow_nav_node: the towfish's position from a survey vessel's sensor topics with the cable model (tow_nav.h,
// docs/survey.md). The towing configuration and its `nav:` section are read beside these keys.
struct TowNavNodeParams
{
  bool origin_from_first_fix = true;           // the first good fix is the origin; else the three keys below
  double origin_latitude = 0.0;                // [deg] WGS84, north positive
  double origin_longitude = 0.0;               // [deg] WGS84, east positive
  double origin_altitude = 0.0;                // [m] above the WGS84 ellipsoid
  std::string heading_convention = "enu";      // enu: yaw from east toward north; compass: from north, clockwise
  std::string depth_source = "depth";          // depth: survey/fish/depth; pressure: survey/fish/pressure
  double atmospheric_pressure = 101325.0;      // [Pa] taken off the fish's absolute pressure
  double hold = 1.5;                           // [s] a measurement waits this long for the others of its instant
  double max_ship_gap = 2.0;                   // [s] a USBL fix needs a ship fix and heading this near its stamp
  double rate = 10.0;                          // [Hz] the estimate's updates and outputs
  std::string world_frame = "odom";            // ENU about the origin: the estimate's frame
  std::string ship_frame = "ship";             // the USBL fixes' frame
  std::string fish_frame = "tow_vehicle_nav";  // the estimate's child frame (tf)
  bool publish_tf = true;                      // the tf world_frame -> fish_frame
};
const ParamTable<TowNavNodeParams>& towNavNodeParams();
void validate(const TowNavNodeParams& params, const std::string& prefix);
// From a YAML file's mapping (tow_sim_nav --nav-config): unknown keys refused; errors name `name`.key.
TowNavNodeParams readTowNavNodeParams(const YAML::Node& params, const std::string& name);

// tow_sim_replay: a batch run's shapes replayed into rviz on its own clock.
struct ReplayParams
{
  std::string run;                            // folder of a tow_sim_batch run (its shapes.csv)
  double speed = 1.0;                         // [-] simulated seconds per wall second
  double publish_rate = 10.0;                 // [Hz] wall time: /clock and cable/markers
  bool loop = false;                          // start again after the last shape (else hold it)
  std::string world_frame = "odom";           // frame of the markers
  std::string vehicle_frame = "tow_vehicle";  // tf child frame at the vehicle
  std::string view_frame = "tow_view";        // tf frame midway between tow point and vehicle ("": none)
  double tension_color_max = 5000.0;          // [N] red end of the colour scale
  double cable_marker_width = 0.5;            // [m]
};
const ParamTable<ReplayParams>& replayParams();
void validate(const ReplayParams& params, const std::string& prefix);

}  // namespace tow_sim
