#include "core/random_chain.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace tow_sim
{
namespace test
{
Eigen::Vector3d randomVector(std::mt19937& rng, double scale)
{
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Eigen::Vector3d(u(rng), u(rng), u(rng));
}

std::shared_ptr<Vehicle> makeRandomVehicle(EndKind kind, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  VehicleParams p;
  p.tail_from_bail = 0.5 + 2.5 * u(rng);
  p.nose_from_bail = u(rng);
  auto along = [&] { return -p.nose_from_bail + (p.nose_from_bail + p.tail_from_bail) * u(rng); };
  p.cg_from_bail = along();
  p.cb_from_bail = along();
  p.horizontal_fin_from_bail = along();
  p.vertical_fin_from_bail = along();
  p.mass = 20.0 + 300.0 * u(rng);
  p.displaced_volume = 0.3 * u(rng);
  const Eigen::Matrix3d a = Eigen::Matrix3d::Random();
  p.inertia_B = a * a.transpose() + Eigen::Vector3d(1.0, 20.0, 20.0).asDiagonal().toDenseMatrix();
  p.c1 = 50.0 * u(rng);
  p.c2 = 400.0 * u(rng);
  p.added_mass_a = 200.0 * u(rng);
  const Matrix6d b = Matrix6d::Random();
  p.added_mass_b = 30.0 * b * b.transpose();
  p.added_mass_approach = kind == EndKind::kVehicleA ? AddedMassApproach::kA : AddedMassApproach::kB;
  p.munk_terms = kind == EndKind::kVehicleBMunk;
  p.thrust_offset_z = u(rng) - 0.5;
  p.rudder.center_of_pressure_offset = 0.05;
  return std::make_shared<Vehicle>(p);
}

namespace
{
CableParams randomCable(int segments, bool elastic, std::mt19937& rng)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  CableParams cable;
  cable.segments = segments;
  cable.length = 20.0 + 480.0 * u(rng);
  cable.diameter = 0.005 + 0.05 * u(rng);
  cable.mass_per_length = 0.1 + 3.0 * u(rng);
  cable.normal_drag_coefficient = 2.0 * u(rng);
  cable.tangential_drag_coefficient = 0.05 * u(rng);
  cable.added_mass_coefficient = 1.5 * u(rng);
  cable.tangential_drag_model = u(rng) < 0.5 ? TangentialDragModel::kPode : TangentialDragModel::kQuadratic;
  if (elastic)
  {
    cable.axial_stiffness = std::pow(10.0, 5.0 + 3.0 * u(rng));
    cable.axial_damping = 0.01 * *cable.axial_stiffness * u(rng);
  }
  return cable;
}
}  // namespace

RandomCase makeRandomCase(int segments, std::mt19937& rng, EndKind kind, bool winch, bool seabed, bool elastic)
{
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const CableParams cable = randomCable(segments, elastic, rng);
  EndElementParams end;
  end.length = 0.5 + 4.0 * u(rng);
  end.mass = 10.0 + 500.0 * u(rng);
  end.displaced_volume = 0.3 * u(rng);
  end.cg_from_bail = end.length * u(rng);
  end.cb_from_bail = end.length * u(rng);
  end.diameter = 0.1 + 0.5 * u(rng);
  Environment env;
  env.current_W = randomVector(rng, 1.5);

  RandomCase c;
  std::shared_ptr<const EndBody> end_body;
  if (kind == EndKind::kRigid)
    end_body = std::make_shared<RigidEndElement>(end, NumericsParams());
  else
    end_body = makeRandomVehicle(kind, rng);
  c.model = std::make_shared<ChainModel>(cable, end_body, env, NumericsParams());
  c.ship.p_W = randomVector(rng, 100.0);
  if (seabed)
    c.ship.p_W.z() = -600.0;  // the whole chain under water
  c.ship.v_W = randomVector(rng, 3.0);
  c.ship.a_W = randomVector(rng, 0.5);
  c.geometry = c.model->initialGeometry();
  c.data = c.model->initialData(0.0);
  if (kind != EndKind::kRigid)
    c.model->endBody().command(c.data.actuators, 0.0, 0.6 * (u(rng) - 0.5), 0.6 * (u(rng) - 0.5),
                               400.0 * (u(rng) - 0.5));
  double payout_rate = 0.0;
  if (winch)
  {
    payout_rate = 4.0 * (u(rng) - 0.5);
    c.geometry.first_length = (0.5 + u(rng)) * c.model->nominalSegmentLength();
    c.geometry.first_rate = payout_rate;
    c.geometry.first_acceleration = 2.0 * (u(rng) - 0.5);
  }
  const int n = c.model->jointCount();
  c.x.resize(3, n);
  c.v.resize(3, n);
  Eigen::Vector3d x_f = c.ship.p_W, v_f = c.ship.v_W;
  for (int e = 0; e < n; ++e)
  {
    const Eigen::Vector3d s = randomVector(rng, 1.0).normalized();
    const Eigen::Vector3d omega = randomVector(rng, 0.3);
    const bool stretches = elastic && e < c.geometry.segments;
    const double d = c.geometry.elementLength(e) * (stretches ? 1.0 + 0.002 * u(rng) : 1.0);
    c.x.col(e) = x_f + d * s;
    c.v.col(e) = v_f + d * omega.cross(s);  // consistent with the length constraint
    if (stretches)
      c.v.col(e) += 0.05 * (u(rng) - 0.5) * s;  // an elastic segment's stretch rate
    if (e == 0)
      c.v.col(e) += payout_rate * s;  // ... and the winch's rate
    x_f = c.x.col(e);
    v_f = c.v.col(e);
  }
  if (seabed)
  {
    // A flat bottom 0.1 m above the median depth of the joints: about half of them in it, none on it.
    std::vector<double> z(static_cast<size_t>(n));
    for (int j = 0; j < n; ++j)
      z[static_cast<size_t>(j)] = c.x(2, j);
    std::nth_element(z.begin(), z.begin() + n / 2, z.end());
    SeabedParams bottom;
    bottom.type = SeabedParams::Type::kFlat;
    bottom.depth = -z[static_cast<size_t>(n / 2)] - 0.1;
    c.model = std::make_shared<ChainModel>(cable, end_body, env, NumericsParams(), std::make_shared<Seabed>(bottom));
  }
  return c;
}

}  // namespace test
}  // namespace tow_sim
