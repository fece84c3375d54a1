# The JCFPM UCS of a solve case file, set up in Yade: what tools/bench-yade.py
# and tools/compare-yade.py share. Imported by those scripts when Yade runs
# them (yade -j1 -n -x SCRIPT ...); not a script itself.
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
#     damps each component of the force: solve's damping.form "components";
#     solve's default, "vector", damps the force vector, Eq. 39-40)
#   end layers (axial.mode "layers", the UCS): the spheres whose extent along
#     z reaches within the layer thickness (default one mean diameter) of
#     either end move at half the closing speed each (or the top one at all
#     of it with "move": "top"), their other degrees of freedom blocked, as
#     solve's (solve/boundary.c).
#   platens (axial.mode "strain_rate" or "velocity", e.g. the Brazilian
#     test, along x, y or z): two Yade walls placed where they touch the
#     specimen, moving as solve's platens (solve/platens.c). solve's platen
#     contact is Cundall-Strack with twice the stiffnesses of a sphere's
#     contact with its mirror image, k_n = 2 E r, k_s = 2 ks_ratio E r, and
#     the friction contact.platen_friction (default contact.friction, 0.5).
#     Yade's wall-sphere JCFPM contact has k_n = 2 E_w r E r / (E_w r + E r)
#     (the wall's "radius" is the sphere's): a wall of JCFpmMat with
#     E_w = 1e12 E gives 2 E r (1 - 1e-12), k_s likewise, its friction
#     min(phi_c, atan(platen_friction)), never cohesive (another type).
import json
import math
import os
import sys

from yade import O
from yade.wrapper import (ForceResetter, InsertionSortCollider, Bo1_Sphere_Aabb,
                          InteractionLoop, Ig2_Sphere_Sphere_ScGeom, Bo1_Wall_Aabb,
                          Ig2_Wall_Sphere_ScGeom,
                          Ip2_JCFpmMat_JCFpmMat_JCFpmPhys,
                          Law2_ScGeom_JCFpmPhys_JointedCohesiveFrictionalPM,
                          NewtonIntegrator, JCFpmMat)
from yade.utils import sphere, wall
from yade.minieigenHP import Vector3

PI = 3.141592653589793


def fail(msg):
    sys.stderr.write("%s: %s\n" % (os.path.basename(sys.argv[0]), msg))
    sys.exit(1)


def relative(base, path):
    return path if os.path.isabs(path) else os.path.join(os.path.dirname(base), path)


def read_case(case_path):
    """The case's material, damping and loading (its one stage's "axial"),
    checked to be a JCFPM test Yade can run the same way: end layers along
    z, or platens along x, y or z, without lateral loading. Returns (case,
    material, damping, axial, axis index)."""
    with open(case_path) as f:
        case = json.load(f)
    material = case["material"]
    if isinstance(material, str):
        with open(relative(case_path, material)) as f:
            material = json.load(f)
    if material.get("law") != "jcfpm":
        fail("%s: law '%s': expected jcfpm" % (case_path, material.get("law")))
    damping = case.get("damping", {})
    alpha = damping.get("translational", 0.1)
    if damping.get("rotational", 0.1) != alpha:
        fail("%s: damping: Yade has one damping for translation and rotation, "
             "the case gives two" % case_path)
    if len(case["loading"]) != 1:
        fail("%s: loading: expected one stage" % case_path)
    axial = case["loading"][0].get("axial", {})
    if (axial.get("mode") not in ("layers", "strain_rate", "velocity")
            or case["loading"][0].get("lateral", {}).get("mode", "free") != "free"):
        fail("%s: loading: expected end layers (axial.mode layers) or moving platens "
             "(strain_rate, velocity), without lateral loading" % case_path)
    axis = case.get("axis", [0, 0, 1])
    if sorted(abs(a) for a in axis) != [0, 0, 1] or (axial["mode"] == "layers" and axis[2] != 1):
        fail("%s: axis %s: expected x, y or z (z with end layers)" % (case_path, axis))
    return case, material, alpha, axial, [abs(a) for a in axis].index(1)


def read_spheres(path):
    """Lines "x y z r" (m); '#' starts a comment line."""
    spheres = []
    with open(path) as f:
        for line in f:
            cols = line.split()
            if cols and not cols[0].startswith("#"):
                spheres.append([float(c) for c in cols[:4]])
    return spheres


