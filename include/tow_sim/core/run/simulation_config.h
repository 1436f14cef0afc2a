// Everything that describes a towed system before it runs: the cable, the vehicle, the water, the
// numerics, the winch and the seabed. Plain structs with defaults; ChainModel, Simulator and TowRun
// validate them. The configuration loader (config.h) fills one from YAML or the ROS parameter server.
#pragma once

#include "tow_sim/core/environment/seabed.h"
#include "tow_sim/core/params.h"
#include "tow_sim/core/vehicle/vehicle.h"

namespace tow_sim
{
struct SimulationConfig
{
  CableParams cable;
  VehicleParams vehicle;
  Environment environment;
  NumericsParams numerics;
  WinchParams winch;
  SeabedParams seabed;  // its grid already read from seabed.grid_file
};

}  // namespace tow_sim
