"""Generator of softpad/data/objects.json: the thesis's Table 6.1 objects from independent specs.

    python examples/make_objects.py src/softpad/data/objects.json

Every number below comes from a named source, never from a trial or a wished-for plan:

* masses: Table 6.1 of the seed (Section 6.3), the object's total;
* LEGO Duplo geometry: the Duplo grid is twice LEGO System's (8 mm stud pitch, 9.6 mm brick
  height): 16 mm pitch, 19.2 mm brick body, 9.6 mm plate; a 2 x N piece measures
  31.8 x (16 N - 0.2) mm (0.1 mm play each side, as on System bricks). Studs (4.5 mm) are left
  out: they sit on top, where neither the pad nor the fingertips touch;
* the banana: YCB 011_banana, its spine and thickness from the convex hulls of YCB's scanned
  model (YcbBanana/collision_vhacd.obj in eleramp/pybullet-object-models): 192 mm long,
  38 mm thick;
* limes: 49 mm across (a common Persian lime), three in a net lying in a flat triangle,
  touching; the seed gives only their total mass (187 g);
* the cylinder: 50 mm x 125 mm can with "a heavy small part in one side" (seed); the shell is
  0.2 mm tinplate (7.85 g/cm^3: 37 g), the rest of the 88.9 g is the heavy part;
* the charger: a laptop power brick (75 x 55 x 30 mm) with its coiled cable and plug, masses of
  the three in proportion to their volumes; the seed gives only the total (312.3 g).

Within an object, the mass of each part is proportional to its volume (one density), unless a
source above says otherwise. Placements put each object where the seed says it lay (modules),
centred on the module grid; the trials add the placement noise.
"""

import json
import math
import sys

from softpad.sim._objects import CATALOGUE_SCHEMA, object_from_dict

U = 0.045  # module pitch, m
PITCH = 0.016  # Duplo stud pitch, m
BRICK_H, PLATE_H = 0.0192, 0.0096


def duplo(n: int) -> float:
    """Length of a 2 x n Duplo piece, m (16 mm a stud, 0.2 mm play)."""
    return PITCH * n - 0.0002


W2 = duplo(2)


def box(name, lx, ly, lz, x, y, z0, yaw=0.0):
    return {
        "name": name,
        "shape": "box",
        "size_m": [round(lx, 5), round(ly, 5), round(lz, 5)],
        "pos_m": [round(x, 5), round(y, 5), round(z0 + lz / 2, 5)],
        "yaw_rad": round(yaw, 6),
        "volume": lx * ly * lz,
    }


def lying_cylinder(name, r, length, x, y, yaw=0.0, z0=0.0):
    return {
        "name": name,
        "shape": "cylinder",
        "radius_m": r,
        "length_m": round(length, 5),
        "axis": "x",
        "pos_m": [round(x, 5), round(y, 5), round(z0 + r, 5)],
        "yaw_rad": round(yaw, 6),
        "volume": math.pi * r * r * length,
    }


def sphere(name, r, x, y):
    return {
        "name": name,
        "shape": "sphere",
        "radius_m": r,
        "pos_m": [round(x, 5), round(y, 5), r],
        "volume": 4 / 3 * math.pi * r**3,
    }


def by_volume(parts, mass):
    """Share ``mass`` over ``parts`` in proportion to their volumes (one density)."""
    total = sum(p["volume"] for p in parts)
    out = []
    for p in parts:
        q = {k: v for k, v in p.items() if k != "volume"}
        q["mass_kg"] = round(mass * p["volume"] / total, 7)
        out.append(q)
    out[-1]["mass_kg"] = round(mass - sum(q["mass_kg"] for q in out[:-1]), 7)
    return out


def with_masses(parts, masses):
    out = []
    for p, m in zip(parts, masses, strict=True):
        q = {k: v for k, v in p.items() if k != "volume"}
        q["mass_kg"] = m
        out.append(q)
    return out


OBJECTS = []


