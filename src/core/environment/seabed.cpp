#include "tow_sim/core/environment/seabed.h"

#include "tow_sim/core/param_tables.h"
#include "tow_sim/core/params.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace tow_sim
{
void validate(const SeabedParams& s, const std::string& p)
{
  validateParams(seabedParams(), s, p);
  if (s.type == SeabedParams::Type::kGrid)
  {
    const std::string g = s.grid_file.empty() ? p + ".grid" : p + ".grid_file (" + s.grid_file + ")";
    if (s.grid.depth.rows() < 2 || s.grid.depth.cols() < 2)
      throw std::invalid_argument(g + ": the depth grid needs at least 2 x 2 points, got " +
                                  std::to_string(s.grid.depth.rows()) + " x " + std::to_string(s.grid.depth.cols()));
    for (int i = 0; i < 2; ++i)
    {
      requireInRange(g + ".origin[" + std::to_string(i) + "]", s.grid.origin[i], -1e7, 1e7, "[m]");
      requireInRange(g + ".spacing[" + std::to_string(i) + "]", s.grid.spacing[i], 0.0, 1e5, "[m]", true);
    }
    for (int j = 0; j < s.grid.depth.rows(); ++j)
      for (int i = 0; i < s.grid.depth.cols(); ++i)
        requireInRange(g + ".depth[" + std::to_string(j) + "][" + std::to_string(i) + "]", s.grid.depth(j, i), 0.0,
                       12000.0, "[m]");
  }
}

Seabed::Seabed(const SeabedParams& params) : p_(params)
{
  validate(p_);
}

namespace
{
// Bilinear interpolation and its gradient on the grid, clamped at the edges.
double gridDepth(const BathymetryGrid& g, double x, double y, Eigen::Vector2d* gradient)
{
  if (!std::isfinite(x) || !std::isfinite(y))  // a diverging stage: NaN, never an index out of the grid
  {
    if (gradient)
      gradient->setConstant(std::numeric_limits<double>::quiet_NaN());
    return std::numeric_limits<double>::quiet_NaN();
  }
  const int nx = static_cast<int>(g.depth.cols()), ny = static_cast<int>(g.depth.rows());
  const double u = std::clamp((x - g.origin.x()) / g.spacing.x(), 0.0, nx - 1.0);
  const double w = std::clamp((y - g.origin.y()) / g.spacing.y(), 0.0, ny - 1.0);
  const int i = std::min(static_cast<int>(u), nx - 2), j = std::min(static_cast<int>(w), ny - 2);
  const double fu = u - i, fw = w - j;
  const double d00 = g.depth(j, i), d01 = g.depth(j, i + 1), d10 = g.depth(j + 1, i), d11 = g.depth(j + 1, i + 1);
  if (gradient)
  {
    const bool inside_x = x > g.origin.x() && x < g.origin.x() + (nx - 1) * g.spacing.x();
    const bool inside_y = y > g.origin.y() && y < g.origin.y() + (ny - 1) * g.spacing.y();
    (*gradient).x() = inside_x ? ((1 - fw) * (d01 - d00) + fw * (d11 - d10)) / g.spacing.x() : 0.0;
    (*gradient).y() = inside_y ? ((1 - fu) * (d10 - d00) + fu * (d11 - d01)) / g.spacing.y() : 0.0;
  }
  return (1 - fw) * ((1 - fu) * d00 + fu * d01) + fw * ((1 - fu) * d10 + fu * d11);
}
}  // namespace

double Seabed::bottomZ(double x, double y) const
{
  switch (p_.type)
  {
    case SeabedParams::Type::kFlat:
      return -p_.depth;
    case SeabedParams::Type::kGrid:
      return -gridDepth(p_.grid, x, y, nullptr);
    default:
      return -std::numeric_limits<double>::infinity();
  }
}

Eigen::Vector3d Seabed::normal(double x, double y) const
{
  if (p_.type != SeabedParams::Type::kGrid)
    return Eigen::Vector3d::UnitZ();
  Eigen::Vector2d grad_depth;
  gridDepth(p_.grid, x, y, &grad_depth);
  // The bottom is z = -depth(x, y): its upward normal is (d depth/dx, d depth/dy, 1), normalised.
  return Eigen::Vector3d(grad_depth.x(), grad_depth.y(), 1.0).normalized();
}

Eigen::Vector3d Seabed::contactForce(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, double stiffness,
                                     double damping) const
{
  if (p_.type == SeabedParams::Type::kNone)
    return Eigen::Vector3d::Zero();
  const double below = -altitude(p_W);
  if (below <= 0.0)
    return Eigen::Vector3d::Zero();
  const Eigen::Vector3d n = normal(p_W.x(), p_W.y());
  const double penetration = below * n.z();  // along the normal
  const double normal_speed = v_W.dot(n);
  const double push = std::max(0.0, stiffness * penetration - damping * normal_speed);
  const Eigen::Vector3d slide = v_W - normal_speed * n;
  const double speed = slide.norm();
  Eigen::Vector3d f = push * n;
  if (speed > 0.0)
    f -= p_.friction * push * slide / std::sqrt(speed * speed + p_.friction_speed * p_.friction_speed);
  return f;
}

void Seabed::contactJacobian(const Eigen::Vector3d& p_W, const Eigen::Vector3d& v_W, double stiffness, double damping,
                             Eigen::Matrix3d& df_dp, Eigen::Matrix3d& df_dv) const
{
  df_dp.setZero();
  df_dv.setZero();
  if (p_.type == SeabedParams::Type::kNone)
    return;
  const double below = -altitude(p_W);
  if (below <= 0.0)
    return;
  const Eigen::Vector3d n = normal(p_W.x(), p_W.y());
  const double normal_speed = v_W.dot(n);
  const double push = stiffness * below * n.z() - damping * normal_speed;
  if (push <= 0.0)
    return;
  // The penetration below * n_z grows along -n (the bottom z = -depth(x, y) has the normal
  // (d depth/dx, d depth/dy, 1) / norm, so d below / dp = -n / n_z): d push / dp = -k n, d push / dv = -c n.
  const Eigen::Matrix3d I3 = Eigen::Matrix3d::Identity();
  const Eigen::Vector3d slide = v_W - normal_speed * n;
  const double root = std::sqrt(slide.squaredNorm() + p_.friction_speed * p_.friction_speed);
  // f = push (n - friction slide / root): its direction times d push, plus push times d(direction).
  const Eigen::Vector3d direction = n - p_.friction * slide / root;
  df_dp = direction * (-stiffness * n).transpose();
  df_dv = direction * (-damping * n).transpose();
  const Eigen::Matrix3d along = I3 - n * n.transpose();  // d slide / dv
  df_dv -= p_.friction * push * (I3 - slide * slide.transpose() / (root * root)) / root * along;
}

const ParamTable<SeabedParams>& seabedParams()
{
  using B = SeabedParams;
  static const ParamTable<B> table =
      ParamTable<B>()
          .choice("type", &B::type,
                  { { "none", SeabedParams::Type::kNone },
                    { "flat", SeabedParams::Type::kFlat },
                    { "grid", SeabedParams::Type::kGrid } },
                  "no bottom, flat at depth, or a bathymetry grid")
          .number("depth", &B::depth, "m", 0.0, 12000.0, kOpen, "flat bottom")
          .text("grid_file", &B::grid_file, "a readable file",
                "YAML {origin: [x, y], spacing: [dx, dy], depth: [[row at y0], …]} [m], depths ≥ 0, at least 2 × 2; "
                "relative to the configuration's folder (offline), else absolute")
          .number("stiffness", &B::stiffness, "N/m per m", 0.0, 1e8, kOpen,
                  "cable: normal force per metre of penetration, per metre of cable")
          .number("damping", &B::damping, "N s/m per m", 0.0, 1e8, kClosed, "cable: on the rate of penetration")
          .number("vehicle_stiffness", &B::vehicle_stiffness, "N/m", 0.0, 1e9, kOpen,
                  "at each of the vehicle's nose and tail points")
          .number("vehicle_damping", &B::vehicle_damping, "N s/m", 0.0, 1e9, kClosed, "at each of them")
          .number("friction", &B::friction, "-", 0.0, 5.0, kClosed, "Coulomb coefficient: sliding ≤ friction × normal")
          .number("friction_speed", &B::friction_speed, "m/s", 0.0, 10.0, kOpen,
                  "the friction force builds up over this sliding speed");
  return table;
}

}  // namespace tow_sim
