// The Rosenbrock-W tableaus in the stepper's form (rosenbrock_tableau.h) against what their methods are
// known to do on the scalar test equation y' = lambda y, one step of h from y = 1: with the exact J the
// step is R(z), z = h lambda, a rational approximation of exp(z) of the method's order, and R(-inf) = 0
// (L-stability); with J = 0 (a W-method's J may be anything) the step still agrees with exp(z) to the
// method's order. And the embedded solution's error estimate goes like h^(embedded order + 1).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "tow_sim/core/integration/rosenbrock_tableau.h"

namespace tow_sim
{
namespace
{
struct ScalarStep
{
  double y_next = 0.0;
  double error = 0.0;
};

// One step of the form (S15) on y' = lambda y from y = 1, with J = j (a number).
ScalarStep scalarStep(const RosenbrockTableau& rw, double lambda, double j, double h)
{
  double K[RosenbrockTableau::kMaxStages] = {};
  const double W = 1.0 - rw.gamma * h * j;
  ScalarStep out;
  out.y_next = 1.0;
  for (int i = 0; i < rw.stages; ++i)
  {
    double y_stage = 1.0, r = 0.0;
    for (int k = 0; k < i; ++k)
    {
      y_stage += h * rw.a[i][k] * K[k];
      r += rw.c[i][k] * K[k];
    }
    K[i] = (lambda * y_stage + r) / W;
    out.y_next += h * rw.m[i] * K[i];
    out.error += h * rw.e[i] * K[i];
  }
  return out;
}

// log2 of how the local error |y_next - exp(z)| falls when h halves, from h = 0.02 (lambda = -1).
double localOrder(const RosenbrockTableau& rw, double j_factor)
{
  const double lambda = -1.0;
  double previous = 0.0, slope = 0.0;
  for (double h : { 0.02, 0.01, 0.005 })
  {
    const double e = std::abs(scalarStep(rw, lambda, j_factor * lambda, h).y_next - std::exp(lambda * h));
    if (previous > 0.0)
      slope = std::log2(previous / e);
    previous = e;
  }
  return slope;  // local error ~ h^(order + 1)
}

double estimateOrder(const RosenbrockTableau& rw)
{
  const double lambda = -1.0;
  const double e1 = std::abs(scalarStep(rw, lambda, lambda, 0.01).error);
  const double e2 = std::abs(scalarStep(rw, lambda, lambda, 0.005).error);
  return std::log2(e1 / e2);
}

void checkTableau(const RosenbrockTableau& rw)
{
  const double exact_j = localOrder(rw, 1.0), zero_j = localOrder(rw, 0.0), estimate = estimateOrder(rw);
  const double stiff = scalarStep(rw, -1e12, -1e12, 1.0).y_next;
  std::printf("%s: local error order %.2f (exact J), %.2f (J = 0); estimate %.2f; R(-1e12) = %.2e\n", rw.name.c_str(),
              exact_j, zero_j, estimate, stiff);
  EXPECT_NEAR(exact_j, rw.order + 1, 0.15) << rw.name;
  EXPECT_NEAR(zero_j, rw.order + 1, 0.15) << rw.name;
  EXPECT_NEAR(estimate, rw.embedded_order + 1, 0.15) << rw.name;
  EXPECT_LT(std::abs(stiff), 1e-9) << rw.name;
  // Consistency: the solution weights sum to 1 (a constant f is integrated exactly); the stage times lie
  // in the step.
  double t_increments[RosenbrockTableau::kMaxStages] = {};
  double sum = 0.0;
  for (int i = 0; i < rw.stages; ++i)
  {
    double K_t = 1.0, c = 0.0;
    for (int k = 0; k < i; ++k)
    {
      K_t += rw.c[i][k] * t_increments[k];
      c += rw.a[i][k] * t_increments[k];
    }
    t_increments[i] = K_t;
    sum += rw.m[i] * K_t;
    EXPECT_GE(c, -1e-12) << rw.name << " stage " << i;
    EXPECT_LE(c, 1.0 + 1e-12) << rw.name << " stage " << i;
  }
  EXPECT_NEAR(sum, 1.0, 1e-12) << rw.name;
}

TEST(RosenbrockTableau, Ros2IsSecondOrderLStableWithAFirstOrderEstimate)
{
  checkTableau(ros2Tableau());
}

TEST(RosenbrockTableau, Ros34pw2IsThirdOrderAsAWMethodLStableWithASecondOrderEstimate)
{
  checkTableau(ros34pw2Tableau());
}

}  // namespace
}  // namespace tow_sim
