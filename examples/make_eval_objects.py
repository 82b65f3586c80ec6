"""Generator of the evaluation object sets: YCB objects as boxes and lying cylinders.

    python examples/make_eval_objects.py src/softpad/data/object_sets

writes ``ycb-dev.toml`` (the development half) and ``ycb-eval.toml`` (the evaluation half) in
the design object-set format (``softpad-object-set/1``, docs/design.md).

Sources. Sizes and masses are those of the YCB object set's published table (B. Calli et al.,
"The YCB object and model set", IEEE Robotics & Automation Magazine 22(3), 2015, Table 1), as
the author of this script recalls them; they were not re-measured or looked up again here and
may be off by a few millimetres or grams. Objects that are neither boxes nor cylinders are
approximated (say so in ``note``): a standing can by a box of the same footprint area, a fruit
or a ball by a cylinder lying on its side, its diameter the object's width and its length the
object's length (a sphere: its diameter both ways).

Selection. Every object of the table that a 2 x 3 pad of 45 mm modules (90 x 135 mm) can carry
whole and one of the thesis's three mountings (10/4, 6/2, 4/0 cm) can close across: its
narrowest horizontal side at most 90 mm (10 mm under the widest opening) and its footprint
within 135 x 90 mm lying on its largest face. The mounting is the narrowest one whose opening
exceeds that side by 10 mm (the thesis also chose a mounting per object). Too long or too wide
for the pad (cracker box, sugar box, mustard, banana, master chef can, tools, plates) and
objects lighter than 5 g are left out.

Placements. ``placement = "anywhere"``: each trial draws the object's pose from its own seed,
anywhere on the pad its footprint fits (5 mm of overhang allowed), its centre at least 10 mm
from the pad's centre (softpad.trials._geometry.anywhere_placement; issue 45), as a lab would
put a held-out object down. (The generator still draws the offsets and yaw it once wrote, so
that the seeded split below stays the same.)

Split. The objects are shuffled with the same generator and dealt alternately: the first,
third, ... to ``dev`` (develop and tune on it), the second, fourth, ... to ``eval`` (report on
it, once). docs/planner.md names both halves.
"""

from __future__ import annotations

import math
import random
import sys
from pathlib import Path

PAD_MM = (135.0, 90.0)
MOUNTINGS = (("4/0", 40.0), ("6/2", 60.0), ("10/4", 100.0))
SEED = 34

#: name, shape, dimensions (box: lx, ly, lz mm; cylinder: diameter, length mm), mass g, note.
YCB = (
    ("ycb-005-tomato-soup-can", "cylinder", (66.0, 101.0), 349.0, ""),
    ("ycb-007-tuna-fish-can", "box", (75.0, 75.0, 33.0), 171.0, "standing can 85 x 33 mm"),
    ("ycb-008-pudding-box", "box", (110.0, 89.0, 35.0), 187.0, ""),
    ("ycb-009-gelatin-box", "box", (85.0, 73.0, 28.0), 97.0, ""),
    ("ycb-010-potted-meat-can", "box", (97.0, 50.0, 82.0), 370.0, ""),
    ("ycb-012-strawberry", "cylinder", (43.8, 55.0), 18.0, "fruit 43.8 x 55 mm"),
    ("ycb-013-apple", "cylinder", (75.0, 75.0), 68.0, "fruit 75 mm"),
    ("ycb-014-lemon", "cylinder", (54.0, 68.0), 29.0, "fruit 54 x 68 mm"),
    ("ycb-015-peach", "cylinder", (59.0, 59.0), 33.0, "fruit 59 mm"),
    ("ycb-016-pear", "cylinder", (66.2, 100.0), 49.0, "fruit 66.2 x 100 mm"),
    ("ycb-017-orange", "cylinder", (73.0, 73.0), 47.0, "fruit 73 mm"),
    ("ycb-018-plum", "cylinder", (52.0, 52.0), 25.0, "fruit 52 mm"),
    ("ycb-026-sponge", "box", (114.0, 72.0, 14.0), 6.2, ""),
    ("ycb-040-large-marker", "cylinder", (18.0, 121.0), 15.8, ""),
    ("ycb-055-baseball", "cylinder", (75.0, 75.0), 148.0, "ball 75 mm"),
    ("ycb-056-tennis-ball", "cylinder", (64.7, 64.7), 58.0, "ball 64.7 mm"),
    ("ycb-058-golf-ball", "cylinder", (42.7, 42.7), 46.0, "ball 42.7 mm"),
    ("ycb-061-foam-brick", "box", (75.0, 50.0, 50.0), 28.0, ""),
    ("ycb-062-dice", "box", (16.0, 16.0, 16.0), 5.2, ""),
    ("ycb-077-rubiks-cube", "box", (57.0, 57.0, 57.0), 252.0, ""),
)