def obj(name, mass, parts, x, y, yaw, modules, cog, theta, gripper, desc, **extra):
    assert abs(sum(p["mass_kg"] for p in parts) - mass) < 1e-6, name
    OBJECTS.append(
        {
            "name": name,
            "description": desc,
            "mass_kg": mass,
            "gripper": gripper,
            "expected_modules": modules,
            "table_6_1": {"cog": cog, "theta": round(theta, 12)},
            "placement": {"x_m": round(x, 5), "y_m": round(y, 5), "yaw_rad": round(yaw, 6)},
            "parts": parts,
            **extra,
        }
    )


pi = math.pi
obj(
    "object-1",
    0.0238,
    by_volume([box("brick 2x4", duplo(4), W2, BRICK_H, 0, 0, 0)], 0.0238),
    2.5 * U,
    1.0 * U,
    pi / 2,
    [3, 6],
    [2.5, 1.0],
    0.0,
    "6/2",
    "One Lego Duplo 2x4 brick (63.8 x 31.8 x 19.2 mm body), long axis along y, centred on the "
    "line between modules 3 and 6.",
)
obj(
    "object-2",
    0.0253,
    by_volume(
        [
            box("brick 2x2 left", W2, W2, BRICK_H, -2 * PITCH, 0, 0),
            box("brick 2x2 right", W2, W2, BRICK_H, 2 * PITCH, 0, 0),
            box("plate 2x6 bridge", duplo(6), W2, PLATE_H, 0, 0, BRICK_H),
        ],
        0.0253,
    ),
    1.0 * U,
    1.0 * U,
    -pi / 4,
    [1, 5],
    [1.04, 0.96],
    pi / 4,
    "6/2",
    "Two Duplo 2x2 bricks under the ends of a 2x6 plate (symmetric, one density, as the seed "
    "says of objects 1, 2, 3 and 6), laid diagonally from module 1 to module 5.",
)
obj(
    "object-3",
    0.0444,
    by_volume(
        [
            box("plate 2x8", duplo(8), W2, PLATE_H, 0, 0, 0),
            box("brick 2x4 left", duplo(4), W2, BRICK_H, -2 * PITCH, 0, PLATE_H),
            box("brick 2x4 right", duplo(4), W2, BRICK_H, 2 * PITCH, 0, PLATE_H),
            box("brick 2x2 top", W2, W2, BRICK_H, 0, 0, PLATE_H + BRICK_H),
        ],
        0.0444,
    ),
    1.5 * U,
    1.5 * U,
    0.0,
    [1, 2, 3],
    [1.5, 1.5],
    pi / 2,
    "6/2",
    "A Duplo 2x8 plate with two 2x4 bricks on it and a 2x2 brick on top in the middle: long, "
    "symmetric, along the top row (modules 1, 2, 3).",
)
obj(
    "object-4",
    0.052,
    by_volume(
        [
            box("brick 2x4", duplo(4), W2, BRICK_H, 0, 0, 0),
            box("brick 2x2 lower", W2, W2, BRICK_H, PITCH, 0, BRICK_H),
            box("brick 2x2 upper", W2, W2, BRICK_H, PITCH, 0, 2 * BRICK_H),
        ],
        0.052,
    ),
    0.5 * U,
    1.0 * U,
    pi / 2,
    [1, 4],
    [0.5, 1.2],
    0.0,
    "6/2",
    "A Duplo 2x4 brick across the line between modules 1 and 4 with two 2x2 bricks stacked on "
    "its upper half (over module 1): heavier there, as the seed says.",
)
obj(
    "object-5",
    0.0649,
    by_volume(
        [
            box("plate 2x8", duplo(8), W2, PLATE_H, 0, 0, 0),
            box("brick 2x2 lower", W2, W2, BRICK_H, -PITCH, 0, PLATE_H),
            box("brick 2x2 upper", W2, W2, BRICK_H, -PITCH, 0, PLATE_H + BRICK_H),
        ],
        0.0649,
    ),
    1.5 * U,
    1.5 * U,
    0.0,
    [1, 2, 3],
    [1.36, 1.5],
    pi / 2,
    "6/2",
    "A Duplo 2x8 plate along the top row with two 2x2 bricks stacked one stud pitch left of its "
    "middle: heavier towards module 1, as the seed says (it gives no position; one stud is the "
    "smallest offset the stud grid allows).",
)
obj(
    "object-6",
    0.122,
    by_volume([box("three 2x8 bricks", duplo(8), W2, 3 * BRICK_H, 0, 0, 0)], 0.122),
    1.5 * U,
    0.5 * U,
    0.0,
    [4, 5, 6],
    [1.55, 0.5],
    pi / 2,
    "6/2",
    "Three Duplo 2x8 bricks stacked (127.8 x 31.8 x 57.6 mm), homogeneous, centred along the "
    "bottom row.",
)


