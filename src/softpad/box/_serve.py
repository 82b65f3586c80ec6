"""What ``softpad box serve`` serves and how: the box's URL with the simulator's frame rate,
the installation's link with the endpoints given, the TLS and real-time checks, and the
daemon built from them (:class:`ServeOptions`).

Every check raises :class:`~softpad.errors.InputError` naming the value, its limit and the
option it came from.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

from softpad.errors import InputError

#: Frame rate of a served simulator unless the URL or the rate given says otherwise, Hz (the
#: hardware box's default sample rate).
SERVE_SIM_RATE_HZ = 1000.0


@dataclass(frozen=True)
class ServeOptions:
    """The daemon to serve, as ``softpad box serve`` is told it.

    Parameters
    ----------
    box
        The back-end's URL (``sim://...``, ``hw://FILE.toml``, any registered scheme).
    hardware
        An installation file whose wired box is served (``hw://FILE``), or None.
    config
        The installation file of the link and thresholds, or None (the URL's ``hw://`` file,
        else the defaults).
    listen
        Zenoh endpoints to listen on instead of the installation's.
    port
        A TCP port on 127.0.0.1 (1..65535) listened on beside ``listen``, or None.
    rate_hz
        The served simulator's frame rate, Hz; None: the URL's ``rate_hz``, else
        :data:`SERVE_SIM_RATE_HZ`.
    watchdog_s
        Controller silence that closes the inflation valves, s; None: the link's.
    realtime
        Run the simulator on the wall clock even when its controller lags (default: at most
        2 frames ahead of what the controller read).
    rt_priority
        SCHED_FIFO priority 1..99 of the daemon, or None.
    """

    box: str = "sim://"
    hardware: str | None = None
    config: str | None = None
    listen: Sequence[str] = ()
    port: int | None = None
    rate_hz: float | None = None
    watchdog_s: float | None = None
    realtime: bool = False
    rt_priority: int | None = None

    @property
    def url(self) -> str:
        """The served URL: ``hw://`` of :attr:`hardware`, else :attr:`box` with the
        simulator's rate (:attr:`rate_hz`, else the URL's, else :data:`SERVE_SIM_RATE_HZ`)."""
        from softpad.box._registry import parse_url

        if self.hardware:
            return f"hw://{self.hardware}"
        url = str(self.box)
        if not url.startswith("sim://"):
            return url
        if self.rate_hz is None and "rate_hz" in parse_url(url)[2]:
            return url
        rate = self.rate_hz or SERVE_SIM_RATE_HZ
        if "rate_hz" in parse_url(url)[2]:
            raise InputError("give the rate once: --rate-hz or the URL's rate_hz")
        return url + ("&" if "?" in url else "?") + f"rate_hz={rate:g}"

    @property
    def served(self) -> str:
        """What is served, in words: the hardware's installation file or the simulator."""
        if self.hardware:
            return f"the hardware box wired in {self.hardware}"
        return f"the simulated box {self.url}"

    def installation(self) -> Any:
        """The :class:`~softpad.config.Installation` of :attr:`hardware`, :attr:`config` or
        the ``hw://`` URL's file, else the defaults."""
        from softpad.box._registry import parse_url
        from softpad.config import Installation, load_installation

        scheme, location, _options = parse_url(self.url)
        path = self.hardware or self.config or (location if scheme == "hw" else None)
        return load_installation(path) if path else Installation()

    def link(self, installation: Any) -> Any:
        """The installation's link with :attr:`listen` and :attr:`port` as its endpoints,
        checked (remote policy, TLS)."""
        from softpad.config import check_endpoint, check_remote_policy

        link = installation.link
        listen = [check_endpoint(e, "--listen") for e in self.listen]
        if self.port is not None:
            if not 1 <= self.port <= 65535:
                raise InputError(f"--port must be within 1..65535, got {self.port}")
            listen.append(f"tcp/127.0.0.1:{self.port}")
        if listen:
            link = dataclasses.replace(link, listen=tuple(listen))
            check_remote_policy(link)
        if link.tls_certificate is not None and not any(e.startswith("tls/") for e in link.listen):
            raise InputError(
                "link.tls_certificate is set but no listen endpoint is tls/: TLS would protect "
                f"nothing on {', '.join(link.listen)}; listen on tls/HOST:PORT or drop the TLS keys"
            )
        return link

    def daemon(self, log: Callable[[str], None] | None = None) -> Any:
        """The :class:`~softpad.box.BoxDaemon` serving the opened box (not started).

        Parameters
        ----------
        log
            Where the daemon's messages go, or None (its default).
        """
        from softpad.box._credentials import daemon_auth
        from softpad.box._daemon import BoxDaemon
        from softpad.box._registry import open_box, served_services

        if self.rt_priority is not None and not 1 <= self.rt_priority <= 99:
            raise InputError(f"--rt-priority must be from 1 to 99, got {self.rt_priority}")
        url = self.url
        inst = self.installation()
        link = self.link(inst)
        box = open_box(url)
        try:
            services = served_services(url, box)  # the simulator's world and robot for sim://
            return BoxDaemon(
                box, link.listen, link.key_prefix,
                max_pressure_pa=inst.thresholds.max_pressure_pa,
                watchdog_s=self.watchdog_s or link.watchdog_s,
                watchdog_action=link.watchdog_action, services=services,
                lockstep_frames=2 if services and not self.realtime else None,
                rt_priority=self.rt_priority, auth=daemon_auth(link), log=log,
            )  # fmt: skip
        except BaseException:
            box.close()
            raise


__all__ = ["SERVE_SIM_RATE_HZ", "ServeOptions"]
