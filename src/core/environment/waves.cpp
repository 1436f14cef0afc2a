#include "tow_sim/core/environment/waves.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

#include "tow_sim/core/constants.h"
#include "tow_sim/core/param_tables.h"

namespace tow_sim
{
namespace
{
// Beyond this k z (deep) or k (z + h) - k h (finite depth) a component's motion is below 1e-9 of the surface's.
constexpr double kNegligibleDecay = -20.7;

// Uniform on [0, 1) from the generator's raw 64 bits: the same numbers on every platform (the standard fixes
// mt19937_64's sequence but not what its distributions make of it).
double uniform(std::mt19937_64& rng)
{
  return static_cast<double>(rng() >> 11) * 0x1.0p-53;
}

// A direction about `mean` from the spreading function cos^{2s}((theta - mean)/2), by inverting its
// cumulative distribution (tabulated).
class SpreadingSampler
{
public:
  explicit SpreadingSampler(double s) : cdf_(kPoints + 1, 0.0)
  {
    for (int i = 1; i <= kPoints; ++i)
    {
      const double mid = -kPi + (i - 0.5) * step();
      cdf_[i] = cdf_[i - 1] + std::pow(std::cos(0.5 * mid), 2.0 * s);
    }
    for (double& c : cdf_)
      c /= cdf_.back();
  }
  double offset(double u) const
  {
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), u);
    const int i = std::clamp(static_cast<int>(it - cdf_.begin()), 1, kPoints);
    const double width = cdf_[i] - cdf_[i - 1];
    const double frac = width > 0.0 ? (u - cdf_[i - 1]) / width : 0.5;
    return -kPi + (i - 1 + frac) * step();
  }

private:
  static constexpr int kPoints = 4096;
  static double step() { return 2.0 * kPi / kPoints; }
  std::vector<double> cdf_;
};
}  // namespace

double waveNumber(double omega, double gravity, double water_depth)
{
  const double deep = omega * omega / gravity;
  if (water_depth <= 0.0)
    return deep;
  // omega^2 = g k tanh(k h). Both the deep-water and the shallow-water (omega / sqrt(g h)) wave numbers lie
  // below the root (tanh x < 1, tanh x < x); bracket it by doubling, then Newton kept inside the bracket.
  auto f = [&](double k) { return gravity * k * std::tanh(k * water_depth) - omega * omega; };
  double lo = std::max(deep, omega / std::sqrt(gravity * water_depth)), hi = 2.0 * lo;
  while (f(hi) < 0.0)
  {
    lo = hi;
    hi *= 2.0;
  }
  double k = 0.5 * (lo + hi);
  for (int i = 0; i < 200 && hi - lo > 1e-15 * hi; ++i)
  {
    const double fk = f(k);
    (fk < 0.0 ? lo : hi) = k;
    const double th = std::tanh(k * water_depth);
    const double next = k - fk / (gravity * (th + k * water_depth * (1.0 - th * th)));
    if (fk == 0.0 || std::abs(next - k) <= 1e-15 * k)
      return fk == 0.0 ? k : next;
    k = next > lo && next < hi ? next : 0.5 * (lo + hi);
  }
  return k;
}

JonswapSpectrum::JonswapSpectrum(double significant_height, double peak_period, double peak_enhancement)
    : omega_p_(2.0 * kPi / peak_period), gamma_(peak_enhancement), scale_(1.0)
{
  // m0 of the shape in x = omega/omega_p by Simpson's rule on [0.05, 60] (the shape is below 1e-300 under
  // 0.05 and its tail above 60 holds (1/4) 60^-4 of the ~0.2 of the whole: 1e-8).
  const int n = 200000;
  const double lo = 0.05, hi = 60.0, h = (hi - lo) / n;
  double sum = shape(lo) + shape(hi);
  for (int i = 1; i < n; ++i)
    sum += (i % 2 ? 4.0 : 2.0) * shape(lo + i * h);
  const double m0_shape = sum * h / 3.0 * omega_p_;  // d omega = omega_p dx
  scale_ = significant_height * significant_height / 16.0 / m0_shape;
}

double JonswapSpectrum::shape(double x) const
{
  if (x <= 0.0)
    return 0.0;
  const double sigma = x <= 1.0 ? 0.07 : 0.09;
  const double r = std::exp(-(x - 1.0) * (x - 1.0) / (2.0 * sigma * sigma));
  return std::pow(x, -5.0) * std::exp(-1.25 * std::pow(x, -4.0)) * std::pow(gamma_, r);
}

