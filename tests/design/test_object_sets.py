"""Object sets from TOML and their placement on any pad."""

from __future__ import annotations

from pathlib import Path

import pytest

from softpad.design import (
    THESIS_DESIGN,
    PadDesign,
    example_object_set,
    load_object_set,
)
from softpad.design._objects import footprint_centre_m
from softpad.errors import InputError
from softpad.sim import get_object, object_names


def _size(d: PadDesign) -> tuple[float, float]:
    return d.cols * d.pitch_m, d.rows * d.pitch_m


def test_thesis_set_is_table_6_1() -> None:
    s = example_object_set("thesis-set")
    assert s.names == tuple(object_names())
    for o in s.objects:
        assert o.spec.mass_kg == get_object(o.name).mass_kg
        assert s.mounting(o) == get_object(o.name).gripper


@pytest.mark.parametrize("name", ["banana", "charger", "limes"])
def test_as_thesis_placement_is_the_catalogues_on_the_thesis_pad(name: str) -> None:
    o = next(o for o in example_object_set("thesis-set").objects if o.name == name)
    placed = o.placed_on(_size(THESIS_DESIGN))
    assert placed.placement == get_object(name).placement


def test_as_thesis_placement_keeps_the_offset_from_the_pad_centre() -> None:
    o = example_object_set("thesis-set").objects[0]
    big = PadDesign(4, 6, 0.045)
    p, q = o.placed_on(_size(THESIS_DESIGN)).placement, o.placed_on(_size(big)).placement
    assert q.x_m - p.x_m == pytest.approx(3 * 0.045 / 2)
    assert q.y_m - p.y_m == pytest.approx(2 * 0.045 / 2)


def test_centre_and_offset_placements() -> None:
    s = example_object_set("blocks")
    brick, block, can = s.objects
    for o, (dx, dy) in ((brick, (0.0, 0.0)), (block, (0.0, 0.0)), (can, (0.0, -0.005))):
        spec = o.placed_on((0.135, 0.09))
        cx, cy = footprint_centre_m(spec.parts, spec.placement.yaw_rad)
        assert spec.placement.x_m + cx == pytest.approx(0.0675 + dx)
        assert spec.placement.y_m + cy == pytest.approx(0.045 + dy)
    assert block.spec.mass_kg == pytest.approx(0.25)
    assert can.spec.parts[0].radius_m == pytest.approx(0.02)


@pytest.mark.parametrize(
    ("text", "named"),
    [
        ('schema = "x"\n', "schema"),
        ('schema = "softpad-object-set/1"\n', r"\[\[object\]\]"),
        (
            'schema = "softpad-object-set/1"\n[[object]]\nname = "a"\nmass_g = -1\nsize_mm = [1,1,1]\n',
            "mass_g",
        ),
        ('schema = "softpad-object-set/1"\n[[object]]\nname = "a"\nmass_g = 10\n', "size_mm"),
        ('schema = "softpad-object-set/1"\n[[object]]\nname = "a"\ncatalogue = "pear"\n', "pear"),
        (
            'schema = "softpad-object-set/1"\n[[object]]\nname = "a"\ncatalogue = "toy"\nplacement = "left"\n',
            "placement",
        ),
        (
            'schema = "softpad-object-set/1"\n[[object]]\nname = "a"\ncatalogue = "toy"\ngripper = "9/9"\n',
            "gripper",
        ),
        ("schema = \n", "not valid TOML"),
    ],
    ids=[
        "schema",
        "no-objects",
        "mass",
        "size",
        "unknown-catalogue",
        "placement",
        "gripper",
        "toml",
    ],
)
def test_bad_object_set_names_the_problem(tmp_path: Path, text: str, named: str) -> None:
    f = tmp_path / "set.toml"
    f.write_text(text)
    with pytest.raises(InputError, match=named):
        load_object_set(f)


def test_missing_file_and_unknown_example() -> None:
    with pytest.raises(InputError, match="not found"):
        load_object_set("/nonexistent/set.toml")
    with pytest.raises(InputError, match="thesis-set"):
        example_object_set("nope")
