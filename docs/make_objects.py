"""Design script of softpad/data/objects.json (the thesis's Table 6.1 objects).

Builds every object from Duplo bricks and primitives, prints the increments the analytic world
gives (linear sensitivity SENS Pa/N, default 0.85 kPa/N) and the plan of the thesis planner,
and writes the catalogue when given a path:

    python docs/make_objects.py src/softpad/data/objects.json

The tuned placements/masses are the defaults of ``a(...)``; ARGS="key=value ..." overrides them.
"""
import json, math, sys, os
import numpy as np
from softpad.sim._objects import object_from_dict, CATALOGUE_SCHEMA
from softpad.sim._footprint import object_footprint, PadSurface, GRAVITY_M_S2
from softpad.planning import plan_grasps
from softpad.layout import PadLayout
U = 0.045
SENS = float(os.environ.get('SENS', 850))
A = {k: float(v) for k, v in (kv.split('=') for kv in os.environ.get('ARGS', '').split())}
def a(k, d): return A.get(k, d)
def box(name, lx, ly, lz, x, y, z0, m, yaw=0.0):
    return {"name": name, "shape": "box", "size_m": [round(lx,5), round(ly,5), round(lz,5)], "pos_m": [round(x,5), round(y,5), round(z0 + lz/2,5)], "yaw_rad": round(yaw,6), "mass_kg": round(m,6)}
def lcyl(name, r, l, x, y, m, yaw=0.0, z0=0.0):
    return {"name": name, "shape": "cylinder", "radius_m": r, "length_m": round(l,5), "axis": "x", "pos_m": [round(x,5), round(y,5), round(z0 + r,5)], "yaw_rad": round(yaw,6), "mass_kg": round(m,6)}
def sph(name, r, x, y, m, z0=0.0):
    return {"name": name, "shape": "sphere", "radius_m": r, "pos_m": [round(x,5), round(y,5), round(z0+r,5)], "mass_kg": round(m,6)}
P = {}
def obj(name, mass, parts, x, y, yaw, modules, cog, theta, gripper, desc, **extra):
    tot = sum(p["mass_kg"] for p in parts)
    assert abs(tot - mass) < 1e-6, (name, tot, mass)
    P[name] = {"name": name, "description": desc, "mass_kg": mass, "gripper": gripper,
        "expected_modules": modules, "table_6_1": {"cog": cog, "theta": round(theta, 12)},
        "placement": {"x_m": round(x,5), "y_m": round(y,5), "yaw_rad": round(yaw,6)}, "parts": parts, **extra}
pi = math.pi
L24, W2, H = 0.0635, 0.0317, 0.0192
obj("object-1", 0.0238, [box("brick 2x4", L24, W2, 0.023, 0, 0, 0, 0.0238)], 2.5*U, 1.0*U, pi/2, [3,6], [2.5,1.0], 0.0, "6/2",
    "One Lego Duplo 2x4 brick (63.5 x 31.7 x 23 mm), long axis along y across the line between modules 3 and 6.")
d2 = a('d2', 0.0071)
obj("object-2", 0.0253, [box("brick 2x2 left", W2, W2, H, -0.0317, 0, 0, 0.00815),
                         box("brick 2x2 right", W2, W2, H, 0.0317, 0, 0, 0.00815),
                         box("plate 2x6 bridge", 0.0951, W2, 0.0096, d2, 0, H, 0.009)], 1.0*U, 1.0*U, -pi/4, [1,5], [1.04,0.96], pi/4, "6/2",
    "A Duplo 2x6 plate bridging two 2x2 bricks, laid diagonally from module 1 to module 5; the plate overhangs towards module 5, which makes that end slightly heavier.")
obj("object-3", 0.0444, [box("plate 2x8", 0.127, W2, 0.0096, 0, 0, 0, 0.0204),
                         box("brick 2x4 left", L24, W2, 0.0192, -L24/2, 0, 0.0096, 0.0100),
                         box("brick 2x4 right", L24, W2, 0.0192, L24/2, 0, 0.0096, 0.0100),
                         box("brick 2x2 top", W2, W2, 0.0192, 0, 0, 0.0288, 0.0040)], 1.5*U, 1.5*U, 0.0, [1,2,3], [1.5,1.5], pi/2, "6/2",
    "Duplo 2x8 plate with two 2x4 bricks and a centred top brick: long, symmetric, along the top row (modules 1, 2, 3).")