def seg(name, p0, p1, r):
    dx, dy = p1[0] - p0[0], p1[1] - p0[1]
    return lying_cylinder(
        name, r, math.hypot(dx, dy), (p0[0] + p1[0]) / 2, (p0[1] + p1[1]) / 2, math.atan2(dy, dx)
    )


# The YCB banana (011_banana): its spine and thickness read off the convex hulls of YCB's scanned
# model (collision_vhacd.obj of YcbBanana in eleramp/pybullet-object-models, metres, banana
# frame: length along x, 192 mm from -0.075 to 0.117; 38 mm thick; ends curving to -y). Points
# (x, y) of the spine and the radius of each stretch between them.
YCB_BANANA_SPINE = [
    (-0.070, -0.045),
    (-0.045, -0.020),
    (-0.010, 0.003),
    (0.040, 0.006),
    (0.080, -0.003),
    (0.112, -0.020),
]
YCB_BANANA_RADII = [0.008, 0.016, 0.019, 0.019, 0.014]
# Laid with its chord (end to end) parallel to the line through the centres of modules 4 and 3,
# its centre of mass on the pad's centre between them (1.5, 1) module units, bulging towards
# module 2: so it lies on modules 2, 3 and 4 as the seed says ("it lays on modules 2, 3, and 4");
# its ends reach past the pad's edges, as a 192 mm banana on a 135 x 90 mm pad must. (Its chord's
# midpoint on that centre instead puts the 38 mm thick middle on modules 1-3: not the seed's.)
(_x0, _y0), (_x1, _y1) = YCB_BANANA_SPINE[0], YCB_BANANA_SPINE[-1]
CHORD = math.atan2(1.0, 2.0) - math.atan2(_y1 - _y0, _x1 - _x0)
banana_parts = [
    seg(f"stretch {k + 1}", YCB_BANANA_SPINE[k], YCB_BANANA_SPINE[k + 1], r)
    for k, r in enumerate(YCB_BANANA_RADII)
]
banana_parts = by_volume(banana_parts, 0.0598)
_mx = sum(p["mass_kg"] * p["pos_m"][0] for p in banana_parts) / 0.0598  # centre of mass,
_my = sum(p["mass_kg"] * p["pos_m"][1] for p in banana_parts) / 0.0598  # banana frame
BANANA_AT = (
    1.5 * U - (math.cos(CHORD) * _mx - math.sin(CHORD) * _my),
    1.0 * U - (math.sin(CHORD) * _mx + math.cos(CHORD) * _my),
)
obj(
    "banana",
    0.0598,
    banana_parts,
    BANANA_AT[0],
    BANANA_AT[1],
    CHORD,
    [2, 3, 4],
    [1.0, 1.0],
    -pi / 4,
    "6/2",
    "The YCB banana (011: 192 mm long, 38 mm thick, spine from YCB's scanned model) as five "
    "lying cylinders along its curve, one density, 59.8 g (Table 6.1; YCB lists 66 g); its "
    "chord parallel to the line through the centres of modules 4 and 3, its centre of mass on "
    "the pad's centre, bulging towards module 2 (on modules 2, 3, 4 as in the seed), its ends "
    "past the pad's edges.",
)
obj(
    "toy",
    0.1316,
    by_volume(
        [
            box("body", 0.036, 0.036, 0.04, 1.5 * U, 0.5 * U, 0),
            box("left arm", 0.055, 0.022, 0.03, 1.5 * U - 0.032, 0.5 * U + 0.032, 0, 3 * pi / 4),
            box("left hand", 0.03, 0.03, 0.035, 0.5 * U + 0.002, 1.5 * U - 0.002, 0),
            box("right arm", 0.055, 0.022, 0.03, 1.5 * U + 0.032, 0.5 * U + 0.032, 0, pi / 4),
            box("right hand", 0.03, 0.03, 0.035, 2.5 * U - 0.002, 1.5 * U - 0.002, 0),
        ],
        0.1316,
    ),
    0.0,
    0.0,
    0.0,
    [1, 3, 5],
    [2.0, 1.0],
    -pi / 4,
    "6/2",
    "A V-shaped toy: body on module 5, arms reaching diagonally to modules 1 and 3; one density "
    "(the seed gives no shape or mass distribution, only the total and the modules its plan "
    "implies).",
)
R_LIME = 0.0245
obj(
    "limes",
    0.187,
    by_volume(
        [
            sphere("lime 1", R_LIME, -R_LIME, 0.0),
            sphere("lime 2", R_LIME, R_LIME, 0.0),
            sphere("lime 3", R_LIME, 0.0, 2 * R_LIME * math.sqrt(3) / 2),
        ],
        0.187,
    ),
    1.5 * U,
    0.5 * U,
    0.0,
    [2, 4, 5, 6],
    [1.5, 0.8],
    0.0,
    "10/4",
    "Three limes (49 mm, 62.3 g each) in a tight net (one rigid body), lying flat in a triangle "
    "of touching limes: two along the bottom row either side of the middle, the third above "
    "them on module 2.",
)
can = [
    lying_cylinder("can", 0.025, 0.125, 0.0, 0.0),
    lying_cylinder("heavy part", 0.02, 0.02, -0.0625 + 0.001 + 0.01, 0.0, z0=0.005),
]
shell_kg = round(7850 * 0.0002 * (2 * pi * 0.025 * 0.125 + 2 * pi * 0.025**2), 4)
obj(
    "cylinder",
    0.0889,
    with_masses(can, [shell_kg, round(0.0889 - shell_kg, 7)]),
    1.5 * U,
    1.0 * U,
    0.0,
    [1, 2, 3, 4, 5, 6],
    [1.14, 1.0],
    pi / 2,
    "6/2",
    f"A can (50 mm across, 125 mm long; 0.2 mm tinplate, {shell_kg * 1e3:.1f} g) lying along x "
    "on the line between the rows, with a heavy part (the rest of the 88.9 g) against its left "
    "end cap: the seed's 'heavy small part in one side'; its COG (1.14) says which side.",
)
obj(
    "charger",
    0.3123,
    by_volume(
        [
            box("brick", 0.075, 0.055, 0.03, 0, 0, 0),
            box("cable coil", 0.03, 0.03, 0.015, 0.055, -0.012, 0),
            box("plug", 0.03, 0.025, 0.02, 0.09, -0.02, 0),
        ],
        0.3123,
    ),
    1.0 * U,
    1.0 * U,
    0.0,
    [1, 2, 4, 5, 6],
    [1.16, 1.0],
    pi / 2,
    "6/2",
    "A laptop power brick (75 x 55 x 30 mm) centred over modules 1, 2, 4 and 5, with its coiled "
    "cable and plug on module 6; one density.",
)


def main(out: str | None = None) -> list[dict]:
    """Validate every object, write the catalogue to ``out`` (when given), print the parts'
    masses; return the objects."""
    for d in OBJECTS:
        object_from_dict(d)  # validates
    if out is not None:
        with open(out, "w", encoding="utf-8") as f:
            json.dump({"schema": CATALOGUE_SCHEMA, "objects": OBJECTS}, f, indent=1)
            f.write("\n")
    for d in OBJECTS:
        print(d["name"], [(p["name"], p["mass_kg"]) for p in d["parts"]])
    return OBJECTS


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else None)
