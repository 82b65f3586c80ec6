"""Argument parsing helpers shared by the sub-commands: numbers with units, lists, files."""

from __future__ import annotations

import argparse
import math

from softpad.errors import InputError


def number_list(text: str, flag: str, scale: float = 1.0, positive: bool = False) -> list[float]:
    """Parse ``"1,1.5,2"`` into floats times ``scale``, naming the flag and the bad item on error."""
    items = [s.strip() for s in str(text).replace(";", ",").split(",")]
    if items == [""]:
        raise InputError(f"{flag} needs comma-separated numbers, got an empty value")
    out = []
    for i, s in enumerate(items, 1):
        try:
            v = float(s)
        except ValueError:
            raise InputError(f"{flag}: item {i} {s!r} is not a number") from None
        if not math.isfinite(v):
            raise InputError(f"{flag}: item {i} must be finite, got {s!r}")
        if positive and v <= 0:
            raise InputError(f"{flag}: item {i} must be > 0, got {s!r}")
        out.append(v * scale)
    return out


def kpa_list(text: str, flag: str) -> list[float]:
    """Parse ``"0.1,0,0.2"`` (kPa) into pascals, naming the flag and the bad item on error."""
    return number_list(text, flag, scale=1e3)


def finite_float(name: str, lo: float | None = None, hi: float | None = None, unit: str = ""):
    """An argparse ``type=`` that accepts a finite float within [lo, hi]."""

    def parse(text: str) -> float:
        try:
            v = float(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be a number, got {text!r}") from None
        if not math.isfinite(v):
            raise argparse.ArgumentTypeError(f"{name} must be finite, got {text!r}")
        u = f" {unit}" if unit else ""
        if lo is not None and v < lo:
            raise argparse.ArgumentTypeError(f"{name} must be >= {lo:g}{u}, got {v:g}{u}")
        if hi is not None and v > hi:
            raise argparse.ArgumentTypeError(f"{name} must be <= {hi:g}{u}, got {v:g}{u}")
        return v

    parse.__name__ = name
    return parse


def bounded_int(name: str, lo: int, hi: int):
    """An argparse ``type=`` that accepts an integer within [lo, hi]."""

    def parse(text: str) -> int:
        try:
            v = int(text)
        except ValueError:
            raise argparse.ArgumentTypeError(f"{name} must be an integer, got {text!r}") from None
        if not lo <= v <= hi:
            raise argparse.ArgumentTypeError(f"{name} must be from {lo} to {hi}, got {v}")
        return v

    parse.__name__ = name
    return parse


def name_list(text: str, flag: str) -> list[str]:
    """Parse ``"a,b"`` into names: none empty, none repeated (the flag and item named on error)."""
    items = [s.strip() for s in str(text).split(",")]
    if not any(items):
        raise InputError(f"{flag} needs comma-separated names, got {text!r}")
    for i, s in enumerate(items, 1):
        if not s:
            raise InputError(f"{flag}: item {i} is empty in {text!r}")
        if s in items[: i - 1]:
            raise InputError(f"{flag}: {s!r} is named twice in {text!r}")
    return items


def int_ranges(text: str, flag: str, lo: int = 0, hi: int = 2**31 - 1) -> list[int]:
    """Parse ``"0-9"``, ``"3"`` or ``"0-2,7"`` into integers within [lo, hi], in order, once each."""
    out: list[int] = []
    for item in (s.strip() for s in str(text).split(",")):
        a, sep, b = item.partition("-")
        try:
            first = int(a)
            last = int(b) if sep else first
        except ValueError:
            raise InputError(
                f"{flag}: {item!r} is not an integer or a range like 0-9 (from {lo} to {hi})"
            ) from None
        if not (lo <= first <= hi and lo <= last <= hi) or last < first:
            raise InputError(f"{flag}: {item!r} must lie within {lo}..{hi}, first <= last")
        if last - first >= 10_000:
            raise InputError(f"{flag}: {item!r} has more than 10000 values")
        out.extend(v for v in range(first, last + 1) if v not in out)
    return out


class Renamed(argparse.Action):
    """An option that was renamed: using it is a usage error naming the new spelling."""

    def __init__(self, option_strings: list[str], dest: str, new: str = "", **kwargs: object):
        kwargs["help"] = argparse.SUPPRESS
        super().__init__(option_strings, dest, **kwargs)  # type: ignore[arg-type]
        self.new = new

    def __call__(self, parser: argparse.ArgumentParser, *args: object, **kwargs: object) -> None:
        parser.error(f"{'/'.join(self.option_strings)} is now {self.new}")


def add_json_force(p: argparse.ArgumentParser, force: bool = True) -> None:
    """``--json`` (one JSON object on stdout) and, for commands that write files, ``--force``."""
    p.add_argument(
        "--json", action="store_true", help="print one JSON object on stdout (text on stderr)"
    )
    if force:
        p.add_argument("--force", action="store_true", help="overwrite existing output files")
