// Does J's inexactness bound the implicit stepper's step in a turn (issue 32)? On the shipped turn_180's state
// in the turn (t = 150 s), the same window is integrated twice: by the simulator (ROS34PW2 with its O(nu) J,
// docs/solver.md (S16)), and by a dense ROS34PW2 whose J is the exact derivative of the whole right-hand side
// (central differences of Simulator::derivative, every entry, at every step), with the same error norm (S24)
// (positions relative to the tow point, velocities; atol and rtol of the scenario's numerics) and controller
// (S25). If J's omissions bounded the step, the dense run would take fewer steps. The dense run is not
// projected onto the segment lengths: its drift is printed beside it. Prints a table; times nothing.
// Usage: bench_exact_jacobian [--segments 100,200,...] [--window SECONDS]
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "tow_sim/core/integration/rosenbrock_tableau.h"
#include "tow_sim/core/run/tow_run.h"
#include "tow_sim/scenario/scenario.h"
#include "tow_sim/scenario/ship_path.h"

namespace
{
using namespace tow_sim;

struct DenseRun
{
  int steps = 0, rejected = 0;
  double drift = 0.0;  // [-] the largest relative segment-length error at the end
  Eigen::VectorXd y;
};

// The exact J = df/dy at (t, y) by central differences, and df/dt likewise.
void differentiate(const Simulator& sim, double t, const Eigen::VectorXd& y, Eigen::MatrixXd& J, Eigen::VectorXd& f_t)
{
  const Eigen::Index n = y.size();
  auto f = [&](double tt, const Eigen::VectorXd& yy)
  {
    std::vector<double> in(yy.data(), yy.data() + n), out(n);
    sim.derivative(tt, in, out);
    return Eigen::VectorXd(Eigen::Map<Eigen::VectorXd>(out.data(), n));
  };
  J.resize(n, n);
  for (Eigen::Index q = 0; q < n; ++q)
  {
    const double e = 1e-6 * std::max(1.0, std::abs(y[q]));
    Eigen::VectorXd up = y, down = y;
    up[q] += e;
    down[q] -= e;
    J.col(q) = (f(t, up) - f(t, down)) / (2.0 * e);
  }
  f_t = (f(t + 1e-4, y) - f(t - 1e-4, y)) / 2e-4;
}

// (S24) over the joints' positions (relative to the tow point p0, p1 at either end) and velocities.
double errorNorm(const NumericsParams& num, int joints, const Eigen::VectorXd& err, const Eigen::VectorXd& y0,
                 const Eigen::VectorXd& y1, const Eigen::Vector3d& p0, const Eigen::Vector3d& p1)
{
  auto ratio = [&](double e, double a, double b, double atol)
  { return std::pow(e / (atol + num.implicit_rel_tol * std::max(std::abs(a), std::abs(b))), 2); };
  double sum = 0.0;
  for (int j = 0; j < joints; ++j)
    for (int i = 0; i < 3; ++i)
    {
      const int x = 3 * j + i, v = 3 * joints + 3 * j + i;
      sum += ratio(err[x], y0[x] - p0[i], y1[x] - p1[i], num.implicit_position_tol) +
             ratio(err[v], y0[v], y1[v], num.implicit_velocity_tol);
    }
  return std::sqrt(sum / (6.0 * joints));
}

// One dense ROS34PW2 step of size h from (t, y) (docs/solver.md (S15) with W = I - gamma h J exact).
void denseStep(const Simulator& sim, const RosenbrockTableau& rw, double t, double h, const Eigen::VectorXd& y,
               const Eigen::PartialPivLU<Eigen::MatrixXd>& W, const Eigen::VectorXd& f_t, Eigen::VectorXd& y_next,
               Eigen::VectorXd& err)
{
  const Eigen::Index n = y.size();
  Eigen::VectorXd k[RosenbrockTableau::kMaxStages];
  double k_t[RosenbrockTableau::kMaxStages];
  for (int i = 0; i < rw.stages; ++i)
  {
    double t_stage = t;
    k_t[i] = 1.0;
    Eigen::VectorXd y_stage = y;
    for (int j = 0; j < i; ++j)
    {
      t_stage += h * rw.a[i][j] * k_t[j];
      k_t[i] += rw.c[i][j] * k_t[j];
      y_stage += h * rw.a[i][j] * k[j];
    }
    std::vector<double> in(y_stage.data(), y_stage.data() + n), out(n);
    sim.derivative(t_stage, in, out);
    Eigen::VectorXd rhs = Eigen::Map<Eigen::VectorXd>(out.data(), n) + rw.gamma * h * k_t[i] * f_t;
    for (int j = 0; j < i; ++j)
      rhs += rw.c[i][j] * k[j];
    k[i] = W.solve(rhs);
  }
  y_next = y;
  err.setZero(n);
  for (int i = 0; i < rw.stages; ++i)
  {
    y_next += h * rw.m[i] * k[i];
    err += h * rw.e[i] * k[i];
  }
}

// The dense run from the simulator's state now to t_end, adaptive as (S25).
DenseRun denseRun(const Simulator& sim, const ShipHistory& ship, const NumericsParams& num, double t_end)
{
  const RosenbrockTableau& rw = ros34pw2Tableau();
  DenseRun run;
  run.y = Eigen::Map<const Eigen::VectorXd>(sim.stateVector().data(), sim.stateVector().size());
  const int joints = static_cast<int>((run.y.size() - 2) / 6);  // x, v of x_2 .. x_{nu+2}; cable out, payout rate
  double t = sim.time(), h = std::min(0.1, num.max_step);
  Eigen::MatrixXd J;
  Eigen::VectorXd f_t, y_next, err;
  while (t < t_end - 1e-9)
  {
    h = std::min(h, t_end - t);
    differentiate(sim, t, run.y, J, f_t);
    const Eigen::PartialPivLU<Eigen::MatrixXd> W(Eigen::MatrixXd::Identity(J.rows(), J.cols()) - rw.gamma * h * J);
    denseStep(sim, rw, t, h, run.y, W, f_t, y_next, err);
    const double norm = errorNorm(num, joints, err, run.y, y_next, ship.towPoint(t).p_W, ship.towPoint(t + h).p_W);
    const double grow = 0.9 * std::pow(std::max(norm, 1e-10), -1.0 / (rw.embedded_order + 1));
    if (!(norm <= 1.0))
    {
      ++run.rejected;
      h *= std::clamp(grow, 0.2, 0.9);
      continue;
    }
    ++run.steps;
    t += h;
    run.y = y_next;
    h = std::min(num.max_step, h * std::clamp(grow, 0.2, 5.0));
  }
  Eigen::Vector3d previous = ship.towPoint(t).p_W;
  for (int j = 0; j + 1 < joints; ++j)  // the cable's segments (the last joint is the vehicle's CG)
  {
    const Eigen::Vector3d x = run.y.segment<3>(3 * j);
    run.drift = std::max(run.drift, std::abs((x - previous).norm() / sim.geometry().elementLength(j) - 1.0));
    previous = x;
  }
  return run;
}
}  // namespace

