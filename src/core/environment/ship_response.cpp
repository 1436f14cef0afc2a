#include "tow_sim/core/environment/ship_response.h"

#include "tow_sim/core/attitude.h"
#include "tow_sim/core/constants.h"
#include "tow_sim/core/io/numeric_csv.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace tow_sim
{
namespace
{

// The generic vessel (docs/tools.md, "The ship in waves").
constexpr double kLength = 60.0, kBeam = 12.0;              // [m]
constexpr double kHeavePeriod = 6.0, kHeaveDamping = 0.25;  // [s], [-]
constexpr double kPitchPeriod = 5.5, kPitchDamping = 0.25;  // [s], [-]
constexpr double kRollPeriod = 10.0, kRollDamping = 0.1;    // [s], [-]

// The mean of cos(k x) over [-l, l] (sin q / q) and the least-squares slope factor of a surface
// a cos(psi - k x) over [-l, l] relative to its slope at the centre: 3 (sin q - q cos q) / q^3, q = k l.
double meanFactor(double q)
{
  return std::abs(q) < 1e-4 ? 1.0 - q * q / 6.0 : std::sin(q) / q;
}
double slopeFactor(double q)
{
  return std::abs(q) < 1e-3 ? 1.0 - q * q / 10.0 : 3.0 * (std::sin(q) - q * std::cos(q)) / (q * q * q);
}
// One degree of freedom's response to a quasi-static excitation: 1 / (1 - r^2 + 2 i zeta r), r = omega/omega_n.
std::complex<double> resonance(double omega, double period, double damping)
{
  const double r = omega * period / kTwoPi;
  return 1.0 / std::complex<double>(1.0 - r * r, 2.0 * damping * r);
}

}  // namespace

RaoTable::RaoTable(std::vector<double> frequencies, std::vector<double> directions, std::vector<RaoValue> values,
                   const std::string& source)
    : frequencies_(std::move(frequencies)), directions_(std::move(directions)), values_(std::move(values))
{
  auto fail = [&](const std::string& what) { throw std::invalid_argument(source + ": " + what); };
  if (frequencies_.empty() || directions_.empty())
    fail("needs at least one frequency and one direction");
  for (size_t i = 0; i < frequencies_.size(); ++i)
    if (!(std::isfinite(frequencies_[i]) && frequencies_[i] > 0.0 && (i == 0 || frequencies_[i] > frequencies_[i - 1])))
      fail("frequencies must be finite, > 0 [rad/s] and strictly increasing (at " + std::to_string(frequencies_[i]) +
           ")");
  for (size_t i = 0; i < directions_.size(); ++i)
    if (!(std::isfinite(directions_[i]) && directions_[i] >= 0.0 && directions_[i] < kTwoPi &&
          (i == 0 || directions_[i] > directions_[i - 1])))
      fail("directions must lie in [0, 2 pi) [rad] and strictly increase (at " + std::to_string(directions_[i]) + ")");
  if (values_.size() != frequencies_.size() * directions_.size())
    fail("needs " + std::to_string(frequencies_.size() * directions_.size()) +
         " values (every direction at every "
         "frequency), got " +
         std::to_string(values_.size()));
  for (const RaoValue& v : values_)
    for (const std::complex<double>& c : { v.heave, v.roll, v.pitch })
      if (!std::isfinite(c.real()) || !std::isfinite(c.imag()) || std::abs(c) > 100.0)
        fail("amplitudes must be finite and at most 100 (m/m or rad/m)");
}

RaoValue genericVesselRao(double omega, double beta, double gravity)
{
  // Wave vector in the ship frame: k (cos beta, sin beta).
  const double k = omega * omega / gravity;
  const double kx = k * std::cos(beta), ky = k * std::sin(beta);
  const double qx = 0.5 * kx * kLength, qy = 0.5 * ky * kBeam;
  // zeta = a cos(psi - kx x - ky y) over the waterplane: mean a cos(psi) mx my; slopes d zeta / dx =
  // a kx sin(psi) sx my, d zeta / dy = a ky sin(psi) sy mx (least squares). Bow down is positive pitch,
  // port up positive roll: pitch = -slope_x, roll = slope_y; a sin(psi) = Re(-i a e^{i psi}).
  const std::complex<double> i(0.0, 1.0);
  RaoValue r;
  r.heave = meanFactor(qx) * meanFactor(qy) * resonance(omega, kHeavePeriod, kHeaveDamping);
  r.pitch = i * kx * slopeFactor(qx) * meanFactor(qy) * resonance(omega, kPitchPeriod, kPitchDamping);
  r.roll = -i * ky * slopeFactor(qy) * meanFactor(qx) * resonance(omega, kRollPeriod, kRollDamping);
  return r;
}

RaoTable RaoTable::genericVessel(double gravity)
{
  std::vector<double> frequencies, directions;
  for (int f = 0; f <= 118; ++f)
    frequencies.push_back(0.05 + 0.025 * f);  // 0.05 .. 3 rad/s
  for (int d = 0; d < 72; ++d)
    directions.push_back(d * kTwoPi / 72.0);  // every 5 degrees
  std::vector<RaoValue> values;
  for (double beta : directions)
    for (double omega : frequencies)
      values.push_back(genericVesselRao(omega, beta, gravity));
  return RaoTable(frequencies, directions, values, "the generic vessel's RAO");
}

RaoTable RaoTable::fromCsvFile(const std::string& path)
{
  const std::string name = "rao file '" + path + "'";
  const std::vector<NumericCsvRow> rows = readNumericCsv(
      path, 8, "rao file",
      "frequency, direction, heave_amplitude, heave_phase, roll_amplitude, roll_phase, pitch_amplitude, pitch_phase");
  std::vector<double> frequencies, directions;
  std::vector<std::pair<std::pair<double, double>, RaoValue>> grid;  // ((direction, frequency), value)
  for (const NumericCsvRow& row : rows)
  {
    const std::vector<double>& c = row.values;
    if (c[2] < 0.0 || c[4] < 0.0 || c[6] < 0.0)
      throw std::invalid_argument(name + " line " + std::to_string(row.line) + ": amplitudes must be >= 0");
    grid.push_back(
        { { c[1], c[0] }, RaoValue{ std::polar(c[2], c[3]), std::polar(c[4], c[5]), std::polar(c[6], c[7]) } });
    frequencies.push_back(c[0]);
    directions.push_back(c[1]);
  }
  auto unique = [](std::vector<double>& v)
  {
    std::sort(v.begin(), v.end());
    v.erase(std::unique(v.begin(), v.end()), v.end());
  };
  unique(frequencies);
  unique(directions);
  std::sort(grid.begin(), grid.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<RaoValue> values;
  const size_t nf = std::max<size_t>(frequencies.size(), 1);
  for (size_t i = 0; i < grid.size(); ++i)
  {
    if (i > 0 && grid[i].first == grid[i - 1].first)
      throw std::invalid_argument(name + ": frequency " + std::to_string(grid[i].first.second) + " at direction " +
                                  std::to_string(grid[i].first.first) + " is given twice");
    const size_t d = i / nf, f = i % nf;
    if (d >= directions.size() || grid[i].first != std::make_pair(directions[d], frequencies[f]))
      throw std::invalid_argument(name + ": not a full grid (every direction at every frequency)");
    values.push_back(grid[i].second);
  }
  return RaoTable(frequencies, directions, values, name);
}

RaoValue RaoTable::at(double omega, double beta) const
{
  // Frequency: the bracketing pair, clamped at the ends.
  const size_t nf = frequencies_.size(), nd = directions_.size();
  size_t f1 = std::upper_bound(frequencies_.begin(), frequencies_.end(), omega) - frequencies_.begin();
  size_t f0 = f1 == 0 ? 0 : f1 - 1;
  f1 = std::min(f1, nf - 1);
  const double wf = f1 == f0 ? 0.0 : (omega - frequencies_[f0]) / (frequencies_[f1] - frequencies_[f0]);
  // Direction: periodic.
  double b = std::fmod(beta, kTwoPi);
  if (b < 0.0)
    b += kTwoPi;
  size_t d1 = std::upper_bound(directions_.begin(), directions_.end(), b) - directions_.begin();
  size_t d0;
  double lo, hi;
  if (d1 == 0 || d1 == nd)  // between the last direction and the first plus 2 pi
  {
    d0 = nd - 1;
    d1 = 0;
    lo = directions_[d0] - (b < directions_[0] ? kTwoPi : 0.0);
    hi = directions_[0] + (b < directions_[0] ? 0.0 : kTwoPi);
  }
  else
  {
    d0 = d1 - 1;
    lo = directions_[d0];
    hi = directions_[d1];
  }
  const double wd = nd == 1 || hi == lo ? 0.0 : (b - lo) / (hi - lo);
  auto value = [&](size_t d, size_t f) -> const RaoValue& { return values_[d * nf + f]; };
  auto mix = [&](auto member)
  {
    return (1.0 - wd) * ((1.0 - wf) * value(d0, f0).*member + wf * value(d0, f1).*member) +
           wd * ((1.0 - wf) * value(d1, f0).*member + wf * value(d1, f1).*member);
  };
  return RaoValue{ mix(&RaoValue::heave), mix(&RaoValue::roll), mix(&RaoValue::pitch) };
}

ShipWaveMotion shipWaveMotion(const WaveField& waves, const RaoTable& rao, double t, const Eigen::Vector2d& p,
                              const Eigen::Vector2d& v, double heading)
{
  ShipWaveMotion m;
  for (const WaveComponent& c : waves.components())
  {
    const double psi = c.omega * t - (c.kx * p.x() + c.ky * p.y()) + c.phase;
    const double encounter = c.omega - (c.kx * v.x() + c.ky * v.y());  // d psi / dt
    const RaoValue r = rao.at(c.omega, c.direction - heading);
    const std::complex<double> e = c.amplitude * std::polar(1.0, psi), de = std::complex<double>(0.0, encounter) * e;
    m.heave += (r.heave * e).real();
    m.roll += (r.roll * e).real();
    m.pitch += (r.pitch * e).real();
    m.heave_rate += (r.heave * de).real();
    m.roll_rate += (r.roll * de).real();
    m.pitch_rate += (r.pitch * de).real();
  }
  return m;
}

ShipRigidMotion scriptedShipMotion(double t, double x, double y, double heading, double speed, double yaw_rate,
                                   const WaveField* waves, const RaoTable* rao)
{
  ShipRigidMotion m;
  m.yaw = heading;
  m.yaw_rate = yaw_rate;
  m.p_W = Eigen::Vector3d(x, y, 0.0);
  m.v_W = Eigen::Vector3d(speed * std::cos(heading), speed * std::sin(heading), 0.0);
  if (!waves || !rao)
    return m;
  const ShipWaveMotion w = shipWaveMotion(*waves, *rao, t, m.p_W.head<2>(), m.v_W.head<2>(), heading);
  m.p_W.z() = w.heave;
  m.v_W.z() = w.heave_rate;
  m.roll = w.roll;
  m.roll_rate = w.roll_rate;
  m.pitch = w.pitch;
  m.pitch_rate = w.pitch_rate;
  return m;
}

Eigen::Vector3d shipAngularVelocity(const ShipRigidMotion& m)
{
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(m.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Eigen::Matrix3d Ry = Eigen::AngleAxisd(m.pitch, Eigen::Vector3d::UnitY()).toRotationMatrix();
  return m.yaw_rate * Eigen::Vector3d::UnitZ() + Rz * (m.pitch_rate * Eigen::Vector3d::UnitY()) +
         Rz * Ry * (m.roll_rate * Eigen::Vector3d::UnitX());
}

void towPointOf(const ShipRigidMotion& m, const Eigen::Vector3d& r_S, Eigen::Vector3d& p_W, Eigen::Vector3d& v_W)
{
  const Eigen::Vector3d arm = rotationFromEuler(m.roll, m.pitch, m.yaw) * r_S;
  p_W = m.p_W + arm;
  v_W = m.v_W + shipAngularVelocity(m).cross(arm);
}

}  // namespace tow_sim
