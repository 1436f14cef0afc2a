// The parameter tables of the core's structs (param_table.h): every key once, with its unit, range, default
// and meaning. validate() of each struct checks its table, then what a table cannot say (matrices, tables,
// keys whose limits involve another struct).
#pragma once

#include "tow_sim/core/depth_autopilot.h"
#include "tow_sim/core/fins.h"
#include "tow_sim/core/param_table.h"
#include "tow_sim/core/params.h"
#include "tow_sim/core/seabed.h"
#include "tow_sim/core/vehicle.h"

namespace tow_sim
{
const ParamTable<CableParams>& cableParams();
const ParamTable<WaveParams>& waveParams();
const ParamTable<Environment>& environmentParams();
const ParamTable<NumericsParams>& numericsParams();
const ParamTable<WinchParams>& winchParams();
const ParamTable<SeabedParams>& seabedParams();
const ParamTable<FinPairParams>& finParams();
const ParamTable<VehicleParams>& vehicleParams();
const ParamTable<EndElementParams>& endElementParams();
const ParamTable<DepthAutopilotParams>& autopilotParams();

}  // namespace tow_sim
