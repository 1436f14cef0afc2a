#include "tow_sim/core/integration/rosenbrock_tableau.h"

#include <Eigen/Core>
#include <Eigen/LU>

namespace tow_sim
{
namespace
{
// The stepper's form of a method published in the standard form (rosenbrock_tableau.h).
RosenbrockTableau fromStandardForm(const std::string& name, int order, int embedded_order, const Eigen::Matrix4d& A,
                                   const Eigen::Matrix4d& Gamma, const Eigen::Vector4d& b,
                                   const Eigen::Vector4d& b_embedded)
{
  RosenbrockTableau t;
  t.name = name;
  t.stages = 4;
  t.order = order;
  t.embedded_order = embedded_order;
  t.gamma = Gamma(0, 0);
  const Eigen::Matrix4d inverse = Gamma.inverse();
  const Eigen::Matrix4d a = t.gamma * A * inverse;
  const Eigen::Matrix4d c = t.gamma * (Eigen::Matrix4d::Identity() / t.gamma - inverse);
  const Eigen::Vector4d m = t.gamma * inverse.transpose() * b;
  const Eigen::Vector4d e = t.gamma * inverse.transpose() * (b - b_embedded);
  for (int i = 0; i < 4; ++i)
  {
    for (int j = 0; j < i; ++j)
    {
      t.a[i][j] = a(i, j);
      t.c[i][j] = c(i, j);
    }
    t.m[i] = m[i];
    t.e[i] = e[i];
  }
  return t;
}

RosenbrockTableau makeRos2()
{
  RosenbrockTableau t;
  t.name = "ros2";
  t.stages = 2;
  t.order = 2;
  t.embedded_order = 1;
  t.gamma = 1.7071067811865475;  // 1 + 1/sqrt(2)
  t.a[1][0] = 1.0;
  t.c[1][0] = -2.0;
  t.m[0] = 1.5;
  t.m[1] = 0.5;
  t.e[0] = 0.5;  // against y + h K1
  t.e[1] = 0.5;
  return t;
}

RosenbrockTableau makeRos34pw2()
{
  // Rang and Angermann (2005), Table 2 (ROS34PW2), in the standard form.
  const double g = 4.3586652150845900e-01;
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero(), Gamma = g * Eigen::Matrix4d::Identity();
  A(1, 0) = 8.7173304301691801e-01;
  A(2, 0) = 8.4457060015369423e-01;
  A(2, 1) = -1.1299064236484185e-01;
  A(3, 2) = 1.0;
  Gamma(1, 0) = -8.7173304301691801e-01;
  Gamma(2, 0) = -9.0338057013044082e-01;
  Gamma(2, 1) = 5.4180672388095326e-02;
  Gamma(3, 0) = 2.4212380706095346e-01;
  Gamma(3, 1) = -1.2232505839045147e+00;
  Gamma(3, 2) = 5.4526025533510214e-01;
  const Eigen::Vector4d b(2.4212380706095346e-01, -1.2232505839045147e+00, 1.5452602553351020e+00, g);
  const Eigen::Vector4d b_embedded(3.7810903145819369e-01, -9.6042292212423178e-02, 0.5, 2.1793326075422950e-01);
  return fromStandardForm("ros34pw2", 3, 2, A, Gamma, b, b_embedded);
}
}  // namespace

const RosenbrockTableau& ros2Tableau()
{
  static const RosenbrockTableau t = makeRos2();
  return t;
}

const RosenbrockTableau& ros34pw2Tableau()
{
  static const RosenbrockTableau t = makeRos34pw2();
  return t;
}

}  // namespace tow_sim
