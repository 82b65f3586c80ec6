"""A sweep refuses, before any work, an object set whose objects would lie off a design's
pad (ObjectSet.check_on_pads, moved from the command line)."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from softpad.design import THESIS_DESIGN, example_object_set
from softpad.errors import InputError


def test_the_thesis_set_lies_on_the_thesis_pad() -> None:
    example_object_set("thesis-set").check_on_pads([THESIS_DESIGN])


def test_an_object_off_a_small_pad_is_named_with_the_pad() -> None:
    tiny = SimpleNamespace(rows=1, cols=1, pitch_m=0.02)
    with pytest.raises(InputError, match=r"object '[^']+' would lie .*the 1x1 pad of 20 x 20 mm"):
        example_object_set("thesis-set").check_on_pads([THESIS_DESIGN, tiny])
