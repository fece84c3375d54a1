# The Yade side of tools/bench-yade: the JCFPM UCS of a solve case file, in
# Yade, on the sphere list the case's specimen imports. Run by
#
#   yade -j1 -n -x tools/bench-yade.py CASE.json SPECIMEN.json STEPS DT OUT.json
#
# CASE.json is the solve case (its material, damping and end-layer loading
# are used), SPECIMEN.json a pack --config file with "import" (the sphere
# list, "x y z r" per line) and "diameter"; DT the time step in s (solve's).
# Writes one JSON object to OUT.json: spheres, bonds at start, the wall
# seconds of setup and of the N loading steps, and after them the axial
# stress and strain as solve measures them (end-layer forces over the
# specimen's cross-section, the layers' relative displacement over the
# initial height) and the bonds still intact. tools/yade_jcfpm.py sets the
# run up and says how the parameters map.
import json
import os
import sys
import time

t_start = time.perf_counter()
sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
import yade_jcfpm as yj  # noqa: E402
from yade import O  # noqa: E402

case_path, specimen_path, steps, dt, out_path = sys.argv[1:6]
steps, dt = int(steps), float(dt)
case, material, alpha, axial, ax = yj.read_case(case_path)
if axial["mode"] != "layers":
    yj.fail("%s: expected end layers (axial.mode layers)" % case_path)
with open(specimen_path) as f:
    specimen = json.load(f)
spheres = yj.read_spheres(yj.relative(specimen_path, specimen["import"]))
ids, bonds, law = yj.build(material, spheres, alpha, dt)
bottom, top, v_bottom, v_top, height = yj.end_layers(spheres, ids, axial)
setup = time.perf_counter() - t_start

t0 = time.perf_counter()
O.run(steps, True)
loop = time.perf_counter() - t0

# The forces of the last step act on the positions before its move, as
# solve's last history row: strain after steps - 1 moves.
area = yj.PI * (0.5 * specimen["diameter"]) ** 2
result = {
    "spheres": len(ids), "bonds": bonds, "steps": steps, "dt": dt,
    "setup_seconds": setup, "loop_seconds": loop,
    "stress_axial": yj.axial_load(bottom, top) / area,
    "strain_axial": (v_bottom - v_top) * (steps - 1) * dt / height,
    "bonds_intact": sum(1 for i in O.interactions if i.isReal and i.phys.isCohesive),
    "layers": [len(bottom), len(top)],
}
with open(out_path, "w") as f:
    json.dump(result, f)
    f.write("\n")