int main(int argc, char** argv)
{
  std::vector<int> segments = { 100, 200, 400 };
  double window = 10.0;
  for (int i = 1; i < argc; ++i)
  {
    if (!std::strcmp(argv[i], "--segments") && i + 1 < argc)
    {
      segments.clear();
      std::stringstream list(argv[++i]);
      for (std::string item; std::getline(list, item, ',');)
        segments.push_back(std::stoi(item));
    }
    else if (!std::strcmp(argv[i], "--window") && i + 1 < argc)
      window = std::stod(argv[++i]);
    else
    {
      std::fprintf(stderr, "usage: bench_exact_jacobian [--segments 100,200,...] [--window SECONDS]\n");
      return 2;
    }
  }
  std::printf("turn_180 from t = 150 s for %.0f s: steps (rejected) of the simulator's J and of an exact dense J\n",
              window);
  std::printf("%6s %14s %14s %12s %14s\n", "nu", "simulator J", "exact J", "dense drift", "depth apart [m]");
  for (int nu : segments)
  {
    Scenario sc = loadScenarioFile(std::string(TOW_SIM_SOURCE_DIR) + "/scenarios/turn_180.yaml");
    sc.config.cable.segments = nu;
    auto ship = std::make_shared<ShipHistory>(buildShipPath(sc));
    TowRun run(sc.config, ship, sc.initial);
    run.start(0.0);
    run.advanceTo(150.0);
    const DenseRun dense = denseRun(run.simulator(), *ship, sc.config.numerics, 150.0 + window);
    const StepReport report = run.advanceTo(150.0 + window);
    const TowSnapshot s = run.snapshot();
    const Eigen::Index joints = (dense.y.size() - 2) / 6;
    const double depth_apart = std::abs(dense.y[3 * (joints - 1) + 2] - s.joints(2, s.joints.cols() - 1));
    std::printf("%6d %9d (%2d) %9d (%2d) %12.1e %14.1e\n", nu, report.steps, report.rejected, dense.steps,
                dense.rejected, dense.drift, depth_apart);
    std::fflush(stdout);
  }
  return 0;
}
