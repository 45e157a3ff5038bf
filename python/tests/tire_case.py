"""The small generated tire of the tire tests and a short cleat rig (shared by test_tire.py
and test_tire_studies.py; the session fixture `reduced` is in conftest.py)."""

import tomllib

# The small generated tire of the app tests (apps/tire/tests/common: 96 x 8 elements, isotropic
# tread, 33 contact nodes, 50 free-node modes; reduced in about 2 s) and a short rig (0.05 s
# settling + 0.05 s record at 60 km/h: 500 steps, about 1 s) as the TOML the CLI reads.
TIRE_TOML = """
[tire.generator]
circumferential_divisions = 96
section_divisions = 8
thickness_divisions = 1
bead_elements = 1
patch_half_angle_deg = 20.0
[tire.generator.tread]
young = 150e6
poisson = 0.45
density = 1500.0
[tire.generator.carcass]
modulus = 0.0
[tire.reduction]
contact_nodes = 33
free_modes = 50
"""
RIG_TOML = """
vtk_interval = 0
vtk_tire_interval = 0
[rig]
settle_time = 0.05
record_time = 0.05
"""
TIRE = tomllib.loads(TIRE_TOML)["tire"]
RIG = tomllib.loads(RIG_TOML)
