// The sea floor: flat at a depth, or a bathymetry grid; contact of cable joints and the vehicle's hull
// ends with it through a stiff penalty with damping and (smoothed) Coulomb friction.
#pragma once

#include <Eigen/Core>
#include <string>

#include "tow_sim/core/param_table.h"

namespace tow_sim
{
// Depths on a regular grid in the world's horizontal plane; bilinear between nodes, the edge values
// beyond the grid.
struct BathymetryGrid
{
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();   // [m] world x, y of depth(0, 0)
  Eigen::Vector2d spacing = Eigen::Vector2d::Ones();  // [m] dx, dy, > 0
  Eigen::MatrixXd depth;  // [m] depth(j, i) at (origin.x + i dx, origin.y + j dy), rows along y, 0 .. 12000
};

struct SeabedParams
{
  enum class Type
  {
    kNone,  // no bottom (default)
    kFlat,  // at `depth`
    kGrid   // from `grid` (read from a file by the configuration loader, loadBathymetryFile)
  };
  Type type = Type::kNone;
  double depth = 200.0;  // [m] flat bottom, (0, 12000]
  BathymetryGrid grid;
  std::string grid_file;             // where the grid came from (for messages and round trips)
  double stiffness = 1.0e4;          // [N/m per m of cable] cable: normal force per metre of penetration, (0, 1e8]
  double damping = 100.0;            // [N s/m per m of cable] on the normal penetration rate, [0, 1e8]
  double vehicle_stiffness = 1.0e5;  // [N/m] at each of the vehicle's hull ends (nose, tail), (0, 1e9]
  double vehicle_damping = 4000.0;   // [N s/m] at each hull end, [0, 1e9]
  double friction = 0.5;             // [-] Coulomb coefficient, [0, 5]
  double friction_speed = 0.05;      // [m/s] the friction force builds up over this sliding speed, (0, 10]
};
// The parameter table of the seabed (param_table.h): every key with its unit, range, default and meaning.
const ParamTable<SeabedParams>& seabedParams();

// Throws std::invalid_argument naming "<prefix>.<key>", the value and the range.
void validate(const SeabedParams& seabed, const std::string& prefix = "seabed");

class Seabed
{
public:
  explicit Seabed(const SeabedParams& params);  // validates

  bool present() const { return p_.type != SeabedParams::Type::kNone; }
  // [m] height z of the bottom below (x, y), world (negative: below the surface).
  double bottomZ(double x, double y) const;
  // Unit normal of the bottom at (x, y), pointing up into the water.
  Eigen::Vector3d normal(double x, double y) const;
  // [m] height of p above the bottom, measured vertically (negative: in the bottom).
  double altitude(const Eigen::Vector3d& p_W) const { return p_W.z() - bottomZ(p_W.x(), p_W.y()); }

  // Contact force [N] on a point at p moving at v, for a penalty of `stiffness` [N/m] and `damping`
  // [N s/m]: zero above the bottom; else pushing out along the normal (never pulling) plus friction
  // against the sliding velocity, at most `friction` times the normal force.
  Eigen::Vector3d contactForce(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, double stiffness,
                               double damping) const;
  // Its derivatives with respect to p [N/m] and v [N s/m] (for the implicit stepper), the normal held
  // fixed (on a grid it also turns with p: left out); zero where the force is.
  void contactJacobian(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, double stiffness, double damping,
                       Eigen::Matrix3d& df_dp, Eigen::Matrix3d& df_dv) const;

  const SeabedParams& params() const { return p_; }

private:
  SeabedParams p_;
};

}  // namespace tow_sim
