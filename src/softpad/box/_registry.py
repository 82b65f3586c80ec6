"""Back-ends chosen by URL: ``open_box("sim://?seed=1&channels=8")``.

Back-ends are parts of a :class:`softpad.registry.Registry` (:data:`BOX_BACKENDS`, entry-point
group :data:`ENTRY_POINT_GROUP`), as planners, detectors and robots are. Built in:

=====================  ============================================================
``sim://``             the simulated box (:func:`softpad.box.open_sim_url`)
``zenoh://host:port``  a box served by ``softpad box serve`` (:class:`ZenohBox`)
``hw://FILE.toml``     the real Pneumaticbox wired as the installation file says
                       (:class:`HardwareBox`; ``hw:///etc/softpad/site.toml``)
=====================  ============================================================

``replay://run.mcap`` comes from :mod:`softpad.record` through the entry point (the box layer
imports nothing above it). What a served back-end offers besides frames and valves (the
simulator's world and robot, ``sim.setup`` ...) is registered beside it in
:data:`BOX_SERVICES` under the same scheme.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any
from urllib.parse import parse_qsl, urlsplit

from softpad.box._base import Box
from softpad.errors import InputError
from softpad.registry import Registry

#: A back-end's factory: (netloc + path, options) -> an open box.
BoxFactory = Callable[[str, dict[str, str]], Box]

#: Entry-point group through which installed packages offer box back-ends by URL scheme.
ENTRY_POINT_GROUP = "softpad.box_backends"

#: Box back-ends by URL scheme.
BOX_BACKENDS: Registry[BoxFactory] = Registry("box back-end", ENTRY_POINT_GROUP)
BOX_BACKENDS.register_lazy(
    "sim", "softpad.box._sim_url:open_sim_url", "the simulated box (gas physics, world, sensors)"
)
BOX_BACKENDS.register_lazy(
    "zenoh", "softpad.box._zenoh:open_zenoh_url", "a box served over zenoh by softpad box serve"
)
BOX_BACKENDS.register_lazy(
    "hw", "softpad.box._hardware_url:open_hardware_url", "the real box, wired in FILE.toml"
)

#: Services a served box of a scheme offers (``softpad box serve``): factories taking the open
#: box and returning ``{op: handler}`` (see :class:`~softpad.box.BoxDaemon`'s ``services``).
BOX_SERVICES: Registry[Callable[[Box], Mapping[str, Any]]] = Registry(
    "box service set", "softpad.box_services"
)
# the simulator's world and robot: the simulated arm lives above the box layer (a lazy string)
BOX_SERVICES.register_lazy(
    "sim", "softpad.harness:served_simulation", "the simulated world and robot (sim.*, robot.*)"
)

#: URL of the default back-end (the simulated box).
DEFAULT_URL = "sim://"


def register_backend(scheme: str, factory: BoxFactory, summary: str | None = None) -> None:
    """Make ``open_box("<scheme>://...")`` call ``factory(location, options)``.

    Parameters
    ----------
    scheme
        The URL scheme (lower case).
    factory
        Takes the URL's location (netloc + path) and options, returns an open :class:`Box`.
    summary
        One line for help texts (default: the factory's docstring's first line).
    """
    BOX_BACKENDS.register(scheme.lower(), factory, summary)


def available_box_backends() -> tuple[str, ...]:
    """URL schemes of the box back-ends (built in, registered, and from entry points)."""
    return BOX_BACKENDS.names()


def served_services(url: str, box: Box) -> dict[str, Any]:
    """The services ``softpad box serve`` offers for the box opened from ``url``: those
    registered for its scheme in :data:`BOX_SERVICES` (none for a real box).

    Parameters
    ----------
    url
        The box's URL.
    box
        The box opened from it.

    Returns
    -------
    dict
        ``{op: handler}`` for :class:`~softpad.box.BoxDaemon`.
    """
    scheme = parse_url(url)[0]
    if scheme not in BOX_SERVICES.names():
        return {}
    return dict(BOX_SERVICES.factory(scheme)(box))


def parse_url(url: str) -> tuple[str, str, dict[str, str]]:
    """Split a box URL into (scheme, location, options); InputError on a malformed one.

    Parameters
    ----------
    url
        ``scheme://location?key=value&...``.
    """
    if not isinstance(url, str) or "://" not in url:
        raise InputError(f"box URL must look like 'scheme://...' (e.g. sim://?seed=1), got {url!r}")
    try:
        parts = urlsplit(url)
    except ValueError as exc:
        raise InputError(f"malformed box URL {url!r}: {exc}") from None
    try:
        pairs = parse_qsl(parts.query, keep_blank_values=True, strict_parsing=bool(parts.query))
    except ValueError:
        raise InputError(f"malformed options in box URL {url!r}") from None
    options: dict[str, str] = {}
    for k, v in pairs:
        if k in options:
            raise InputError(f"option {k!r} given twice in box URL {url!r}")
        options[k] = v
    return parts.scheme.lower(), parts.netloc + parts.path, options


def open_box(url: str = DEFAULT_URL) -> Box:
    """Open the box named by ``url``.

    Parameters
    ----------
    url
        ``sim://`` (the simulated box, see :func:`softpad.box.open_sim_url` for its options)
        or ``zenoh://host:port[/prefix]`` (a box served by ``softpad box serve``,
        :class:`softpad.box.ZenohBox`)
        or ``hw://FILE.toml`` (the real box wired as the installation file says,
        :class:`softpad.box.HardwareBox`)
        or ``replay://run.mcap[?speed=fast|recorded|FACTOR]`` (a recording played back,
        :class:`softpad.record.ReplayBox`); any scheme of :func:`available_box_backends`.

    Raises
    ------
    InputError
        Unknown scheme or option, or a malformed value (the message names it).
    """
    scheme, location, options = parse_url(url)
    if scheme not in BOX_BACKENDS.names():
        raise InputError(
            f"unknown box URL scheme {scheme!r} in {url!r}; available: "
            + ", ".join(f"{s}://" for s in available_box_backends())
        )
    factory = BOX_BACKENDS.factory(scheme)
    try:
        return factory(location, options)
    except InputError as exc:
        if url in str(exc):
            raise
        raise InputError(f"{exc} (box URL {url!r})") from None
