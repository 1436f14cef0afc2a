"""tow_sim from Python: the ROS-free core with NumPy (docs/python.md).

    import tow_sim
    cfg = tow_sim.load_config("config/tow_sim.yaml")     # or tow_sim.Config.from_dict({...})
    eq = tow_sim.steady_tow(cfg, speed=2.0, cable_out=500.0)
    run = tow_sim.Run(tow_sim.load_scenario("scenarios/turn_180.yaml"))
    series = run.run(until=600.0, every=1.0)             # timeseries.csv's columns as arrays

After `source devel/setup.bash` this package also holds the generated messages (tow_sim.msg, tow_sim.srv).
Errors are Python exceptions: ValueError for a bad key or value (the message names the key and the range),
RuntimeError for a run that diverged. Stepping releases the GIL.
"""
from tow_sim._core import (  # noqa: F401  (the module's interface)
    Config,
    Run,
    Scenario,
    Snapshot,
    load_config,
    load_scenario,
    modes,
    plan_cable_out,
    response,
    run_batch,
    sea_state,
    steady_tow,
    strumming,
    towing_chart,
)

__all__ = [
    "Config",
    "Run",
    "Scenario",
    "Snapshot",
    "load_config",
    "load_scenario",
    "modes",
    "plan_cable_out",
    "response",
    "run_batch",
    "sea_state",
    "steady_tow",
    "strumming",
    "towing_chart",
]
