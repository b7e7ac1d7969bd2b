"""Atomic writes: a result is either there whole or not at all.

Everything the package writes goes to a temporary file in the target's
directory first and is then moved over the target with ``os.replace``.
"""

from __future__ import annotations

import os
import tempfile
from collections.abc import Callable, Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

__all__ = ["atomic_path", "read_toml", "save_figure", "write_text", "write_with"]


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


def write_with(target: str | Path, writer: Callable[[Path], None]) -> Path:
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
