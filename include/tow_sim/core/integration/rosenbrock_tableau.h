// Rosenbrock-W tableaus in the form the implicit stepper uses (docs/solver.md §7):
//   W k_i = f(t + c_i h, y + h sum_{j<i} a_ij k_j) + sum_{j<i} c_ij k_j + gamma h k_t,i df/dt,   (S15)
//   W = I - gamma h J,  k_t,i = 1 + sum_{j<i} c_ij k_t,j,
//   y_next = y + h sum_i m_i k_i,  error = h sum_i e_i k_i (y_next less the embedded solution),
// which needs no product with J outside the stage matrix. A method published in the standard form
//   (I - gamma h J) kbar_i = h f(y + sum a_ij kbar_j) + h J sum_{j<i} gamma_ij kbar_j,  y_next = y + sum b_i kbar_i,
// is brought to it by u = Gamma kbar (Gamma lower triangular with gamma on its diagonal) and k = u / (gamma h):
//   a = gamma A Gamma^-1,  c = gamma (diag(1/gamma) - Gamma^-1),  m = gamma b Gamma^-1,
//   e = gamma (b - b_embedded) Gamma^-1   (Hairer and Wanner, Solving ODEs II, §IV.7).
#pragma once

#include <string>

namespace tow_sim
{
struct RosenbrockTableau
{
  static constexpr int kMaxStages = 4;
  std::string name;
  int stages = 0;
  int order = 0;           // of y_next
  int embedded_order = 0;  // of the embedded solution: the error estimate goes like h^(embedded_order + 1)
  double gamma = 0.0;
  double a[kMaxStages][kMaxStages] = {};
  double c[kMaxStages][kMaxStages] = {};
  double m[kMaxStages] = {};
  double e[kMaxStages] = {};
};

// ROS2 (Verwer, Spee, Blom and Hundsdorfer 1999): 2 stages, order 2, L-stable, gamma = 1 + 1/sqrt(2),
// embedded order 1 (y + h K1).
const RosenbrockTableau& ros2Tableau();
// ROS34PW2 (Rang and Angermann 2005): 4 stages, order 3 as a W-method (any J), L-stable, stiffly
// accurate, embedded order 2.
const RosenbrockTableau& ros34pw2Tableau();

}  // namespace tow_sim
