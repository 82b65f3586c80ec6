"""A pad's readings from a frame file's text (softpad.sensing.parse_readings, PadReadings):
the formats, the increments checked against the pad and the sensor's range."""

from __future__ import annotations

import pytest

from softpad.errors import InputError
from softpad.layout import PadLayout
from softpad.sensing import PadReadings, parse_readings

PAD = PadLayout()


@pytest.mark.parametrize(
    ("text", "values_pa", "reference_pa"),
    [
        ('{"delta_kpa": [0, 0.124, 0.078, 0.109, 0, 0]}', (0, 124, 78, 109, 0, 0), None),
        ('{"pressures_kpa": [1.2, 1.1], "reference_kpa": [1.1, 1.1]}', (1200, 1100), (1100, 1100)),
        ("0,0.124,0.078,0.109,0,0\n", (0, 124, 78, 109, 0, 0), None),
        ("delta_kpa\n0\n0.062\n", (0, 62), None),
        ("pressure_kpa,reference_kpa\r1.2,1.1\r1.15,1.1\r", (1200, 1150), (1100, 1100)),
    ],
    ids=["json-delta", "json-pressures", "csv-line", "csv-delta", "csv-pressures-cr"],
)
def test_the_formats_read_to_pascals(text: str, values_pa, reference_pa) -> None:
    r = parse_readings(text, "frame")
    assert r.values_pa == pytest.approx(values_pa)
    if reference_pa is None:
        assert r.reference_pa is None
    else:
        assert r.reference_pa == pytest.approx(reference_pa)


@pytest.mark.parametrize(
    ("text", "match"),
    [
        ("", "f is empty"),
        ("{not json", "not valid JSON"),
        ('{"delta": [1]}', "needs key delta_kpa"),
        ('{"delta_kpa": [0], "pressures_kpa": [1]}', "both delta_kpa and pressures_kpa"),
        ('{"delta_kpa": "0,1"}', "delta_kpa must be a list"),
        ("0,1_0", "item 2 '1_0' is not a number"),
        ("0\n0", "without a header give one line"),
        ("module,weight\n1,2\n", "header must name delta_kpa"),
        ("delta_kpa\n", "a header but no data rows"),
    ],
    ids=[
        "empty", "bad-json", "bad-key", "both", "not-a-list", "separator", "two-lines",
        "bad-header", "no-rows",
    ],
)  # fmt: skip
def test_bad_text_is_an_input_error_naming_it(text: str, match: str) -> None:
    with pytest.raises(InputError, match=match):
        parse_readings(text, "f")


def test_increments_are_checked_against_the_pad_and_the_sensor() -> None:
    banana = PadReadings((0.0, 124.0, 78.0, 109.0, 0.0, 0.0))
    assert banana.increments_pa(PAD, "s") == [0.0, 124.0, 78.0, 109.0, 0.0, 0.0]
    with pytest.raises(InputError, match="s: a 2x3 pad needs 6 increments"):
        PadReadings((0.0,) * 5).increments_pa(PAD, "s")
    with pytest.raises(InputError, match=r"module 2 is 124 kPa.*pascals given as kPa"):
        PadReadings((0.0, 124e3, 0.0, 0.0, 0.0, 0.0)).increments_pa(PAD, "s")
    with pytest.raises(InputError, match="module 1 is -3 kPa"):
        PadReadings((-3e3, 0.0, 0.0, 0.0, 0.0, 0.0)).increments_pa(PAD, "s")


def test_readings_with_a_reference_give_their_difference() -> None:
    r = PadReadings((1200.0,) + (1100.0,) * 5, (1100.0,) * 6)
    assert r.increments_pa(PAD, "s") == pytest.approx([100.0, 0, 0, 0, 0, 0])
    with pytest.raises(InputError, match="s: pressures: module 1 reads 1200 kPa"):
        PadReadings((1.2e6,) + (1100.0,) * 5, (1100.0,) * 6).increments_pa(PAD, "s")
    with pytest.raises(InputError, match="needs 6 pressures and 6 reference values"):
        PadReadings((1100.0,) * 5, (1100.0,) * 5).increments_pa(PAD, "s")
