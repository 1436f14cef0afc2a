// Random chains for the tests that compare the O(nu) solver and stepper with dense references: random
// cable and end-body parameters, currents, ship motion, fins and thrust, a winch paying out, and joint
// positions and velocities that satisfy the length constraints.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <random>

#include "tow_sim/core/chain/chain_model.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
namespace test
{
struct RandomCase
{
  std::shared_ptr<ChainModel> model;
  ChainGeometry geometry;  // the first segment paid out
  ChainData data;          // the actuators commanded
  ShipEndState ship;
  Eigen::Matrix3Xd x, v;
};

enum class EndKind
{
  kRigid,
  kVehicleA,
  kVehicleB,
  kVehicleBMunk
};

Eigen::Vector3d randomVector(std::mt19937& rng, double scale);

// A vehicle with random geometry, inertia with products, fins mid-travel and thrust.
std::shared_ptr<Vehicle> makeRandomVehicle(EndKind kind, std::mt19937& rng);

// winch: the first segment is paid out (random length, rate and acceleration) while the rest is not.
// seabed: a flat bottom through the middle of the chain's depth range (some joints in it).
// elastic: an elastic cable (EA 1e5 .. 1e8 N, some axial damping), each segment stretched up to 0.2 % and
// stretching at a random rate (no winch then).
RandomCase makeRandomCase(int segments, std::mt19937& rng, EndKind kind = EndKind::kRigid, bool winch = false,
                          bool seabed = false, bool elastic = false);

}  // namespace test
}  // namespace tow_sim
