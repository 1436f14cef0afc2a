// tow_sim_urdf: prints the towed vehicle's URDF (robot_description) for a configuration in the node's YAML
// format: the vehicle section, the node's vehicle_frame and vehicle_diameter, and sensor_frames.
//   tow_sim_urdf [CONFIG.yaml]        (no file: the defaults)
// tow_sim.launch sets robot_description from it; robot_state_publisher then publishes the fin and sensor
// frames from tow_sim_node's joint_states.
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <exception>
#include <string>

#include "cli.h"
#include "tow_sim/config/config.h"
#include "tow_sim/scenario/towfish_urdf.h"

namespace
{
constexpr char kTool[] = "tow_sim_urdf";
constexpr char kUsage[] = "tow_sim_urdf [CONFIG.yaml]";
constexpr char kHelp[] = R"(
Prints the towed vehicle's URDF (robot_description) for a configuration in the node's YAML format:
from its vehicle section, the node's vehicle_frame and vehicle_diameter, and sensor_frames.
tow_sim.launch sets robot_description from it.

Arguments:
  CONFIG.yaml   the configuration (config/tow_sim.yaml's format). Default: no file, the defaults.
  -h, --help    prints this help and exits.

Output: the URDF on stdout; no file.
Exit codes: 0 done; 2 bad arguments or configuration.
)";
}  // namespace

int main(int argc, char** argv)
{
  if (tow_sim::cli::wantsHelp(argc, argv))
    return tow_sim::cli::printHelp(kUsage, kHelp);
  if (argc > 2)
    return tow_sim::cli::fail(kTool, kUsage, "takes at most one argument, CONFIG.yaml");
  if (argc == 2 && argv[1][0] == '-')
    return tow_sim::cli::fail(kTool, kUsage, std::string("unknown argument '") + argv[1] + "'");
  try
  {
    YAML::Node root;
    tow_sim::SimulationConfig config;
    if (argc == 2)
    {
      config = tow_sim::loadConfigFile(argv[1]);
      root = YAML::LoadFile(argv[1]);
    }
    const tow_sim::TowfishDescription description = tow_sim::readTowfishDescription(root);
    std::fputs(tow_sim::towfishUrdf(config.vehicle, description).c_str(), stdout);
    return 0;
  }
  catch (const std::exception& e)
  {
    std::fprintf(stderr, "tow_sim_urdf: %s\n", e.what());
    return 2;
  }
}