double JonswapSpectrum::operator()(double omega) const
{
  return scale_ * shape(omega / omega_p_);
}

WaveField::WaveField(const WaveParams& p, double gravity) : depth_(p.water_depth)
{
  validate(p);
  if (!(gravity > 0.0) && p.type != WaveParams::Type::kNone)
    throw std::invalid_argument("environment.waves: waves need gravity > 0 (environment.gravity)");
  auto add = [&](double amplitude, double omega, double direction, double phase)
  {
    WaveComponent c;
    c.amplitude = amplitude;
    c.omega = omega;
    c.k = waveNumber(omega, gravity, depth_);
    c.direction = direction;
    c.phase = phase;
    c.kx = c.k * std::cos(direction);
    c.ky = c.k * std::sin(direction);
    components_.push_back(c);
  };
  if (p.type == WaveParams::Type::kRegular)
    add(0.5 * p.height, 2.0 * kPi / p.period, p.direction, p.phase);
  if (p.type != WaveParams::Type::kJonswap)
    return;

  // Equal frequency bins over the band, each component at a random frequency within its bin (so that the
  // sea does not repeat with the bins' period), a_i = sqrt(2 S(omega_i) d omega), a random phase and, with
  // spreading, one random direction per component drawn from the spreading function.
  const JonswapSpectrum spectrum(p.significant_height, p.peak_period, p.peak_enhancement);
  const double lo = kJonswapLowestFrequency * spectrum.peakFrequency();
  const double d_omega = (kJonswapHighestFrequency - kJonswapLowestFrequency) * spectrum.peakFrequency() / p.components;
  std::mt19937_64 rng(static_cast<std::uint64_t>(p.seed));
  const SpreadingSampler spread(p.spreading);
  for (int i = 0; i < p.components; ++i)
  {
    const double omega = lo + (i + uniform(rng)) * d_omega;
    const double phase = 2.0 * kPi * uniform(rng);
    const double direction = p.spreading > 0.0 ? p.direction + spread.offset(uniform(rng)) : p.direction;
    add(std::sqrt(2.0 * spectrum(omega) * d_omega), omega, direction, phase);
  }
  // Frequencies increase with i and k with omega: already in order of increasing k.
}

double WaveField::elevation(double x, double y, double t) const
{
  double zeta = 0.0;
  for (const WaveComponent& c : components_)
    zeta += c.amplitude * std::cos(c.omega * t - (c.kx * x + c.ky * y) + c.phase);
  return zeta;
}

WaveKinematics WaveField::kinematics(const Eigen::Vector3d& p, double t) const
{
  WaveKinematics out;
  const double z = p.z();
  if (z >= 0.0 || (depth_ > 0.0 && z <= -depth_))
    return out;
  for (const WaveComponent& c : components_)
  {
    // Horizontal and vertical depth factors: e^{k z} (deep), cosh / sinh of k (z + h) over sinh(k h).
    double horizontal, vertical;
    if (depth_ <= 0.0)
    {
      if (c.k * z < kNegligibleDecay)
        break;  // and every later (shorter) component
      horizontal = vertical = std::exp(c.k * z);
    }
    else
    {
      const double kh = c.k * depth_, kzh = c.k * (z + depth_);
      if (kzh - kh < kNegligibleDecay)
        break;
      if (kh > 20.0)  // cosh / sinh overflow soon; their ratios are e^{k z} to 1e-17
        horizontal = vertical = std::exp(c.k * z);
      else
      {
        horizontal = std::cosh(kzh) / std::sinh(kh);
        vertical = std::sinh(kzh) / std::sinh(kh);
      }
    }
    const double cd = c.kx / c.k, sd = c.ky / c.k;
    const double psi = c.omega * t - (c.kx * p.x() + c.ky * p.y()) + c.phase;
    const double cp = std::cos(psi), sp = std::sin(psi);
    const double a_omega = c.amplitude * c.omega, a_omega2 = a_omega * c.omega;
    // zeta = a cos(psi): u = a omega F_h cos(psi) along the direction, w = -a omega F_v sin(psi).
    const double u = a_omega * horizontal * cp, du = -a_omega2 * horizontal * sp;
    out.velocity_W += Eigen::Vector3d(u * cd, u * sd, -a_omega * vertical * sp);
    out.acceleration_W += Eigen::Vector3d(du * cd, du * sd, -a_omega2 * vertical * cp);
  }
  return out;
}

void validate(const WaveParams& w, const std::string& prefix)
{
  validateParams(waveParams(), w, prefix);
}

}  // namespace tow_sim
