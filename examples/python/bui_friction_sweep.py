"""The toe of Bui et al.'s (2008) aluminium-rod collapse against the friction
angle: the shipped scene at a coarser cell (L0/40), its friction angle swept
from 15 to 30 degrees, each deposit's toe taken where it thins below 5% of
the column's height (the `fronts` series), plotted beside the experiment's.

Run it with `python examples/python/bui_friction_sweep.py`; it writes
out/bui_friction_sweep.png under the repository's root and takes about a
minute on 2 cores.
"""

import math
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

import mpdem

L0 = 0.2  # the column's length (m)
MEASURED_TOE = 0.98  # the experiment's (x_toe - L0) / L0 where 5% of H0 thick
ANGLES = [15.0, 17.5, 19.8, 22.5, 25.0, 30.0]

ROOT = Path(__file__).resolve().parents[2]
base = mpdem.Scene.from_file(ROOT / "scenes" / "granular_collapse_bui.ron")
base.set("grid.cell_size", 0.005)  # L0/40
base.set("grid.cells", [160, 24])

toes = []
for angle in ANGLES:
    scene = mpdem.Scene.from_dict(base.to_dict())
    scene.set("materials[rods].model.DruckerPrager.friction_angle", angle)
    # Jaky's K0 = 1 - sin(phi), as the shipped scene takes for 19.8 degrees.
    k0 = 1.0 - math.sin(math.radians(angle))
    scene.set("bodies[column].initial_stress", {"Geostatic": {"k0": k0}})
    sim = mpdem.Simulation(scene)
    sim.run()
    toe = sim.series("fronts").toe_5[-1]
    toes.append((toe - L0) / L0)
    print(f"phi = {angle:4.1f} deg: toe (x - L0) / L0 = {toes[-1]:.3f}")

fig, ax = plt.subplots(figsize=(6, 4))
ax.plot(ANGLES, toes, "o-", label="mpdem, L0/40, defaults")
ax.plot([19.8], [MEASURED_TOE], "ks", label="experiment (Bui et al. 2008, phi = 19.8)")
ax.set_xlabel("friction angle (degrees)")
ax.set_ylabel("run-out (x_toe - L0) / L0 at 5% of H0")
ax.set_title("Aluminium-rod collapse: toe against friction angle")
ax.grid(True, alpha=0.3)
ax.legend()
fig.tight_layout()
figure = ROOT / "out" / "bui_friction_sweep.png"
figure.parent.mkdir(exist_ok=True)
fig.savefig(figure, dpi=120)
print(f"wrote {figure}")
