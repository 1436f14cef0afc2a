#!/usr/bin/env python3
"""Design a two-part tow with SciPy: the clump weight and main-cable length that put the towfish at a target depth
for the least cost, with the tension at the ship under a limit (docs/python.md, "Examples").

    optimise_depressor.py [--speed 2.0] [--target-depth 400] [--tension-limit 30000]
                          [--cable-cost 20] [--clump-cost 5] [--quick]

The tow: a main cable (its length the design variable; 17.3 mm armoured, 1.2 kg/m) down to a clump weight, then
200 m of near-neutral tether to the default towfish. For each clump mass, the cable out that reaches the depth
comes from the cable-out planner (the steady tow, bisected); SciPy's bounded scalar search then minimises
cable_cost * cable out [per m] + clump_cost * clump mass [per kg] over the clump masses whose tension at the ship
stays under the limit. --quick: a coarser cable, for the tests.
"""
import argparse
import math

from scipy.optimize import minimize_scalar

import tow_sim

TETHER = 200.0  # [m]


def config(clump_mass, main_length, segment_length):
    """The two-part tow with `clump_mass` [kg] at the end of `main_length` [m] of main cable."""
    return tow_sim.Config.from_dict({
        "cable": {
            "diameter": 0.0173, "mass_per_length": 1.2, "normal_drag_coefficient": 1.5,
            "sections": [
                {"length": main_length, "segments": max(1, round(main_length / segment_length))},
                {"length": TETHER, "segments": max(1, round(TETHER / segment_length)), "diameter": 0.02,
                 "mass_per_length": 0.35, "normal_drag_coefficient": 1.2},
            ],
            "bodies": [{"at": main_length, "mass": float(clump_mass), "displaced_volume": clump_mass / 7800.0,
                        "drag_area": 0.4, "added_mass": 0.1 * clump_mass}],
        },
        "winch": {"min_length": TETHER + 50.0, "max_length": 8000.0},
    })


def design(clump_mass, args):
    """The cable out [m] that reaches the target depth with this clump, and the tension at the ship [N] then."""
    cfg = config(clump_mass, 1000.0, args.segment_length)
    plan = tow_sim.plan_cable_out(cfg, speed=args.speed, target_depth=args.target_depth)
    if not plan["reachable"]:
        return math.inf, math.inf
    return plan["cable_out"], plan["tension_ship"]


def cost(clump_mass, args):
    cable_out, tension = design(clump_mass, args)
    over = max(0.0, tension - args.tension_limit)  # a steep penalty past the limit keeps the search inside it
    return args.cable_cost * cable_out + args.clump_cost * clump_mass + 1e3 * over


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--speed", type=float, default=2.0, help="[m/s]")
    parser.add_argument("--target-depth", type=float, default=400.0, help="[m]")
    parser.add_argument("--tension-limit", type=float, default=30000.0, help="[N] at the ship")
    parser.add_argument("--cable-cost", type=float, default=20.0, help="per metre of main cable out")
    parser.add_argument("--clump-cost", type=float, default=5.0, help="per kg of clump")
    parser.add_argument("--min-clump", type=float, default=100.0, help="[kg]")
    parser.add_argument("--max-clump", type=float, default=3000.0, help="[kg]")
    parser.add_argument("--quick", action="store_true", help="20 m segments instead of 10 m")
    args = parser.parse_args(argv)
    args.segment_length = 20.0 if args.quick else 10.0
    best = minimize_scalar(cost, bounds=(args.min_clump, args.max_clump), args=(args,), method="bounded",
                           options={"xatol": 1.0})
    mass = float(best.x)
    cable_out, tension = design(mass, args)
    eq = tow_sim.steady_tow(config(mass, 1000.0, args.segment_length), speed=args.speed, cable_out=cable_out)
    print(f"clump {mass:.1f} kg, cable out {cable_out:.1f} m: towfish at {eq.depth:.2f} m, tension at the ship "
          f"{tension:.0f} N (limit {args.tension_limit:.0f}), cost {best.fun:.0f}")
    return {"clump_mass": mass, "cable_out": cable_out, "depth": eq.depth, "tension_ship": tension, "cost": best.fun}


if __name__ == "__main__":
    main()
