#include "tow_sim/scenario/ship_path.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

#include "tow_sim/core/attitude.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/environment/ship_response.h"
#include "tow_sim/core/io/numeric_csv.h"
#include "tow_sim/scenario/scripted_ship.h"

namespace tow_sim
{
namespace
{

// The weights of the derivative at t[i] of the polynomial through the samples first .. last (Lagrange).
std::vector<double> derivativeWeights(const std::vector<ShipMotionSample>& m, size_t i, size_t first, size_t last)
{
  std::vector<double> w;
  for (size_t j = first; j <= last; ++j)
  {
    double weight = 0.0;
    if (j == i)
      for (size_t k = first; k <= last; ++k)
        weight += k == i ? 0.0 : 1.0 / (m[i].t - m[k].t);
    else
    {
      weight = 1.0 / (m[j].t - m[i].t);
      for (size_t k = first; k <= last; ++k)
        if (k != i && k != j)
          weight *= (m[i].t - m[k].t) / (m[j].t - m[k].t);
    }
    w.push_back(weight);
  }
  return w;
}

// A measured motion: the tow point at each sample, its velocity the derivative of the quartic through the
// five nearest samples (an error of order dt^4: the track's accelerations, from the velocities over one
// sample interval, would amplify a central difference's dt^2 error tenfold at 10 Hz), the pose as given.
// The track's quintic pieces then give it a continuous acceleration, as the node's odometry track does.
ShipHistory replayedPath(const Scenario& sc)
{
  const std::vector<ShipMotionSample>& m = sc.motion;
  const size_t n = m.size();
  ShipHistory path(1.0, n + 10);
  // Headings and roll unwrapped, so that differences across +-pi are the short way round.
  std::vector<double> yaw(n), roll(n);
  std::vector<Eigen::Vector3d> tow(n);
  for (size_t i = 0; i < n; ++i)
  {
    yaw[i] = i == 0 ? m[0].yaw : yaw[i - 1] + std::remainder(m[i].yaw - m[i - 1].yaw, 2.0 * kPi);
    roll[i] = i == 0 ? m[0].roll : roll[i - 1] + std::remainder(m[i].roll - m[i - 1].roll, 2.0 * kPi);
    tow[i] = Eigen::Vector3d(m[i].x, m[i].y, m[i].z) + rotationFromEuler(roll[i], m[i].pitch, yaw[i]) * sc.tow_point_S;
  }
  for (size_t i = 0; i < n; ++i)
  {
    const size_t span = std::min<size_t>(4, n - 1);
    const size_t first = std::min(i >= 2 ? i - 2 : 0, n - 1 - span), last = first + span;
    const std::vector<double> w = derivativeWeights(m, i, first, last);
    Eigen::Vector3d v_tow = Eigen::Vector3d::Zero();
    Eigen::Vector2d v_ship = Eigen::Vector2d::Zero();
    for (size_t j = first; j <= last; ++j)
    {
      v_tow += w[j - first] * tow[j];
      v_ship += w[j - first] * Eigen::Vector2d(m[j].x, m[j].y);
    }
    if (!path.add(m[i].t, tow[i], v_tow,
                  ShipPose{ m[i].x, m[i].y, yaw[i], v_ship.norm(), m[i].z, roll[i], m[i].pitch }))
      throw std::invalid_argument("ship motion file: the row at t = " + std::to_string(m[i].t) +
                                  " s gives a non-finite tow point motion");
  }
  return path;
}
}  // namespace

std::vector<ShipMotionSample> loadShipMotionFile(const std::string& path)
{
  const std::vector<NumericCsvRow> rows = readNumericCsv(path, 7, "ship motion file", "t, x, y, z, roll, pitch, yaw");
  if (rows.size() < 2)
    throw std::invalid_argument("ship motion file '" + path + "': needs at least two rows");
  std::vector<ShipMotionSample> out;
  for (const NumericCsvRow& row : rows)
  {
    const std::vector<double>& c = row.values;
    // As for odometry: at least 1 us apart and within 1e9 s of t = 0 (the track's pieces stay finite).
    if (!out.empty() && !(c[0] >= out.back().t + 1e-6))
      throw std::invalid_argument("ship motion file '" + path + "' line " + std::to_string(row.line) +
                                  ": times must increase strictly, by 1 us or more (t = " + std::to_string(c[0]) +
                                  " after " + std::to_string(out.back().t) + ")");
    if (!(std::abs(c[0]) <= 1e9) || !(std::abs(c[1]) <= 1e7) || !(std::abs(c[2]) <= 1e7) || !(std::abs(c[3]) <= 1e4))
      throw std::invalid_argument("ship motion file '" + path + "' line " + std::to_string(row.line) +
                                  ": t must lie within +-1e9 s, x and y within +-1e7 m, z within +-1e4 m");
    out.push_back(ShipMotionSample{ c[0], c[1], c[2], c[3], c[4], c[5], c[6] });
  }
  return out;
}

ShipHistory buildShipPath(const Scenario& sc, double dt)
{
  if (!sc.motion.empty())
    return replayedPath(sc);
  const size_t samples = static_cast<size_t>(sc.duration / dt) + 40;
  ShipHistory path(1.0, samples + 10);
  ScriptedShip ship(sc.manoeuvres, sc.start_position.x(), sc.start_position.y(), sc.start_heading);
  std::unique_ptr<const WaveField> waves;
  std::shared_ptr<const RaoTable> rao = sc.rao;
  const Environment& env = sc.config.environment;
  if (sc.wave_response && env.waves.type != WaveParams::Type::kNone)
  {
    waves = std::make_unique<const WaveField>(env.waves, env.gravity);
    if (!rao)
      rao = std::make_shared<const RaoTable>(RaoTable::genericVessel(env.gravity));
  }
  for (size_t k = 0; k < samples; ++k)
  {
    // The tow point moves with the ship as a rigid body: v + w x r, r the tow point's offset turned into the
    // world (by the heading, and in waves by the roll and pitch too; the heave moves the reference point).
    const ShipRigidMotion m = scriptedShipMotion(ship.time(), ship.x(), ship.y(), ship.heading(), ship.speed(),
                                                 ship.yawRate(), waves.get(), rao.get());
    Eigen::Vector3d p_tow, v_tow;
    towPointOf(m, sc.tow_point_S, p_tow, v_tow);
    path.add(ship.time(), p_tow, v_tow,
             ShipPose{ ship.x(), ship.y(), ship.heading(), ship.speed(), m.p_W.z(), m.roll, m.pitch });
    ship.step(dt);
  }
  return path;
}

std::shared_ptr<ShipHistory> straightShip(double speed, double from, double to, double dt)
{
  const long samples = std::lround((to - from) / dt) + 1;
  auto ship = std::make_shared<ShipHistory>(1.0, static_cast<size_t>(std::max(8L, samples + 2)));
  for (long k = 0; k < samples; ++k)
  {
    const double t = from + k * dt;
    ship->add(t, Eigen::Vector3d(speed * t, 0.0, 0.0), Eigen::Vector3d(speed, 0.0, 0.0),
              ShipPose{ speed * t, 0.0, 0.0, speed });
  }
  return ship;
}

}  // namespace tow_sim
