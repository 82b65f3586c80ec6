"""What ``softpad config check`` and ``softpad box serve`` check beyond the file's own values:
the link's files (password file, certificates, keys) and weak settings.

:func:`parse_installation` never touches the file system (a workstation reads a file written
for the box); :func:`audit_link` reads the files the link names and says what is wrong with
them (errors) and what is weak (warnings). ``box serve`` refuses to start on any error
(:func:`softpad.box._credentials.daemon_auth`): zenoh takes an empty user/password file as no
authentication at all (issue 49: a client with only the CA certificate took control).
"""

from __future__ import annotations

import stat
from collections.abc import Mapping
from pathlib import Path
from typing import Any

#: Passwords shorter than this are called weak (a warning).
MIN_PASSWORD_CHARS = 12
#: A watchdog longer than this is called weak (a warning), seconds: a controller that vanished
#: leaves its valves open that long (the box-side pressure limit still holds).
WEAK_WATCHDOG_S = 2.0


def audit_link(link: Mapping[str, Any]) -> tuple[list[str], list[str]]:
    """``(errors, warnings)`` about the files and settings of a ``[link]`` table (the raw
    table or :func:`dataclasses.asdict` of :class:`~softpad.config.LinkSettings`; values that
    are not strings are the parser's business and skipped here)."""
    errors: list[str] = []
    warnings: list[str] = []
    text = {k: v for k, v in link.items() if isinstance(v, str) and v.strip()}
    if "password_file" in text:
        _password_file(Path(text["password_file"]), text.get("user"), errors, warnings)
    for key, want in (
        ("tls_certificate", "certificate"),
        ("tls_root_ca", "certificate"),
        ("tls_private_key", "key"),
    ):
        if key in text:
            _pem(key, Path(text[key]), want, errors, warnings)
    watchdog = link.get("watchdog_s")
    if isinstance(watchdog, int | float) and not isinstance(watchdog, bool):
        if WEAK_WATCHDOG_S < watchdog <= 5.0:
            warnings.append(
                f"link.watchdog_s = {watchdog:g} s: a controller that vanished keeps its "
                f"valves that long (at most {WEAK_WATCHDOG_S:g} s is advised)"
            )
    listen = link.get("listen")
    remote = isinstance(listen, list) and any(
        isinstance(e, str) and not _loopback(e) for e in listen
    )
    if remote and "tls_root_ca" not in text:
        warnings.append(
            "listening beyond loopback without client certificates (link.tls_root_ca): any "
            "client holding the password controls the box; mutual TLS is stronger"
        )
    return errors, warnings


def _loopback(endpoint: str) -> bool:
    from softpad.config._settings import is_loopback_endpoint

    return is_loopback_endpoint(endpoint)


def _password_file(path: Path, user: str | None, errors: list[str], warnings: list[str]) -> None:
    name = f"link.password_file {str(path)!r}"
    try:
        text = path.read_text(encoding="utf-8")
        mode = path.stat().st_mode
    except (OSError, UnicodeDecodeError) as exc:
        errors.append(f"{name} cannot be read: {getattr(exc, 'strerror', None) or exc}")
        return
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    pairs = [ln.partition(":") for ln in lines]
    good = {u: pw for u, sep, pw in pairs if sep and u and pw}
    if not lines:
        errors.append(
            f"{name} is empty: zenoh would then turn user/password authentication off "
            "(anyone could connect); write user:password lines"
        )
    elif not good:
        errors.append(f"{name} has no user:password line (zenoh's format; one per user)")
    elif len(good) < len(lines):
        errors.append(f"{name}: {len(lines) - len(good)} line(s) are not user:password")
    if user and good and user not in good:
        errors.append(f"{name} has no line for link.user {user!r}")
    if mode & (stat.S_IRWXG | stat.S_IRWXO):
        warnings.append(
            f"{name} is readable by other users of this machine (mode {stat.S_IMODE(mode):o}): "
            "chmod 600 it"
        )
    short = [u for u, pw in good.items() if len(pw) < MIN_PASSWORD_CHARS]
    if short:
        warnings.append(
            f"{name}: the password of {', '.join(repr(u) for u in short)} is shorter than "
            f"{MIN_PASSWORD_CHARS} characters"
        )


def _pem(key: str, path: Path, want: str, errors: list[str], warnings: list[str]) -> None:
    name = f"link.{key} {str(path)!r}"
    try:
        text = path.read_text(encoding="ascii", errors="replace")
        mode = path.stat().st_mode
    except OSError as exc:
        errors.append(f"{name} cannot be read: {exc.strerror}")
        return
    has_cert = "-----BEGIN CERTIFICATE-----" in text
    has_key = "PRIVATE KEY-----" in text
    if want == "certificate" and not has_cert:
        hint = " (it holds a private key: certificate and key swapped?)" if has_key else ""
        errors.append(f"{name} is not a PEM certificate{hint}")
    elif want == "key" and not has_key:
        hint = " (it holds a certificate: certificate and key swapped?)" if has_cert else ""
        errors.append(f"{name} is not a PEM private key{hint}")
    elif want == "key" and mode & (stat.S_IRWXG | stat.S_IRWXO):
        warnings.append(
            f"{name} is readable by other users of this machine (mode {stat.S_IMODE(mode):o}): "
            "chmod 600 it"
        )
    elif want == "certificate" and has_key:
        warnings.append(f"{name} also holds a private key: a certificate file is public")


def audit_box(box: Mapping[str, Any]) -> list[str]:
    """Warnings about a ``[box]`` table: a normally-closed deflation valve keeps a vented
    channel venting after the daemon exits only while the GPIO driver keeps a released
    line's value (the kernel does not promise it); a normally-open one vents regardless."""
    chans = box.get("channel")
    if box.get("deflate_valves") == "normally_closed" and isinstance(chans, list) and chans:
        return [
            "box.deflate_valves = 'normally_closed': a channel being vented keeps venting "
            "after the daemon exits only while the GPIO driver keeps the released line's "
            "value, and closes on a power loss; normally-open deflation valves vent whatever "
            "happens"
        ]
    return []


def check_installation_file(path: str | Path) -> tuple[Any, list[str]]:
    """``(installation, warnings)`` of an installation file, after every check in one pass:
    the file's values (:func:`~softpad.config.parse_installation`), the link's files and the
    wiring. Raises one ConfigError listing every error (``.errors``), parse and files alike."""
    from softpad.config._settings import ConfigError, parse_installation, read_toml

    p = Path(path)
    raw = read_toml(p)
    errors: list[str] = []
    inst = None
    try:
        inst = parse_installation(raw, str(p))
    except ConfigError as parse_error:
        errors.extend(getattr(parse_error, "errors", None) or [str(parse_error)])
    link = raw.get("link", {})
    box = raw.get("box", {})
    file_errors, warnings = audit_link(link if isinstance(link, dict) else {})
    errors.extend(file_errors)
    warnings.extend(audit_box(box if isinstance(box, dict) else {}))
    if errors:
        head = errors[0] if len(errors) == 1 else f"{len(errors)} errors:\n  " + "\n  ".join(errors)
        every = ConfigError(f"installation file {str(p)!r}: {head}")
        every.errors = errors  # type: ignore[attr-defined]
        raise every
    return inst, warnings