obj("object-4", 0.052, [box("brick 2x4", L24, W2, 0.023, 0, 0, 0, 0.0238),
                        box("brick 2x2 stack", W2, W2, 0.046, 0.0159, 0, 0.023, 0.0282)], 0.5*U, 1.0*U, pi/2, [1,4], [0.5,1.2], 0.0, "6/2",
    "Duplo 2x4 brick across the 1/4 line with two 2x2 bricks stacked on its upper half: heavier over module 1.")
e5 = a('e5', -0.0099)
obj("object-5", 0.0649, [box("plate 2x8", 0.127, W2, 0.0096, 0, 0, 0, 0.0204),
                         box("brick stack", W2, W2, 0.046, e5, 0, 0.0096, 0.0445)], 1.5*U, 1.5*U, 0.0, [1,2,3], [1.36,1.5], pi/2, "6/2",
    "Duplo 2x8 plate along the top row with a stack of bricks left of its middle: heavier towards module 1.")
d6 = a('d6', 0.0032)
obj("object-6", 0.122, [box("2x8 bricks", 0.127, W2, 0.0576, 0, 0, 0, 0.122)], 1.5*U + d6, 0.5*U, 0.0, [4,5,6], [1.55,0.5], pi/2, "6/2",
    "Three layers of Duplo 2x8 bricks (127 x 31.7 x 57.6 mm), homogeneous, along the bottom row, 3.5 mm right of centre.")
def seg(name, p0, p1, r, m):
    dx, dy = p1[0]-p0[0], p1[1]-p0[1]
    return lcyl(name, r, math.hypot(dx, dy), (p0[0]+p1[0])/2, (p0[1]+p1[1])/2, m, math.atan2(dy, dx))
b0, b1, b2, b3 = (0.014, 0.016), (0.045, 0.046), (0.080, 0.068), (0.122+a('b3', 0), 0.072)
mb = a('mb', 0.020)
obj("banana", 0.0598, [seg("stem end", b0, b1, 0.016, mb), seg("middle", b1, b2, 0.018, 0.0238), seg("tip end", b2, b3, 0.016, round(0.036-mb, 6))],
    0.0, 0.0, 0.0, [2,3,4], [1.0, 1.0], -pi/4, "6/2",
    "A YCB banana as three lying cylinders along a curve from module 4 over the corner of modules 1/2/4/5 to module 3; its stem end is the heavier.")
mr = a('mr', 0.030)
obj("toy", 0.1316, [box("body", 0.036, 0.036, 0.04, 1.5*U, 0.5*U, 0, 0.0296),
                    box("left arm", 0.055, 0.022, 0.03, 1.5*U - 0.032, 0.5*U + 0.032, 0, 0.030, 3*pi/4),
                    box("left hand", 0.03, 0.03, 0.035, 0.5*U+0.002, 1.5*U-0.002, 0, round(0.042-mr, 6)),
                    box("right arm", 0.055, 0.022, 0.03, 1.5*U + 0.032, 0.5*U + 0.032, 0, 0.030, pi/4),
                    box("right hand", 0.03, 0.03, 0.035, 2.5*U-0.002, 1.5*U-0.002, 0, mr)],
    0.0, 0.0, 0.0, [1,3,5], [2.0, 1.0], -pi/4, "6/2",
    "A V-shaped toy: body on module 5, arms reaching diagonally to modules 1 and 3, heavier right hand.")
rl, gl = 0.0245, 0.0005
mc, yc, cz = a('mc', 0.0165), a('yc', 0.05), a('cz', 0.0)
ml = round((0.187 - mc) / 3, 6)
lz = a('lz', -0.004)
zt = math.sqrt((2*rl)**2 - (rl + gl)**2)
obj("limes", 0.187, [sph("lime 1", rl, -(rl + gl), 0, ml, z0=lz),
                     sph("lime 2", rl, rl + gl, 0, ml, z0=lz),
                     sph("lime 3", rl, 0, 0, round(0.187 - mc - 2*ml, 6), z0=round(zt + lz, 5)),
                     box("net clip", a('cw', 0.03), a('cl', 0.02), 0.004, 0, yc, cz, mc)],
    1.5*U, 0.5*U, 0.0, [2,4,5,6], [1.5, 0.8], 0.0, "10/4",
    "Three limes (56.8 g, 49 mm) in a net drawn tight (one rigid body): two side by side along the bottom row, on the edges of modules 4 and 6 next to the lines to module 5, "
    "the third on top of them, and the net's gathered end with its clip and label (16.5 g) pulled onto module 2; the limes settle 4 mm into the valleys between the domes, the clip lies on the dome. "
    "Across x the pile is 86 mm wide where the jaws come down (y = 0.8), which the 10/4 mounting (100 mm) straddles with 7 mm a side; three limes in a row (>= 135 mm) would put a jaw on the outer ones. "
    "Module 2 carries about a tenth of the summed increments, so the N = 4 drop-farthest rule keeps 2, 5 and 4 or 6 and the corner shift puts the COG at y = 0.8; "
    "the rule needs the pressure centre within 0.1 module units of x = 1.5, which a turn of a few degrees can break (the pile's outer limes sit on the domes' edges).",
    loose_parts=a("loose", 0) > 0)
