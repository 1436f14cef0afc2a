// The ship's heave, roll and pitch in waves from response amplitude operators (physics.md §9), and the
// tow point of a ship that heaves, rolls and pitches (the rigid-body lever arm).
//
// For each wave component (waves.h) and each of heave, roll and pitch the motion at the ship's reference
// point is Re(R(omega, beta) a e^{i psi}) = |R| a cos(psi + arg R), psi = omega t - k.x_ship + phi the
// component's phase at the ship's reference point and beta = theta - heading the direction the waves
// travel toward relative to the bow (0: following seas, pi: head seas, pi/2: from starboard, travelling
// to port). R is interpolated linearly (as a complex number) in omega and beta; beyond the table's
// frequencies it holds the end values. Angles follow REP-103: roll about x_b (forward; positive: port
// side up), pitch about y_b (port; positive: bow down), heave up. The RAOs are at zero speed: the moving
// ship meets the waves at the encounter frequency through psi, but the operators do not change with it.
#pragma once

#include <Eigen/Core>
#include <complex>
#include <string>
#include <vector>

#include "tow_sim/core/environment/waves.h"

namespace tow_sim
{
// Complex response per metre of wave amplitude: heave [m/m], roll and pitch [rad/m].
struct RaoValue
{
  std::complex<double> heave, roll, pitch;
};

class RaoTable
{
public:
  // frequencies [rad/s] strictly increasing, > 0; directions [rad] strictly increasing within [0, 2 pi)
  // (periodic: between the last and the first plus 2 pi it interpolates across); values[d * F + f] for
  // direction d and frequency f. Throws std::invalid_argument naming `source` for a bad table.
  RaoTable(std::vector<double> frequencies, std::vector<double> directions, std::vector<RaoValue> values,
           const std::string& source = "rao table");

  // The documented default: a generic 60 m vessel (60 m long, 12 m beam) that follows the wave surface
  // averaged over its waterplane in long waves, with one-degree-of-freedom resonances in heave (6 s,
  // damping ratio 0.25), pitch (5.5 s, 0.25) and roll (10 s, 0.1). See docs/tools.md ("The ship in waves").
  static RaoTable genericVessel(double gravity = 9.81);

  // A CSV file: a header line, then rows `frequency, direction, heave_amplitude, heave_phase,
  // roll_amplitude, roll_phase, pitch_amplitude, pitch_phase` [rad/s, rad, m/m, rad, rad/m, rad, rad/m,
  // rad], one per (direction, frequency) of a full grid; lines starting with # are comments. motion =
  // amplitude * a * cos(psi + phase). Throws std::invalid_argument naming the file and the line.
  static RaoTable fromCsvFile(const std::string& path);

  RaoValue at(double omega, double relative_direction) const;
  const std::vector<double>& frequencies() const { return frequencies_; }
  const std::vector<double>& directions() const { return directions_; }

private:
  std::vector<double> frequencies_, directions_;
  std::vector<RaoValue> values_;
};

// The generic vessel's response formula itself (genericVessel() tabulates it).
RaoValue genericVesselRao(double omega, double relative_direction, double gravity);

// The ship's motion in the waves at one time: heave [m], roll, pitch [rad] and their rates.
struct ShipWaveMotion
{
  double heave = 0.0, roll = 0.0, pitch = 0.0;
  double heave_rate = 0.0, roll_rate = 0.0, pitch_rate = 0.0;  // [m/s], [rad/s]
};

// At time t [s] for a ship whose reference point is at (x, y) [m] moving at (vx, vy) [m/s] (world) with
// heading [rad] (ENU): the sum over the field's components.
ShipWaveMotion shipWaveMotion(const WaveField& waves, const RaoTable& rao, double t, const Eigen::Vector2d& p_W,
                              const Eigen::Vector2d& v_W, double heading);

// The pose of a ship and its rates: reference point position and velocity (world), roll, pitch, yaw
// (REP-103: R_WS = Rz(yaw) Ry(pitch) Rx(roll)) and their rates.
struct ShipRigidMotion
{
  Eigen::Vector3d p_W = Eigen::Vector3d::Zero(), v_W = Eigen::Vector3d::Zero();
  double roll = 0.0, pitch = 0.0, yaw = 0.0;
  double roll_rate = 0.0, pitch_rate = 0.0, yaw_rate = 0.0;
};

// A ship on the surface at (x, y) [m] with heading [rad], speed [m/s] along it and yaw rate [rad/s] (the
// scripted ship's state) as a rigid motion at time t [s]: level in calm water (waves null), heaving,
// rolling and pitching by `rao` in `waves`.
ShipRigidMotion scriptedShipMotion(double t, double x, double y, double heading, double speed, double yaw_rate,
                                   const WaveField* waves, const RaoTable* rao);

// The ship's angular velocity in the world frame from the Euler angles and rates (its rotation R_WS:
// rotationFromEuler, attitude.h).
Eigen::Vector3d shipAngularVelocity(const ShipRigidMotion& m);

// The tow point r_S (ship frame, FLU) of a ship moving so: position p + R r_S and velocity v + w x (R r_S).
void towPointOf(const ShipRigidMotion& m, const Eigen::Vector3d& r_S, Eigen::Vector3d& p_W, Eigen::Vector3d& v_W);

}  // namespace tow_sim
