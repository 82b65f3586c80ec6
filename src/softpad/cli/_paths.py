"""Output paths of the ``softpad`` command: checked before the work, written atomically."""

from __future__ import annotations

import contextlib
import os
import tempfile
from collections.abc import Iterator
from pathlib import Path

from softpad.errors import InputError


def check_output(
    path: str | os.PathLike[str] | None,
    flag: str,
    *,
    force: bool = False,
    suffix: str | tuple[str, ...] | None = None,
) -> Path | None:
    """Check an output file before any work starts; return it as a Path (None stays None).

    The folder must exist and be writable, the name must end in ``suffix`` (when given) and
    the file must not exist unless ``force``. Raises :class:`InputError` naming ``flag``.
    """
    if path is None:
        return None
    text = os.fspath(path)
    if not text.strip():
        raise InputError(f"{flag} needs a file name, got an empty value")
    p = Path(text)
    suffixes = (suffix,) if isinstance(suffix, str) else suffix
    if suffixes and p.suffix.lower() not in suffixes:
        raise InputError(f"{flag} must name a {' or '.join(suffixes)} file, got {text!r}")
    if p.is_dir():
        raise InputError(f"{flag} {text!r} is a folder; give a file name")
    _check_folder(p.parent, flag, text)
    if (p.exists() or p.is_symlink()) and not force:
        raise InputError(f"{flag} {text!r} exists; add --force to overwrite it")
    return p


def check_output_dir(path: str | os.PathLike[str], flag: str, *, force: bool = False) -> Path:
    """Check an output folder: its parent writable, itself absent, empty, or ``force`` given."""
    text = os.fspath(path)
    if not text.strip():
        raise InputError(f"{flag} needs a folder name, got an empty value")
    p = Path(text)
    if p.exists() and not p.is_dir():
        raise InputError(f"{flag} {text!r} is a file, not a folder")
    if p.is_dir():
        _check_folder(p, flag, text)
        if any(p.iterdir()) and not force:
            raise InputError(f"{flag} {text!r} is not empty; add --force to write into it")
    else:
        _check_folder(p.parent, flag, text)
    return p


def _check_folder(folder: Path, flag: str, text: str) -> None:
    folder = folder if str(folder) else Path(".")
    if not folder.is_dir():
        raise InputError(f"{flag} {text!r}: folder {str(folder)!r} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(f"{flag} {text!r}: folder {str(folder)!r} is not writable")
    # root passes os.access everywhere; a read-only file system or /proc only shows on a try
    try:
        with tempfile.NamedTemporaryFile(dir=folder, prefix=".softpad-probe-"):
            pass
    except OSError as exc:
        raise InputError(
            f"{flag} {text!r}: cannot write in folder {str(folder)!r} ({exc.strerror})"
        ) from None


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike[str]) -> Iterator[Path]:
    """Yield a temporary path next to ``path`` (same suffix); on success rename it onto ``path``.

    A crash or an error leaves ``path`` as it was (absent or the old file), never half written.
    """
    target = Path(path)
    fd, tmp = tempfile.mkstemp(
        prefix=f".{target.stem}.", suffix=f".tmp{target.suffix}", dir=target.parent or "."
    )
    os.close(fd)
    umask = os.umask(0)
    os.umask(umask)
    os.chmod(tmp, 0o666 & ~umask)  # the permissions a plain open() would give
    tmp_path = Path(tmp)
    try:
        yield tmp_path
        os.replace(tmp_path, target)
    finally:
        with contextlib.suppress(FileNotFoundError):
            tmp_path.unlink()


def write_text_atomic(path: str | os.PathLike[str], text: str) -> Path:
    """Write ``text`` to ``path`` atomically (temporary file, then rename)."""
    with atomic_path(path) as tmp:
        tmp.write_text(text)
    return Path(path)