obj("cylinder", 0.0889, [lcyl("shell", 0.025 - a('sg', 0.0012), 0.125, 0, 0, round(0.0439-a('mi', 0.0045), 6), z0=a('sg', 0.0012)),
                         lcyl("left rim", 0.025, a('lr', 0.012), -0.0625 + a('lr', 0.012)/2, 0, 0.004),
                         lcyl("left band", 0.0241, a('lbd', 0.009), -0.0625 + a('lr', 0.012) + a('lbd', 0.009)/2, 0, 0.002, z0=0.0009),
                         lcyl("bead", 0.025 - a('bg', 0.00045), a('lb', 0.0095), a('xb', 0.0), 0, 0.003, z0=a('bg', 0.00045)),
                         lcyl("right rim", 0.025, a('rr', 0.012), 0.0505 + a('rr', 0.012)/2, 0, 0.004),
                         lcyl("insert", 0.02, 0.02, a('xi', -0.041), 0, round(0.032+a('mi', 0.0045), 6), z0=0.005)],
    1.5*U, 1.0*U, 0.0, [1,2,3,4,5,6], [1.14, 1.0], pi/2, "6/2",
    "A can (50 mm diameter, 125 mm long, 88.9 g) lying along x on the line between the rows, with a 36.5 g insert 41 mm left of its middle (centre of mass at x = 1.10 module units). "
    "It rests on its end rims (12 mm wide; inside the left one a 9 mm swaged band 0.1 mm proud of the body) and, lightly, on a central bead 9.5 mm wide that stands 0.45 mm back from the rims: "
    "a rigid can on stiff, equal supports would give its middle column a third of its weight whatever the insert, leaving the right column under t_o; a recessed bead moves load to the ends, "
    "so modules 2, 3, 5, 6 carry about 0.1 N each (the most they can with the pressure centre at x = 1.14) and the left column the rest. "
    "Sensitive to its yaw: lying in the groove between the rows, turned by 1-2 degrees it rests with one end on each row and is seen on four or five modules (the thesis's cylinder failure).")
obj("charger", 0.3123, [box("brick", 0.075, 0.055, 0.03, 0, 0, 0, 0.2823),
                        box("cable coil", 0.03, 0.03, 0.015, 0.055, -0.012, 0, 0.018),
                        box("plug", 0.03, 0.025, 0.02, 0.09, -0.02, 0, 0.012)],
    1.0*U + a('cx', 0.0009), 1.0*U, 0.0, [1,2,4,5,6], [1.16, 1.0], pi/2, "6/2",
    "A power-supply brick lying over modules 1, 2, 4 and 5, with its coiled cable and plug on module 6.")
cat = [object_from_dict(d) for d in P.values()]
surf = PadSurface()
lay = PadLayout()
for o in cat:
    fp = object_footprint(o, surf)
    d = fp.weight_fraction * o.mass_kg * GRAVITY_M_S2 * SENS
    c = lay.centers
    try:
        pl = plan_grasps(d, lay)
        ps = " | ".join(f"{p.modules} pcom=({p.pcom[0]:.3f},{p.pcom[1]:.3f}) cog=({p.cog[0]:.3f},{p.cog[1]:.3f}) th={p.theta:.3f} {p.rule}" for p in pl)
    except Exception as e:
        ps = repr(e)
    print(f"{o.name:9s} dP={np.round(d,0)} {ps}  target={o.table_cog},{o.table_theta:.3f}")
if len(sys.argv) > 1:
    json.dump({"schema": CATALOGUE_SCHEMA, "objects": list(P.values())}, open(sys.argv[1], 'w'), indent=1)