def build(material, spheres, alpha, dt, extra_engines=(), branch="radius", walls=False):
    """Bodies, engines and the bonds (one step at rest in which every pair
    within range becomes cohesive at its present distance, with no force;
    then the ranges go back to contact, as Yade's JCFPM scripts do).
    extra_engines run after the forces and before the integration.
    branch: the branch vectors of the shear increment, "radius" (Yade's
    default, avoidGranularRatcheting: r1 n and -r2 n) or "contact" (from
    the centres to the contact point, at r - pen/2: for equal radii d/2,
    solve's arms d r_i / (r_i + r_j), solve/kinematics.h). Yade's torque
    arm is r - pen/2 in both (Law2 of JCFPM). walls: with the functors
    of wall-sphere contacts (the walls are added by platens(), after this).
    Returns the body ids, the number of bonds and the Law2 functor."""
    gamma = material["interaction_range"]
    phi_c = material["friction_angle_deg"]
    phi_b = material.get("bond_friction_angle_deg", phi_c)
    mat = O.materials.append(JCFpmMat(
        young=material["E"], poisson=material["ks_ratio"], density=material["density"],
        tensileStrength=material["tensile_strength"], cohesion=material["cohesion"],
        frictionAngle=phi_b * PI / 180, residualFrictionAngle=phi_c * PI / 180))
    ids = O.bodies.append([sphere((x, y, z), r, material=mat) for x, y, z, r in spheres])
    aabb = Bo1_Sphere_Aabb(aabbEnlargeFactor=gamma)
    if branch not in ("radius", "contact"):
        fail("branch '%s': expected radius or contact" % branch)
    scgeom = Ig2_Sphere_Sphere_ScGeom(interactionDetectionFactor=gamma,
                                      avoidGranularRatcheting=branch == "radius")
    law = Law2_ScGeom_JCFpmPhys_JointedCohesiveFrictionalPM()
    newton = NewtonIntegrator(damping=alpha)
    bounds, geoms = [aabb], [scgeom]
    if walls:
        bounds.append(Bo1_Wall_Aabb())
        geoms.append(Ig2_Wall_Sphere_ScGeom(noRatch=branch == "radius"))
    O.engines = [
        ForceResetter(),
        InsertionSortCollider(bounds),
        InteractionLoop(geoms, [Ip2_JCFpmMat_JCFpmMat_JCFpmPhys(cohesiveTresholdIteration=1)],
                        [law]),
        newton,
    ]
    O.dt = dt
    O.run(1, True)
    aabb.aabbEnlargeFactor = 1.0
    scgeom.interactionDetectionFactor = 1.0
    bonds = sum(1 for i in O.interactions if i.isReal and i.phys.isCohesive)
    if extra_engines:
        O.engines = O.engines[:-1] + list(extra_engines) + [newton]
    return ids, bonds, law


def end_layers(spheres, ids, axial):
    """The end layers selected and set moving as solve's (solve/boundary.c).
    Returns (bottom ids, top ids, bottom speed, top speed, height)."""
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
    return bottom, top, v_bottom, v_top, height


def platens(spheres, material, axial, ax, branch="radius"):
    """Two walls normal to axis ax where they touch the specimen, moving as
    solve's platens. Returns ([bottom wall], [top wall], bottom speed, top
    speed, initial gap)."""
    lo = min(s[ax] - s[3] for s in spheres)
    hi = max(s[ax] + s[3] for s in spheres)
    gap = hi - lo
    mu = material.get("contact", {}).get("platen_friction",
                                         material.get("contact", {}).get("friction", 0.5))
    phi_c = material["friction_angle_deg"] * PI / 180
    if math.atan(mu) > phi_c:
        fail("platen friction %g above tan(friction_angle_deg): Yade's wall contact takes "
             "the smaller of the two friction angles" % mu)
    wall_mat = O.materials.append(JCFpmMat(
        young=1e12 * material["E"], poisson=material["ks_ratio"], density=material["density"],
        frictionAngle=math.atan(mu), residualFrictionAngle=math.atan(mu), type=1))
    bottom = O.bodies.append(wall(lo, axis=ax, sense=1, material=wall_mat))
    top = O.bodies.append(wall(hi, axis=ax, sense=-1, material=wall_mat))
    speed = axial["velocity"] if axial["mode"] == "velocity" else axial["rate"] * gap
    v_bottom, v_top = ((0.0, -speed) if axial.get("move", "both") == "top"
                       else (0.5 * speed, -0.5 * speed))
    for i, v in ((bottom, v_bottom), (top, v_top)):
        vel = [0.0, 0.0, 0.0]
        vel[ax] = v
        O.bodies[i].state.vel = Vector3(*vel)
    return [bottom], [top], v_bottom, v_top, gap


def axial_load(bottom, top, ax=2):
    """What the bonds and contacts exert on the end layers (or the walls)
    along axis ax, the mean of the two ends, compression positive (N)."""
    return 0.5 * (sum(O.forces.f(i, True)[ax] for i in top)
                  - sum(O.forces.f(i, True)[ax] for i in bottom))
