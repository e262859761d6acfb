"""Bring your own building and ground motion: a short example for OpenSeesPy users.

In an OpenSeesPy script the ground motion is usually a numpy array handed to
``timeSeries('Path', ..., '-values', *accel, '-dt', dt)`` and the frame is a set of
nodes, masses and elements. slipload takes the same array directly, and a shear building
as a dict with the fields of a building file (docs/REFERENCE.md): floor masses, storey
stiffnesses, damping, storey heights, and one friction damper per floor on a brace.

Run it from the repository root or from examples/:  python examples/own_building_and_record.py
"""

import pathlib

import numpy as np

import slipload

HERE = pathlib.Path(__file__).resolve().parent

# --- the ground motion: an array you already have, in g, at a uniform step -------------
# (here taken from a record of the repository; in your script it is the array you give
# OpenSees' Path time series)
elcentro = slipload.read_record(HERE.parent / "records" / "I-ELC180.AT2")
accel_g = elcentro.accel / 9.80665  # your numpy array, in g
dt = elcentro.dt
record = slipload.record_from_array(np.ascontiguousarray(accel_g), dt, units="g", name="El Centro 180")
print(record)

# --- the building: a two-storey shear frame with a friction damper on each floor -------
building = {
    "name": "two-storey frame",
    "floor_masses": ["2.0e5 kg", "1.8e5 kg"],
    "storey_stiffness": ["180 MN/m", "140 MN/m"],
    "damping": {"modal": {"ratio": 0.02}},
    "storey_heights": ["3.5 m", "3.2 m"],
    "dissipators": [
        {"floor": 1, "brace_stiffness": "200 MN/m", "mass": "200 kg", "slip_load": "150 kN"},
        {"floor": 2, "brace_stiffness": "160 MN/m", "mass": "200 kg", "slip_load": "100 kN"},
    ],
}
scene = slipload.load_scene(building, record=record)
print(scene, "periods (s):", np.round(scene.periods, 3))

# --- one run, with histories to plot or compare with your OpenSees model ----------------
result = slipload.simulate(scene, outputs=["histories", "energies"])
print("peak drift ratio per storey:", np.round(result.peak_drift_ratio, 5))
print("peak base shear: %.0f kN" % (result.peak_base_shear / 1e3))
roof = result.history["x2_m"]  # roof displacement relative to the ground, m, one value per step
print("peak roof displacement: %.4f m at t = %.2f s" % (np.abs(roof).max(), result.history.time[np.abs(roof).argmax()]))

# --- which slip loads? one call runs every pair on a 9 x 9 grid, in parallel ------------
f1, f2 = np.meshgrid(np.linspace(0, 600e3, 9), np.linspace(0, 600e3, 9), indexing="ij")
designs = np.column_stack([f1.ravel(), f2.ravel()])
grid = slipload.batch_designs(scene, [record], designs, progress=False)
peak = grid["peak_drift_ratio"][:, 0, :].max(axis=1)  # worst storey, the one record
best = int(peak.argmin())
print(
    "lowest peak drift ratio %.5f at slip loads %.0f / %.0f kN (bare frame: %.5f)"
    % (peak[best], designs[best, 0] / 1e3, designs[best, 1] / 1e3, peak[0])
)
