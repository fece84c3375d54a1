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
# initial height) and the bonds still intact.
#
# How solve's parameters map to Yade's (share/doc/laws.md, jcfpm; seeds/002
# Table 4.4, Eq. 4.4-4.5):
#   E -> JCFpmMat.young (k_n = 2 E R1 E R2 / (E R1 + E R2), Eq. 4.4)
#   ks_ratio -> JCFpmMat.poisson (k_s = poisson k_n for one material, Eq. 4.5)
#   tensile_strength, cohesion -> JCFpmMat.tensileStrength, cohesion (Pa,
#     times A_int = pi min(R1, R2)^2)
#   bond_friction_angle_deg (default friction_angle_deg) -> frictionAngle (phi_b)
#   friction_angle_deg -> residualFrictionAngle (phi_c of new contacts)
#   interaction_range gamma -> Bo1_Sphere_Aabb.aabbEnlargeFactor and
#     Ig2_Sphere_Sphere_ScGeom.interactionDetectionFactor during the first
#     step, when Ip2_JCFpmMat_JCFpmMat_JCFpmPhys (cohesiveTresholdIteration=1)
#     makes every pair with d <= gamma (R1 + R2) cohesive; 1 afterwards
#   damping (translational = rotational) -> NewtonIntegrator.damping (Yade
#     damps each component of the force; solve the force vector, Eq. 39-40)
#   end layers (axial.mode "layers"): the spheres whose extent along z reaches
#     within the layer thickness (default one mean diameter) of either end
#     move at half the closing speed each (or the top one at all of it with
#     "move": "top"), their other degrees of freedom blocked, as solve's.
import json
import os
import sys
import time

from yade import O
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Sphere_Aabb,
                          InteractionLoop, Ig2_Sphere_Sphere_ScGeom,
                          Ip2_JCFpmMat_JCFpmMat_JCFpmPhys,
                          Law2_ScGeom_JCFpmPhys_JointedCohesiveFrictionalPM,
                          NewtonIntegrator, JCFpmMat)
from yade.utils import sphere
from yade.minieigenHP import Vector3

t_start = time.perf_counter()
case_path, specimen_path, steps, dt, out_path = sys.argv[1:6]
steps, dt = int(steps), float(dt)


def fail(msg):
    sys.stderr.write("bench-yade: %s\n" % msg)
    sys.exit(1)


def relative(base, path):
    return path if os.path.isabs(path) else os.path.join(os.path.dirname(base), path)


with open(case_path) as f:
    case = json.load(f)
with open(specimen_path) as f:
    specimen = json.load(f)
material = case["material"]
if isinstance(material, str):
    with open(relative(case_path, material)) as f:
        material = json.load(f)
if material.get("law") != "jcfpm":
    fail("%s: law '%s': expected jcfpm" % (case_path, material.get("law")))
damping = case.get("damping", {})
alpha_t = damping.get("translational", 0.1)
if damping.get("rotational", 0.1) != alpha_t:
    fail("%s: damping: Yade has one damping for translation and rotation, "
         "the case gives two" % case_path)
if len(case["loading"]) != 1:
    fail("%s: loading: expected one stage" % case_path)
axial = case["loading"][0].get("axial", {})
if axial.get("mode") != "layers" or case["loading"][0].get("lateral", {}).get("mode", "free") != "free":
    fail("%s: loading: expected end layers (axial.mode layers) without lateral loading" % case_path)

gamma = material["interaction_range"]
phi_c = material["friction_angle_deg"]
phi_b = material.get("bond_friction_angle_deg", phi_c)
mat = O.materials.append(JCFpmMat(
    young=material["E"], poisson=material["ks_ratio"], density=material["density"],
    tensileStrength=material["tensile_strength"], cohesion=material["cohesion"],
    frictionAngle=phi_b * 3.141592653589793 / 180,
    residualFrictionAngle=phi_c * 3.141592653589793 / 180))

spheres = []
with open(relative(specimen_path, specimen["import"])) as f:
    for line in f:
        cols = line.split()
        if cols and not cols[0].startswith("#"):
            spheres.append([float(c) for c in cols[:4]])
ids = O.bodies.append([sphere((x, y, z), r, material=mat) for x, y, z, r in spheres])

O.engines = [
    ForceResetter(),
    InsertionSortCollider([Bo1_Sphere_Aabb(aabbEnlargeFactor=gamma, label="aabb")]),
    InteractionLoop(
        [Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=gamma, label="scgeom")],
        [Ip2_JCFpmMat_JCFpmMat_JCFpmPhys(cohesiveTresholdIteration=1)],
        [Law2_ScGeom_JCFpmPhys_JointedCohesiveFrictionalPM()]),
    NewtonIntegrator(damping=alpha_t),
]
O.dt = dt

# The bonds: one step at rest, every pair within range becomes cohesive at
# its present distance (no force, nothing moves); then the ranges go back to
# contact, as Yade's JCFPM scripts do.
O.run(1, True)
aabb.aabbEnlargeFactor = 1.0
scgeom.interactionDetectionFactor = 1.0
bonds = sum(1 for i in O.interactions if i.isReal and i.phys.isCohesive)

# The end layers, selected as solve selects them (solve/boundary.c).
lo = min(z - r for x, y, z, r in spheres)
hi = max(z + r for x, y, z, r in spheres)
height = hi - lo
thickness = axial.get("thickness", 2 * sum(s[3] for s in spheres) / len(spheres))
speed = axial["rate"] * height
top_only = axial.get("move", "both") == "top"
v_bottom, v_top = (0.0, -speed) if top_only else (0.5 * speed, -0.5 * speed)
bottom, top = [], []
for i, (x, y, z, r) in zip(ids, spheres):
    if z - r <= lo + thickness:
        bottom.append(i)
    elif z + r >= hi - thickness:
        top.append(i)
for layer, vz in ((bottom, v_bottom), (top, v_top)):
    for i in layer:
        s = O.bodies[i].state
        s.blockedDOFs = "xyzXYZ"
        s.vel = Vector3(0, 0, vz)
        s.angVel = Vector3(0, 0, 0)
setup = time.perf_counter() - t_start

t0 = time.perf_counter()
O.run(steps, True)
loop = time.perf_counter() - t0

# The forces of the last step act on the positions before its move, as
# solve's last history row: strain after steps - 1 moves.
load = sum(O.forces.f(i, True)[2] for i in top) - sum(O.forces.f(i, True)[2] for i in bottom)
area = 3.141592653589793 * (0.5 * specimen["diameter"]) ** 2
result = {
    "spheres": len(ids), "bonds": bonds, "steps": steps, "dt": dt,
    "setup_seconds": setup, "loop_seconds": loop,
    "stress_axial": 0.5 * load / area,
    "strain_axial": (v_bottom - v_top) * (steps - 1) * dt / height,
    "bonds_intact": sum(1 for i in O.interactions if i.isReal and i.phys.isCohesive),
    "layers": [len(bottom), len(top)],
}
with open(out_path, "w") as f:
    json.dump(result, f)
    f.write("\n")
