"""Back-ends chosen by URL: ``open_box("sim://?seed=1&channels=8")``."""

from __future__ import annotations

from collections.abc import Callable
from urllib.parse import parse_qsl, urlsplit

from softpad.box._base import Box
from softpad.errors import InputError

#: Factories by URL scheme; each takes (netloc + path, options) and returns an open Box.
_BACKENDS: dict[str, Callable[[str, dict[str, str]], Box]] = {}

#: URL of the default back-end (the simulated box).
DEFAULT_URL = "sim://"


def register_backend(scheme: str, factory: Callable[[str, dict[str, str]], Box]) -> None:
    """Make ``open_box("<scheme>://...")`` call ``factory(location, options)``."""
    _BACKENDS[scheme.lower()] = factory


def backends() -> tuple[str, ...]:
    """Registered URL schemes (and those offered through :data:`ENTRY_POINT_GROUP`)."""
    from importlib.metadata import entry_points

    _ensure_builtin()
    return tuple(sorted(set(_BACKENDS) | {ep.name for ep in entry_points(group=ENTRY_POINT_GROUP)}))


def _open_sim(location: str, options: dict[str, str]) -> Box:
    """``sim://``: the simulator is imported only when a simulated box is opened."""
    from softpad.box._sim_url import open_sim_url

    return open_sim_url(location, options)


def _open_zenoh(location: str, options: dict[str, str]) -> Box:
    from softpad.box._zenoh import open_zenoh_url

    return open_zenoh_url(location, options)


def _ensure_builtin() -> None:
    _BACKENDS.setdefault("sim", _open_sim)
    _BACKENDS.setdefault("zenoh", _open_zenoh)


#: Entry-point group through which installed packages offer box back-ends by URL scheme (the
#: ``replay://`` back-end of ``softpad.record`` comes this way: the box layer imports nothing
#: above it).
ENTRY_POINT_GROUP = "softpad.box_backends"


def _from_entry_points(scheme: str) -> Callable[[str, dict[str, str]], Box] | None:
    from importlib.metadata import entry_points

    for ep in entry_points(group=ENTRY_POINT_GROUP):
        if ep.name.lower() == scheme:
            factory: Callable[[str, dict[str, str]], Box] = ep.load()
            register_backend(scheme, factory)
            return factory
    return None


def parse_url(url: str) -> tuple[str, str, dict[str, str]]:
    """Split a box URL into (scheme, location, options); InputError on a malformed one."""
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
        or ``replay://run.mcap[?speed=fast|recorded|FACTOR]`` (a recording played back,
        :class:`softpad.record.ReplayBox`).

    Raises
    ------
    InputError
        Unknown scheme or option, or a malformed value (the message names it).
    """
    _ensure_builtin()
    scheme, location, options = parse_url(url)
    factory = _BACKENDS.get(scheme) or _from_entry_points(scheme)
    if factory is None:
        raise InputError(
            f"unknown box URL scheme {scheme!r} in {url!r}; available: {', '.join(backends())}"
        )
    try:
        return factory(location, options)
    except InputError as exc:
        if url in str(exc):
            raise
        raise InputError(f"{exc} (box URL {url!r})") from None
