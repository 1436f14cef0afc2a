// Linear (Airy) surface waves (physics.md §9): a regular wave or an irregular sea from a JONSWAP spectrum,
// as a sum of components, each zeta_i = a_i cos(omega_i t - k_i (x cos theta_i + y sin theta_i) + phi_i).
// Directions are those the waves travel toward, radians, ENU, counter-clockwise from +x (like a heading).
// Below the mean surface z = 0 a component's particle velocity and acceleration are Airy's, with
// cosh(k (z + h)) / sinh(k h) in water of depth h and e^{k z} in deep water; at and above z = 0 (the splash
// zone, which linear theory does not describe) and below the bottom there are none.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace tow_sim
{
struct WaveParams
{
  enum class Type
  {
    kNone,     // calm water (the report's; default)
    kRegular,  // one component
    kJonswap   // an irregular sea
  };
  Type type = Type::kNone;
  double water_depth = 0.0;  // [m] h for the kinematics and the dispersion relation; 0: deep water, else (0, 12000]
  double direction = 0.0;    // [rad] the waves (JONSWAP: their mean) travel toward, ENU, [-2 pi, 2 pi]
  // Regular wave.
  double height = 2.0;  // [m] crest to trough H = 2 a, (0, 30]
  double period = 8.0;  // [s] T, [1, 60]
  double phase = 0.0;   // [rad] phi: zeta = (H/2) cos(omega t - k.x + phi), [-2 pi, 2 pi]
  // JONSWAP sea.
  double significant_height = 4.0;  // [m] Hs = 4 sqrt(m0) of the spectrum, (0, 30]
  double peak_period = 10.0;        // [s] Tp, [1, 60]
  double peak_enhancement = 3.3;    // [-] gamma, [1, 10]
  double spreading = 0.0;           // [-] s of the cos^{2s}((theta - mean)/2) spreading; 0: long-crested, [0, 100]
  int components = 100;             // [-] number of components, [1, 2000]
  int seed = 1;                     // [-] the random phases, frequencies within their bins and directions, >= 0
};

// One wave component.
struct WaveComponent
{
  double amplitude = 0.0;     // [m] a
  double omega = 0.0;         // [rad/s] angular frequency
  double k = 0.0;             // [rad/m] wave number, omega^2 = g k tanh(k h)
  double direction = 0.0;     // [rad] theta
  double phase = 0.0;         // [rad] phi
  double kx = 0.0, ky = 0.0;  // [rad/m] the wave vector k (cos theta, sin theta)
};

// The water's motion at a point: velocity and (local) acceleration, world ENU.
struct WaveKinematics
{
  Eigen::Vector3d velocity_W = Eigen::Vector3d::Zero();      // [m/s]
  Eigen::Vector3d acceleration_W = Eigen::Vector3d::Zero();  // [m/s^2]
};

// The wave number of angular frequency omega [rad/s] in water of depth h [m] (0: deep, k = omega^2/g).
double waveNumber(double omega, double gravity, double water_depth);

// The JONSWAP spectral density S(omega) [m^2 s/rad] of Hs and Tp with peak enhancement gamma (sigma 0.07
// below the peak, 0.09 above), scaled so that its zeroth moment is Hs^2/16 (computed, not the usual
// approximation of alpha).
class JonswapSpectrum
{
public:
  JonswapSpectrum(double significant_height, double peak_period, double peak_enhancement);
  double operator()(double omega) const;
  double peakFrequency() const { return omega_p_; }  // [rad/s]

private:
  double shape(double x) const;  // of x = omega / omega_p, unscaled
  double omega_p_, gamma_, scale_;
};

class WaveField
{
public:
  // The sea of `params` (validated: std::invalid_argument naming the parameter) under gravity g [m/s^2].
  WaveField(const WaveParams& params, double gravity);

  // In order of increasing wave number (so decreasing reach below the surface).
  const std::vector<WaveComponent>& components() const { return components_; }
  double waterDepth() const { return depth_; }  // [m] 0: deep

  // [m] surface elevation zeta at horizontal position (x, y) [m], time t [s].
  double elevation(double x, double y, double t) const;
  // Particle velocity and acceleration at p_W [m], time t [s].
  WaveKinematics kinematics(const Eigen::Vector3d& p_W, double t) const;

private:
  std::vector<WaveComponent> components_;
  double depth_ = 0.0;
};

void validate(const WaveParams& waves, const std::string& prefix = "environment.waves");

// The JONSWAP components' frequency band, as multiples of the peak frequency: the spectrum beyond it holds
// about 0.5 % of m0 (0.25 % of Hs).
constexpr double kJonswapLowestFrequency = 0.5;
constexpr double kJonswapHighestFrequency = 4.0;

}  // namespace tow_sim
