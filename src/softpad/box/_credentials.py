"""The link's own authentication: zenoh user/password and mutual TLS, from the installation file
(``[link]``) or the environment, for the daemon (listener) and for ``zenoh://`` clients.

Both sides read the same keys of ``[link]``, each for its own end:

=====================  ===========================================  ===========================
key                    daemon (``softpad box serve``)               client (``zenoh://``)
=====================  ===========================================  ===========================
``user``               (with ``password_file``: user/password on)   the user it logs in as
``password_file``      zenoh's dictionary: ``user:password`` lines  its ``user:password`` line
                                                                    (or one line: the password)
``tls_certificate``    its certificate (``tls/`` endpoints)         its client certificate
``tls_private_key``    that certificate's key                       that certificate's key
``tls_root_ca``        the CA that signed the *clients'* certificates  the CA that signed the
                       (set: client certificates required, mTLS)    daemon's certificate; set:
                                                                    the client connects ``tls/``
=====================  ===========================================  ===========================

A client takes its installation file from the URL option ``config=FILE`` or the environment
variable ``SOFTPAD_BOX_CONFIG``; ``SOFTPAD_BOX_USER`` and ``SOFTPAD_BOX_PASSWORD`` override the
user and password. Credentials are never part of a URL (a URL is logged and recorded): a
``zenoh://USER:PASSWORD@HOST`` is refused.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from softpad.config import ConfigError

#: Environment variables a ``zenoh://`` client reads.
ENV_CONFIG, ENV_USER, ENV_PASSWORD = (
    "SOFTPAD_BOX_CONFIG",
    "SOFTPAD_BOX_USER",
    "SOFTPAD_BOX_PASSWORD",
)


def daemon_auth(link: Any) -> dict[str, Any]:
    """:func:`~softpad.box._link.session_config` keywords of the daemon for ``link``
    (:class:`softpad.config.LinkSettings`).

    Raises
    ------
    ConfigError
        A password file that is missing, empty or without ``user:password`` lines, a
        certificate or key that is not one (:func:`softpad.config.audit_link`).
    """
    import dataclasses

    from softpad.config import audit_link

    errors, _ = audit_link(dataclasses.asdict(link))
    if errors:  # an empty password file would turn authentication off (issue 49)
        exc = ConfigError("refusing to serve: " + "; ".join(errors))
        exc.errors = errors  # type: ignore[attr-defined]
        raise exc
    out: dict[str, Any] = {}
    if link.password_file is not None:
        out["dictionary_file"] = link.password_file
    if link.tls_certificate is not None:
        tls: dict[str, Any] = {
            "listen_certificate": link.tls_certificate,
            "listen_private_key": link.tls_private_key,
        }
        if link.tls_root_ca:  # verify every client's certificate against it
            tls.update(root_ca_certificate=link.tls_root_ca, enable_mtls=True)
        out["tls"] = tls
    return out


def client_auth(
    link: Any | None, env: Mapping[str, str] | None = None
) -> tuple[str, dict[str, Any]]:
    """``(protocol, session_config keywords)`` of a ``zenoh://`` client: ``tls`` when its
    file names a root CA, else ``tcp``; user/password from the file or the environment."""
    env = os.environ if env is None else env
    out: dict[str, Any] = {}
    user = env.get(ENV_USER) or (link.user if link is not None else None)
    password = env.get(ENV_PASSWORD)
    if user and password is None and link is not None and link.password_file:
        password = _password_from(Path(link.password_file), user)
    if user and password is not None:
        out.update(user=user, password=password)
    elif user:
        raise ConfigError(
            f"zenoh user {user!r} has no password: set {ENV_PASSWORD} or link.password_file"
        )
    proto = "tcp"
    if link is not None and link.tls_root_ca:
        tls: dict[str, Any] = {"root_ca_certificate": link.tls_root_ca}
        if link.tls_certificate:
            tls.update(
                connect_certificate=link.tls_certificate,
                connect_private_key=link.tls_private_key,
                enable_mtls=True,
            )
        out["tls"] = tls
        proto = "tls"
    return proto, out


def _password_from(path: Path, user: str) -> str:
    """The password of ``user`` in ``path`` (``user:password`` lines, or one bare line)."""
    try:
        lines = [ln.strip() for ln in path.read_text().splitlines() if ln.strip()]
    except OSError as exc:
        raise ConfigError(f"link.password_file {str(path)!r} cannot be read: {exc}") from None
    for ln in lines:
        name, sep, pw = ln.partition(":")
        if sep and name == user:
            return pw
    if len(lines) == 1 and ":" not in lines[0]:
        return lines[0]
    raise ConfigError(f"link.password_file {str(path)!r} has no line for user {user!r}")


def client_link(options: Mapping[str, str], env: Mapping[str, str] | None = None) -> Any | None:
    """The ``[link]`` settings a client uses: the file of the URL option ``config`` or of
    ``SOFTPAD_BOX_CONFIG``; None when neither is given."""
    env = os.environ if env is None else env
    path = options.get("config") or env.get(ENV_CONFIG)
    if not path:
        return None
    from softpad.config import load_installation

    return load_installation(path).link
