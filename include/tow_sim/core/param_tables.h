// The parameter tables of params.h's structs (param_table.h): every key once, with its unit, range, default
// and meaning. validate() of each struct checks its table, then what a table cannot say (matrices, tables,
// keys whose limits involve another struct). The tables of the seabed, fins, vehicle and autopilot are
// declared beside their structs.
#pragma once

#include "tow_sim/core/param_table.h"
#include "tow_sim/core/params.h"

namespace tow_sim
{
const ParamTable<CableParams>& cableParams();
const ParamTable<WaveParams>& waveParams();
const ParamTable<Environment>& environmentParams();
const ParamTable<NumericsParams>& numericsParams();
const ParamTable<WinchParams>& winchParams();
const ParamTable<EndElementParams>& endElementParams();
const ParamTable<DepressorParams>& depressorParams();

}  // namespace tow_sim
