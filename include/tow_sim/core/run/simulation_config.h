// Everything that describes a towed system before it runs: the cable (one uniform cable, or sections with
// point bodies at joints), the vehicle, the water, the numerics, the winch and the seabed. Plain structs
// with defaults; ChainModel, Simulator and TowRun validate them. The configuration loader (config.h) fills
// one from YAML or the ROS parameter server.
#pragma once

#include <string>
#include <vector>

#include "tow_sim/core/chain/chain_model.h"
#include "tow_sim/core/environment/seabed.h"
#include "tow_sim/core/params.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
// A point body on the cable as configured (cable.bodies[i], docs/physics.md §11): where it sits along the
// unstretched cable from the tow point, and its mass and loads (JointBody; its joint follows from `at`).
struct CableBodyParams
{
  double at = 0.0;  // [m] from the tow point along the unstretched cable; must fall on a joint
  JointBody body;   // body.joint is set from `at` by jointBodies()
};

struct SimulationConfig
{
  // The whole cable: with `sections`, its length and segments are the sections' sums, its other keys
  // the defaults of every section (the loader fills them in), and its load limits the whole cable's.
  CableParams cable;
  std::vector<CableParams> sections;    // from the tow point aft; empty: one uniform cable, `cable`
  std::vector<CableBodyParams> bodies;  // point bodies at joints, any order
  VehicleParams vehicle;
  Environment environment;
  NumericsParams numerics;
  WinchParams winch;
  SeabedParams seabed;  // its grid already read from seabed.grid_file
};

// The cable's sections from the tow point aft: `sections`, or `cable` alone.
std::vector<CableParams> cableSections(const SimulationConfig& config);
// The bodies with their joints (segments aft of them) found from `at`. Throws std::invalid_argument naming
// `prefix`cable.bodies[i].at when one is not on a joint within 1e-6 m (the nearest joints' distances in
// the message), or is at the tow point or beyond the cable's end.
std::vector<JointBody> jointBodies(const SimulationConfig& config, const std::string& prefix = "");
// The sections' checks the loader makes beyond each section's own (std::invalid_argument naming the key under
// `prefix`): lengths adding up to cable.length, at most 100000 segments in all, all elastic or all rigid,
// the bodies on joints; with the winch, no body inside the first section (the winch re-meshes it).
void validateSectionsAndBodies(const SimulationConfig& config, const std::string& prefix = "");

}  // namespace tow_sim
