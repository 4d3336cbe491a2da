"""A scene built as a Python dict: a block of sand dropped on a rigid floor
block, run for 0.3 s, its fields read as NumPy arrays.

Run it with `python examples/python/scene_from_dict.py`.
"""

import numpy as np

import mpdem

scene = mpdem.Scene.from_dict(
    {
        "name": "sand_drop",
        "grid": {
            "origin": [0.0, 0.0],
            "cell_size": 0.02,
            "cells": [50, 30],
            "edges": {"left": "Slip", "right": "Slip"},
        },
        "time": {"dt": 5e-5, "end": 0.3},
        "gravity": [0.0, -9.81],
        "materials": [
            {
                "name": "sand",
                "density": 1800.0,
                "model": {
                    "DruckerPrager": {
                        "youngs_modulus": 5e6,
                        "poisson_ratio": 0.3,
                        "friction_angle": 30.0,
                    }
                },
            }
        ],
        "bodies": [
            {
                "name": "sand",
                "material": "sand",
                "shape": {"Rectangle": {"min": [0.35, 0.15], "max": [0.65, 0.45]}},
            }
        ],
        "blocks": [
            {
                "name": "floor",
                "shape": {"Cuboid": {"half_extents": [0.5, 0.05]}},
                "position": [0.5, 0.05],
                "motion": "Fixed",
                "contact": {"normal_stiffness": 1e8, "tangential_stiffness": 1e8, "friction": 0.5},
            }
        ],
        "probes": [{"name": "centre", "body": "sand", "at": [0.5, 0.3]}],
    }
)

sim = mpdem.Simulation(scene)
sim.run()
sand = sim.body("sand")
print(f"{len(sand)} points, mass {sand.mass.sum():.1f} kg/m, t = {sim.time:.3f} s")
print(f"lowest point at y = {sand.position[:, 1].min():.4f} m (floor top at 0.1 m)")
mean_stress = sand.stress[:, [0, 1, 3]].mean(axis=1)
print(f"mean stress from {mean_stress.min():.0f} to {mean_stress.max():.0f} Pa")
print(f"floor reaction {sim.block('floor').force} N/m, weight {sand.mass.sum() * 9.81:.0f} N/m")
probe = sim.series("probes")
print(f"centre fell {-probe.uy[-1]:.4f} m")
print("state hash", sim.state_hash())