def footprint(shape: str, dims: tuple[float, ...]) -> tuple[float, float]:
    """Footprint (x, y) of the object in its own frame, mm (a cylinder lies along x)."""
    return (dims[0], dims[1]) if shape == "box" else (dims[1], dims[0])


def mounting(shape: str, dims: tuple[float, ...]) -> str | None:
    """The narrowest mounting whose opening exceeds the narrowest side by 10 mm."""
    narrow = min(footprint(shape, dims))
    return next((name for name, width in MOUNTINGS if narrow + 10.0 <= width), None)


def fitting_yaws(fx: float, fy: float) -> list[int]:
    """Yaws (degrees) at which a footprint fx x fy stays on the pad with 5 mm of overhang."""
    out = []
    for deg in range(180):
        c, s = abs(math.cos(math.radians(deg))), abs(math.sin(math.radians(deg)))
        if fx * c + fy * s <= PAD_MM[0] + 10.0 and fx * s + fy * c <= PAD_MM[1] + 10.0:
            out.append(deg)
    return out


def entry(rng: random.Random, obj: tuple) -> str:
    name, shape, dims, mass, note = obj
    fx, fy = footprint(shape, dims)
    yaws = fitting_yaws(fx, fy)
    grip = mounting(shape, dims)
    if not yaws or grip is None or mass < 5.0:
        raise SystemExit(f"{name} does not fit the selection; remove it")
    yaw = rng.choice(yaws)
    dx, dy = rng.uniform(-10.0, 10.0), rng.uniform(-10.0, 10.0)
    lines = [
        "[[object]]",
        f'name = "{name}"',
        f"mass_g = {mass:g}",
        f'shape = "{shape}"',
    ]
    if shape == "box":
        lines.append(f"size_mm = [{dims[0]:g}, {dims[1]:g}, {dims[2]:g}]")
    else:
        lines += [f"diameter_mm = {dims[0]:g}", f"length_mm = {dims[1]:g}"]
    del dx, dy, yaw  # drawn only to keep the generator's sequence (and so the split)
    lines += ['placement = "anywhere"', f'gripper = "{grip}"']
    if note:
        lines.insert(1, f"# approximates the YCB {note}")
    return "\n".join(lines) + "\n"


HEADER = """# {title}
# Generated by examples/make_eval_objects.py (seed {seed}); sizes and masses from the YCB object
# set's published table (Calli et al., IEEE RAM 2015), boxes and lying cylinders as described
# there. Do not edit by hand: change the script and regenerate.
schema = "softpad-object-set/1"
name = "{name}"

"""


def main(out_dir: str) -> None:
    rng = random.Random(SEED)
    entries = [(obj[0], entry(rng, obj)) for obj in YCB]
    order = list(range(len(entries)))
    rng.shuffle(order)
    halves = {"ycb-dev": order[0::2], "ycb-eval": order[1::2]}
    titles = {
        "ycb-dev": "Development half of the YCB evaluation set: develop and tune on these only.",
        "ycb-eval": "Evaluation half of the YCB evaluation set: report on these, never tune.",
    }
    for name, idx in halves.items():
        text = HEADER.format(title=titles[name], seed=SEED, name=name)
        text += "\n".join(entries[i][1] for i in sorted(idx))
        Path(out_dir, f"{name}.toml").write_text(text, encoding="utf-8")
        print(name, ", ".join(entries[i][0] for i in sorted(idx)))


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "src/softpad/data/object_sets")
