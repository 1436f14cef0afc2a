// tow_sim_urdf: prints the towed vehicle's URDF (robot_description) for a configuration in the node's YAML
// format: the vehicle section, the node's vehicle_frame and vehicle_diameter, and sensor_frames.
//   tow_sim_urdf [CONFIG.yaml]        (no file: the defaults)
// tow_sim.launch sets robot_description from it; robot_state_publisher then publishes the fin and sensor
// frames from tow_sim_node's joint_states.
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <exception>
#include <string>

#include "tow_sim/config/config.h"
#include "tow_sim/scenario/towfish_urdf.h"

int main(int argc, char** argv)
{
  if (argc > 2 || (argc == 2 && argv[1][0] == '-'))
  {
    std::fprintf(stderr, "usage: tow_sim_urdf [CONFIG.yaml]\n");
    return 2;
  }
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
