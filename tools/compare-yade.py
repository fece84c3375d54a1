# The Yade side of tools/compare-yade: the JCFPM test of a solve case file
# (a UCS with end layers, or platens: a Brazilian test), in Yade, on a sphere list, with solve's time step, to the case's stop
# (its strain_axial and stress_drop, checked on the history rows, the drop
# once bonds have broken) or STEPS
# loading steps, writing a history row every EVERY steps. Run by
#
#   yade -j1 -n -x tools/compare-yade.py CASE.json SPHERES.txt DT STEPS EVERY OUT [BRANCH]
#
# BRANCH: the branch vectors of Yade's shear increment, radius (Yade's
# default) or contact (tools/yade_jcfpm.py, build).
# (tools/yade_jcfpm.py maps the parameters and sets up the bonds and end
# layers). Writes OUT.csv, the rows at steps 0, EVERY, 2 EVERY, ... and the
# last: step, axial strain (the layers' or walls' relative displacement
# over the initial height or gap, from their positions), axial force (what
# the bonds and contacts exert on the layers or walls, the mean of the two
# ends, compression positive; the forces of the step, on the positions before its move, as
# solve's history rows), and the bonds broken in tension and in shear so
# far (Law2's nbTensCracks, nbShearCracks); and OUT.json: spheres, bonds at
# start, end-layer sizes.
import json
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(sys.argv[0])))
import yade_jcfpm as yj  # noqa: E402
from yade import O  # noqa: E402
from yade.wrapper import PyRunner  # noqa: E402
from yade.minieigenHP import Vector3  # noqa: E402

case_path, spheres_path, dt, steps, every, out = sys.argv[1:7]
dt, steps, every = float(dt), int(steps), int(every)
branch = sys.argv[7] if len(sys.argv) > 7 else "radius"
case, material, alpha, axial, ax = yj.read_case(case_path)
layers = axial["mode"] == "layers"
spheres = yj.read_spheres(spheres_path)

stop = case.get("stop", {})
stop_strain = stop.get("strain_axial", float("inf"))
stop_drop = stop.get("stress_drop", 0.0)
rows = []
state = {"peak": 0.0}


def record():
    k = O.iter - state["iter0"]
    if k == 0:
        for i, v in state["start"]:
            O.bodies[i].state.vel = v
    if k % every and k != steps - 1:
        return
    zb, zt = O.bodies[state["b"]].state.pos[ax], O.bodies[state["t"]].state.pos[ax]
    strain = ((zb - state["zb0"]) - (zt - state["zt0"])) / state["height"]
    load = yj.axial_load(state["bottom"], state["top"], ax)
    rows.append((k, strain, load, state["law"].nbTensCracks, state["law"].nbShearCracks))
    state["peak"] = max(state["peak"], load)
    # The drop is armed once bonds break (solve arms it once the loading's
    # start has died away, earlier).
    armed = state["law"].nbTensCracks + state["law"].nbShearCracks > 0
    if k > 0 and (strain >= stop_strain or (armed and load < stop_drop * state["peak"])):
        O.pause()


ids, bonds, law = yj.build(material, spheres, alpha, dt,
                           [PyRunner(command="record()", iterPeriod=1)], branch,
                           walls=not layers)
if layers:
    bottom, top, v_bottom, v_top, height = yj.end_layers(spheres, ids, axial)
else:
    bottom, top, v_bottom, v_top, height = yj.platens(spheres, material, axial, ax, branch)
# The ends start moving in the first step, as solve's: at rest while its
# forces are computed (Yade would otherwise take their speed into that
# step's shear increments, with no motion behind it), then at their speed.
state["start"] = [(i, Vector3(O.bodies[i].state.vel)) for i in bottom + top]
for i in bottom + top:
    O.bodies[i].state.vel = O.bodies[i].state.vel * 0
state.update(iter0=O.iter, b=bottom[0], t=top[0], height=height, bottom=bottom, top=top,
             law=law, zb0=O.bodies[bottom[0]].state.pos[ax], zt0=O.bodies[top[0]].state.pos[ax])
O.run(steps, True)
O.wait()

with open(out + ".csv", "w") as f:
    f.write("step,strain_axial,force_axial,bonds_broken_tension,bonds_broken_shear\n")
    for r in rows:
        f.write("%d,%.12g,%.12g,%d,%d\n" % r)
with open(out + ".json", "w") as f:
    json.dump({"spheres": len(ids), "bonds": bonds,
               "layers": [len(bottom), len(top)] if layers else None,
               "height": height, "dt": dt, "steps": rows[-1][0], "branch": branch}, f)
    f.write("\n")
