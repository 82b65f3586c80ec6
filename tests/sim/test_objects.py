"""Object catalogue: schema, masses of Table 6.1, loading errors, footprints."""

from __future__ import annotations

import json

import numpy as np
import pytest

from softpad.errors import InputError
from softpad.sim import (
    GRAVITY_M_S2,
    PadSurface,
    catalogue_to_json,
    get_object,
    load_catalogue,
    object_footprint,
    object_names,
)

#: Table 6.1 of the seed: weight in grams.
TABLE_6_1_MASS_G = {
    "object-1": 23.8,
    "object-2": 25.3,
    "object-3": 44.4,
    "object-4": 52.0,
    "object-5": 64.9,
    "object-6": 122.0,
    "banana": 59.8,
    "toy": 131.6,
    "limes": 187.0,
    "cylinder": 88.9,
    "charger": 312.3,
}


def test_catalogue_names_in_table_order() -> None:
    assert object_names() == tuple(TABLE_6_1_MASS_G)


@pytest.mark.parametrize("name", list(TABLE_6_1_MASS_G), ids=list(TABLE_6_1_MASS_G))
def test_mass_matches_table_6_1(name: str) -> None:
    spec = get_object(name)
    np.testing.assert_allclose(spec.mass_kg * 1e3, TABLE_6_1_MASS_G[name], atol=1e-9)
    np.testing.assert_allclose(sum(p.mass_kg for p in spec.parts), spec.mass_kg, rtol=1e-9)


@pytest.mark.parametrize("name", list(TABLE_6_1_MASS_G), ids=list(TABLE_6_1_MASS_G))
def test_footprint_balances_weight(name: str) -> None:
    """Winkler contact pressure carries the whole weight and is non-negative."""
    spec = get_object(name)
    fp = object_footprint(spec, PadSurface())
    np.testing.assert_allclose(
        (fp.pressure_pa * fp.area_m2).sum(), spec.mass_kg * GRAVITY_M_S2, rtol=1e-6
    )
    assert (fp.pressure_pa >= 0).all()
    assert 0 < fp.weight_fraction.sum() <= 1 + 1e-9


@pytest.mark.parametrize("name", list(TABLE_6_1_MASS_G), ids=list(TABLE_6_1_MASS_G))
def test_roundtrip_json(name: str, tmp_path) -> None:
    spec = get_object(name)
    p = tmp_path / "cat.json"
    p.write_text(catalogue_to_json([spec]))
    assert load_catalogue(p)[name] == spec


def test_uniform_box_centred_on_module_loads_only_that_module() -> None:
    """A 30 mm box in the middle of module 5 puts its whole weight on module 5."""
    from softpad.sim import ObjectSpec, PartSpec, Placement

    spec = ObjectSpec(
        "cube",
        0.02,
        (PartSpec("box", 0.02, (0, 0, 0.015), size_m=(0.03, 0.03, 0.03)),),
        Placement(1.5 * 0.045, 0.5 * 0.045),
    )
    fp = object_footprint(spec, PadSurface())
    expected = np.zeros(6)
    expected[4] = 1.0
    np.testing.assert_allclose(fp.weight_fraction, expected, atol=1e-9)


def test_heavier_part_loads_its_module_more() -> None:
    """Moment balance: a bar over modules 4 and 5 with a weight on its left end."""
    from softpad.sim import ObjectSpec, PartSpec, Placement

    bar = PartSpec("box", 0.01, (0, 0, 0.005), size_m=(0.08, 0.02, 0.01))
    weight = PartSpec("box", 0.01, (-0.01, 0, 0.015), size_m=(0.01, 0.01, 0.01))
    spec = ObjectSpec("bar", 0.02, (bar, weight), Placement(0.045, 0.0225))
    f = object_footprint(spec, PadSurface(line_width_m=0.0)).weight_fraction
    # rigid bar on a uniform bed: q linear; left half carries 1/2 + 1.5 e / L of the weight
    e = -0.005  # COM offset, m (small enough that no point lifts off)
    np.testing.assert_allclose(f[3], 0.5 - 1.5 * e / 0.08, rtol=2e-3)
    np.testing.assert_allclose(f[4], 0.5 + 1.5 * e / 0.08, rtol=2e-3)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("{", "not valid JSON"),
        ('{"schema": "other"}', "schema"),
        (
            '{"schema": "softpad-objects/1", "objects": [{"name": "a", "mass_kg": 0.01, "parts": []}]}',
            "at least one part",
        ),
        (
            '{"schema": "softpad-objects/1", "objects": [{"name": "a", "mass_kg": 0.01, "parts": '
            '[{"shape": "cone", "pos_m": [0,0,0], "mass_kg": 0.01}], "placement": {"x_m": 0, "y_m": 0}}]}',
            "shape",
        ),
        (
            '{"schema": "softpad-objects/1", "objects": [{"name": "a", "mass_kg": 0.02, "parts": '
            '[{"shape": "sphere", "radius_m": 0.01, "pos_m": [0,0,0.01], "mass_kg": 0.01}], '
            '"placement": {"x_m": 0, "y_m": 0}}]}',
            "weigh",
        ),
    ],
    ids=["bad-json", "bad-schema", "no-parts", "bad-shape", "mass-mismatch"],
)
def test_bad_catalogue_raises_input_error(tmp_path, text: str, match: str) -> None:
    p = tmp_path / "bad.json"
    p.write_text(text)
    with pytest.raises(InputError, match=match):
        load_catalogue(p)


def test_missing_catalogue_file() -> None:
    with pytest.raises(InputError, match="cannot read"):
        load_catalogue("/nonexistent/objects.json")


def test_unknown_object_lists_names() -> None:
    with pytest.raises(InputError, match="known objects: object-1"):
        get_object("teapot")


def test_packaged_file_is_valid_json_with_schema() -> None:
    from importlib import resources

    raw = json.loads(resources.files("softpad").joinpath("data", "objects.json").read_text())
    assert raw["schema"] == "softpad-objects/1"
