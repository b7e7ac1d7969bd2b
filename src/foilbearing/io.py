"""Atomic writes: a result is either there whole or not at all.

Everything the package writes goes to a temporary file in the target's
directory first and is then moved over the target with ``os.replace``. An
output a run will write can be reserved first (:func:`reserve`): a lock file
beside it, created with ``O_EXCL`` and held with ``flock`` for the run, so that
two runs cannot write one output and a folder that cannot be written is found
before any work starts.
"""

from __future__ import annotations

import errno
import fcntl
import os
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

__all__ = [
    "OutputBusy",
    "Reservation",
    "atomic_path",
    "lock_path",
    "read_toml",
    "reserve",
    "save_figure",
    "write_text",
    "write_with",
]


@contextmanager
def atomic_path(target: str | Path) -> Iterator[Path]:
    """Yield a temporary path beside ``target``; on success it replaces ``target``."""
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{target.name}.", suffix=".part", dir=target.parent)
    os.close(fd)
    try:
        yield Path(tmp)
        umask = os.umask(0)
        os.umask(umask)
        os.chmod(tmp, 0o666 & ~umask)  # mkstemp makes 0600; give the file the usual mode
        os.replace(tmp, target)
    except BaseException:
        Path(tmp).unlink(missing_ok=True)
        raise


def write_text(target: str | Path, text: str) -> Path:
    """Write ``text`` to ``target`` atomically (UTF-8)."""
    with atomic_path(target) as tmp:
        tmp.write_text(text, encoding="utf-8")
    return Path(target)


def save_figure(fig: Any, target: str | Path, dpi: int = 130) -> Path:
    """Save a matplotlib figure atomically as PNG.

    The package's figures are :class:`matplotlib.figure.Figure` objects built
    without pyplot, so no backend is selected and nothing needs closing: the
    figure is freed with its last reference.
    """
    with atomic_path(target) as tmp:
        fig.savefig(tmp, format="png", dpi=dpi)
    return Path(target)


def write_with(target: str | Path, writer: Callable[[Path], object]) -> Path:
    """Call ``writer(tmp_path)`` and move the result over ``target`` atomically."""
    with atomic_path(target) as tmp:
        writer(tmp)
    return Path(target)


def read_toml(path: Path, what: str) -> dict[str, Any]:
    """The tables of TOML file ``path``; ``what`` names it in errors ("sweep file").

    Raises
    ------
    InputError
        The file is missing, unreadable or not valid TOML (one line, naming it).
    """
    import tomllib

    from foilbearing.errors import InputError

    try:
        return tomllib.loads(Path(path).read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise InputError(f"{what} not found", source=str(path)) from None
    except (OSError, UnicodeDecodeError, tomllib.TOMLDecodeError) as exc:
        raise InputError(f"cannot read the {what}: {exc}", source=str(path)) from None


class OutputBusy(Exception):
    """Another live process holds the reservation of an output (see :func:`reserve`)."""

    def __init__(self, target: Path, lock: Path, holder: str) -> None:
        super().__init__(f"{target} is being written by another run ({holder}; lock {lock})")
        self.target, self.lock, self.holder = target, lock, holder


def lock_path(target: str | Path) -> Path:
    """The lock file that reserves ``target``: ``.NAME.lock`` beside it."""
    target = Path(target)
    return target.with_name(f".{target.name}.lock")


class Reservation:
    """An output reserved by this process until :meth:`release` (or the process ends).

    Holds the lock file open under an exclusive ``flock``: the kernel drops it when
    the process dies, so a lock left behind by a killed run is taken over by the next
    one, while a live holder is refused.
    """

    def __init__(self, target: Path, lock: Path, fd: int) -> None:
        self.target, self.lock, self._fd = target, lock, fd

    def release(self) -> None:
        """Remove the lock file and drop the lock (idempotent)."""
        if self._fd < 0:
            return
        try:
            if os.stat(self.lock).st_ino == os.fstat(self._fd).st_ino:
                self.lock.unlink()
        except OSError:
            pass  # gone already, or a read-only folder now: the flock still ends below
        os.close(self._fd)
        self._fd = -1


def reserve(target: str | Path) -> Reservation:
    """Reserve ``target`` for this process: create its lock file, take an exclusive lock.

    The parent folder is made if missing. A lock file left by a dead process is taken
    over; one held by a live process raises :class:`OutputBusy`.

    Raises
    ------
    OutputBusy
        Another live process holds ``target``'s lock.
    OSError
        The folder cannot be made or written (read-only, no permission, not a folder).
    """
    target = Path(target)
    lock = lock_path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    for _ in range(5):  # a holder that releases between our open and our lock: try again
        try:
            fd = os.open(lock, os.O_CREAT | os.O_EXCL | os.O_RDWR, 0o644)
        except FileExistsError:
            try:
                fd = os.open(lock, os.O_RDWR)
            except FileNotFoundError:
                continue
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except OSError as exc:
            holder = os.pread(fd, 200, 0).decode("utf-8", "replace").strip() or "unknown"
            os.close(fd)
            if exc.errno in (errno.EWOULDBLOCK, errno.EAGAIN, errno.EACCES):
                raise OutputBusy(target, lock, holder) from None
            raise
        try:
            same = os.stat(lock).st_ino == os.fstat(fd).st_ino
        except FileNotFoundError:
            same = False
        if not same:  # removed by its holder after we opened it: start again
            os.close(fd)
            continue
        os.ftruncate(fd, 0)
        try:
            os.pwrite(fd, f"pid {os.getpid()} on {os.uname().nodename}\n".encode(), 0)
        except OSError:
            pass  # a full disk: the lock holds without its note
        return Reservation(target, lock, fd)
    raise OutputBusy(target, lock, "its lock file keeps changing")
