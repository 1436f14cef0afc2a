#include "tow_sim/core/chain/chain_state.h"

#include <algorithm>
#include <cmath>

namespace tow_sim
{
ChainState straightChain(const ChainGeometry& geometry, const Eigen::Vector3d& tow_point_W,
                         const Eigen::Vector3d& direction_W, const Eigen::Vector3d& velocity_W)
{
  const int n = geometry.jointCount();
  ChainState state;
  state.x.resize(3, n);
  state.v.resize(3, n);
  const Eigen::Vector3d dir = direction_W.normalized();
  Eigen::Vector3d p = tow_point_W;
  for (int e = 0; e < n; ++e)
  {
    p += geometry.elementLength(e) * dir;
    state.x.col(e) = p;
    state.v.col(e) = velocity_W;
  }
  return state;
}

ChainState straightChain(const ChainModel& model, const Eigen::Vector3d& tow_point_W,
                         const Eigen::Vector3d& direction_W, const Eigen::Vector3d& velocity_W)
{
  return straightChain(model.initialGeometry(), tow_point_W, direction_W, velocity_W);
}

double maxRelativeLengthError(const ChainGeometry& geometry, const Eigen::Vector3d& tow_point_W,
                              const Eigen::Ref<const Eigen::Matrix3Xd>& x, int first_element)
{
  double worst = 0.0;
  Eigen::Vector3d x_f = tow_point_W;
  for (int e = 0; e < geometry.elementCount(); ++e)
  {
    const double d = geometry.elementLength(e);
    if (e >= first_element)
      worst = std::max(worst, std::abs((x.col(e) - x_f).norm() / d - 1.0));
    x_f = x.col(e);
  }
  return worst;
}

void removeStretchRates(const ShipEndState& tow_point, int segments, ChainState& state)
{
  Eigen::Vector3d x_f = tow_point.p_W, v_f = tow_point.v_W;
  for (int e = 0; e < segments; ++e)
  {
    const Eigen::Vector3d s = (state.x.col(e) - x_f).normalized();
    state.v.col(e) -= s.dot(state.v.col(e) - v_f) * s;
    x_f = state.x.col(e);
    v_f = state.v.col(e);
  }
}

std::vector<double> segmentStrains(const ChainGeometry& geometry, const Eigen::Matrix3Xd& joints)
{
  std::vector<double> strain(static_cast<size_t>(geometry.segments));
  for (int e = 0; e < geometry.segments; ++e)
    strain[static_cast<size_t>(e)] = (joints.col(e + 1) - joints.col(e)).norm() / geometry.elementLength(e) - 1.0;
  return strain;
}

std::vector<bool> slackFlags(const Eigen::Matrix3Xd& joints, const Eigen::Matrix3Xd& tensions)
{
  std::vector<bool> slack(static_cast<size_t>(tensions.cols()));
  for (Eigen::Index j = 0; j < tensions.cols(); ++j)
    slack[static_cast<size_t>(j)] = tensions.col(j).dot(joints.col(j + 1) - joints.col(j)) > 0.0;
  return slack;
}

void liftAboveSeabed(const Seabed& seabed, ChainState& state)
{
  if (!seabed.present())
    return;
  for (int j = 0; j < state.x.cols(); ++j)
    state.x(2, j) = std::max(state.x(2, j), seabed.bottomZ(state.x(0, j), state.x(1, j)));
}

}  // namespace tow_sim
