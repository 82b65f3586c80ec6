"""Argument parsing helpers shared by the sub-commands: numbers with units, lists, files."""

from __future__ import annotations

import argparse
import functools
import math
import re
import sys
from typing import Any

from softpad.errors import InputError


class UsageError(InputError):
    """The command line does not parse (unknown option, missing value)."""


def number_list(text: str, flag: str, scale: float = 1.0, positive: bool = False) -> list[float]:
    """Parse ``"1,1.5,2"`` into floats times ``scale``, naming the flag and the bad item on error."""
    items = [s.strip() for s in str(text).split(",")]
    if items == [""]:
        raise InputError(f"{flag} needs comma-separated numbers, got an empty value")
    out = []
    for i, s in enumerate(items, 1):
        v = plain_number(s, f"{flag}: item {i}")
        if not math.isfinite(v * scale):
            raise InputError(f"{flag}: item {i} must be finite, got {s!r}")
        if positive and v <= 0:
            raise InputError(f"{flag}: item {i} must be > 0, got {s!r}")
        out.append(v * scale)
    return out


#: What a number on the command line may look like: ASCII digits, one optional sign, decimal
#: point and exponent; no digit separators (``1_0``), no other scripts' digits, no spaces.
_PLAIN_NUMBER = re.compile(
    r"[+-]?(\d+\.?\d*|\.\d+)([eE][+-]?\d+)?|[+-]?(inf|nan)", re.IGNORECASE | re.ASCII
)


def plain_number(text: str, what: str) -> float:
    """``float(text)`` for a plain ASCII decimal number only, else :class:`InputError` naming
    ``what`` and the text (Python's ``float`` also takes ``1_0`` and non-ASCII digits)."""
    s = str(text).strip()
    if not _PLAIN_NUMBER.fullmatch(s):
        raise InputError(f"{what} {s!r} is not a number (ASCII digits like 0.12 or 1e-3)")
    return float(s)


#: What an integer on the command line may look like (``int`` also takes ``1_0`` and ``٣``).
_PLAIN_INTEGER = re.compile(r"[+-]?\d+", re.ASCII)


def plain_int(text: str) -> int:
    """``int(text)`` for plain ASCII digits only, else :class:`argparse.ArgumentTypeError`
    naming the text (the ``type=int`` of every option, see :class:`softpad.cli.main._Parser`)."""
    s = str(text).strip()
    if not _PLAIN_INTEGER.fullmatch(s):
        raise argparse.ArgumentTypeError(f"{s!r} is not an integer (ASCII digits like 10)")
    return int(s)


def plain_float(text: str) -> float:
    """:func:`plain_number` as an argparse type (the ``type=float`` of every option)."""
    try:
        return plain_number(text, "the value")
    except InputError as exc:
        raise argparse.ArgumentTypeError(str(exc)) from None


def kpa_list(text: str, flag: str) -> list[float]:
    """Parse ``"0.1,0,0.2"`` (kPa) into pascals, naming the flag and the bad item on error."""
    return number_list(text, flag, scale=1e3)


def finite_float(name: str, lo: float | None = None, hi: float | None = None, unit: str = ""):
    """An argparse ``type=`` that accepts a finite float within [lo, hi]."""

    def parse(text: str) -> float:
        try:
            v = plain_number(text, name)
        except InputError:
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
            v = plain_int(text)
        except argparse.ArgumentTypeError:
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


#: Help of ``--json`` where a command says nothing more specific.
JSON_HELP = "print one JSON object on stdout (text on stderr)"


def add_command(
    sub: Any,
    name: str,
    help: str,
    description: str | None = None,
    epilog: str | None = None,
    *,
    json: str | None = JSON_HELP,
    force: bool = False,
) -> argparse.ArgumentParser:
    """Register the sub-command ``name`` under ``sub`` (an ``add_subparsers`` action).

    Parameters
    ----------
    help
        One line in the list of commands of the parent's ``--help``.
    description, epilog
        Text above and below the options, printed as written (wrapped by hand; usually a
        module constant).
    json
        Help of the command's ``--json`` option; ``None`` adds none.
    force
        Add ``--force`` (overwrite existing output files), for commands that write files.
    """
    p: argparse.ArgumentParser = sub.add_parser(
        name,
        help=help,
        description=description,
        epilog=epilog,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    if json is not None:
        p.add_argument("--json", action="store_true", help=json)
    if force:
        p.add_argument("--force", action="store_true", help="overwrite existing output files")
    return p


def add_group(sub: Any, name: str, *texts: str | None, metavar: str = "ACTION") -> Any:
    """Register ``name`` as a group of sub-commands and return its ``add_subparsers`` action.

    ``texts`` are the help, description and epilog of :func:`add_command`. The group alone
    (``softpad box``) prints its help on stderr and is a usage error naming the ``metavar``
    and the sub-commands.
    """
    p = add_command(sub, name, *texts, json=argparse.SUPPRESS)  # type: ignore[arg-type]
    actions = p.add_subparsers(dest=f"{name}_command", metavar=metavar)
    p.set_defaults(handler=functools.partial(_missing, p, actions))
    return actions


def _missing(parser: argparse.ArgumentParser, actions: Any, args: argparse.Namespace) -> int:
    """Handler of a group called without its sub-command (see :func:`add_group`)."""
    parser.print_help(sys.stderr)
    names = list(actions.choices)
    listing = ", ".join(names[:-1]) + (" or " if len(names) > 1 else "") + names[-1]
    article = "an" if actions.metavar[0] in "AEIOU" else "a"
    raise UsageError(
        f"{article} {actions.metavar} is required: {listing} (see {parser.prog} --help)"
    )


def add_box_option(
    p: argparse.ArgumentParser, default: str | None = "sim://", help: str | None = None
) -> None:
    """``--box URL``: the box to open (:func:`softpad.box.open_box`)."""
    p.add_argument(
        "--box", default=default, metavar="URL", help=help or f"box URL (default {default})"
    )


def add_number(p: Any, flag: str, help: str, default: float | None = None, **limits: Any) -> None:
    """``flag`` taking a finite number; ``limits`` are :func:`finite_float`'s ``lo``, ``hi``
    and ``unit``; ``p`` is a parser or an argument group."""
    p.add_argument(flag, type=finite_float(flag, **limits), default=default, help=help)


def add_integer(p: Any, flag: str, help: str, default: int, lo: int, hi: int) -> None:
    """``flag`` taking an integer from ``lo`` to ``hi`` (see :func:`bounded_int`)."""
    p.add_argument(flag, type=bounded_int(flag, lo, hi), default=default, help=help)


def add_p0_option(p: Any) -> None:
    """``--p0-kpa``: the pressure every module is inflated to (p0, thesis Section 6.2.1.1)."""
    from softpad import thesis

    add_number(
        p,
        "--p0-kpa",
        "p0, pressure every module is inflated to, kPa, 0.5..2.8 (default 1.1)",
        thesis.P0_PA / 1e3,
        lo=0.5,
        hi=2.8,
        unit="kPa",
    )


def add_registry_option(
    p: Any, flag: str, registry: Any, what: str, default: str | None = "thesis"
) -> None:
    """``flag`` choosing a part from ``registry`` (:class:`softpad.registry.Registry`): its
    choices and help are the registered parts (entry points of installed packages included)."""
    parts = registry.help().replace("%", "%%")
    tail = f" (default {default})" if default is not None else ""
    p.add_argument(flag, choices=registry.names(), default=default, help=f"{what}: {parts}{tail}")
