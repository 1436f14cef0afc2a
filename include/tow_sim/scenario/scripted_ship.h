// The scripted ship: one manoeuvre law for the batch scenarios (sampled into a ShipHistory by
// buildShipPath) and ship_motion_node (stepped by its timer). (Library tow_sim_scenario.)
//
// A planar ship: its speed slews toward its target at most kMaxAcceleration, its yaw rate follows its target
// with the first-order lag kYawLag, and every manoeuvre steers on a course:
//   straight, speed_change  hold the course (the previous manoeuvre's, or the start heading):
//                           yaw rate target (course - heading) / kHeadingTime;
//   turn                    the same toward course + angle, at most speed / radius: it ends steady on its
//                           angle (kHeadingTime = 4 kYawLag makes the approach critically damped);
//   zigzag                  full rate to one side, the rudder reversed when the swing, with the lag's
//                           overshoot, reaches the angle; after the last leg, back to the zigzag's course;
//   waypoints               toward the bearing of the next point, at most speed / radius.
// Over each step of dt the speed and the yaw rate change linearly; the heading and the position are their
// integrals (trapezoid, Simpson), so the velocities agree with the positions.
#pragma once

#include <vector>

#include "tow_sim/config/node_params.h"
#include "tow_sim/scenario/scenario.h"

namespace tow_sim
{
class ScriptedShip
{
public:
  static constexpr double kYawLag = 2.0;           // [s]
  static constexpr double kHeadingTime = 8.0;      // [s] = 4 kYawLag
  static constexpr double kMaxAcceleration = 0.1;  // [m/s^2]

  ScriptedShip(std::vector<Manoeuvre> manoeuvres, double x, double y, double heading);

  // One step of dt [s]. While `teleop` is given, its speed [m/s] and yaw rate [rad/s] are the targets and
  // the script waits; when it stops, the script goes on from the heading the ship has then: the manoeuvre
  // under way starts again there (a turn turns its whole angle from that heading, a zigzag swings about it).
  struct Teleop
  {
    double speed = 0.0, yaw_rate = 0.0;
  };
  void step(double dt, const Teleop* teleop = nullptr);

  double time() const { return time_; }        // [s] since the start
  double x() const { return x_; }              // [m] world
  double y() const { return y_; }              // [m] world
  double heading() const { return heading_; }  // [rad] ENU, unwrapped
  double speed() const { return u_; }          // [m/s]
  double yawRate() const { return r_; }        // [rad/s]
  double course() const { return course_; }    // [rad] the heading the script steers for now
  bool finished() const { return index_ >= manoeuvres_.size(); }

private:
  struct Targets
  {
    double speed, yaw_rate;
  };
  Targets targets();  // from the current manoeuvre, advancing to the next when it is done
  void next();
  double holdCourse(double limit) const;  // yaw rate target toward course_, within +-limit

  std::vector<Manoeuvre> manoeuvres_;
  size_t index_ = 0;
  double time_ = 0.0, started_ = 0.0;  // [s] now, and when the current manoeuvre started
  double x_, y_, heading_, u_, r_ = 0.0;
  double course_;             // [rad] steered for
  double heading0_, speed0_;  // at the start of the current manoeuvre
  int leg_ = 0;               // zigzag leg or waypoint index
  bool teleop_ = false;       // the previous step was under teleop
};

// ship_motion_node's preset (~manoeuvre and its parameters) as a list of manoeuvres, straight on for ever
// (1e6 s) after it: a turn turns for good (1e9 rad), a zigzag swings speed / |turn_radius| x zigzag_period / 4
// about its course for 1000 legs, a speed change follows change_time straight.
std::vector<Manoeuvre> presetManoeuvres(const ShipMotionParams& p);

}  // namespace tow_sim
