"""Keep numba's on-disk caches of the kernels true to every source they inline.

numba checks only a kernel's own source file before reusing its cache: a kernel that
calls or inlines a function of another file (``newton.py`` the BDF rows of ``bdf.py``,
``flux.py`` and ``bdf.py`` the lift-off row of ``foilbearing/laws/lift_off.py``) kept
running the old callee after that file alone changed (measured on 2026-12-03;
docs/numerics.md §3). So, on import, :func:`drop_stale_caches` hashes the sources of
every kernel module and of the compiled laws, compares the digest with the one stored
beside the caches, and when they differ deletes this package's cached kernels, which
numba then compiles afresh (about a minute). A fresh clone has no cache and no digest.
"""

from __future__ import annotations

import hashlib
from collections.abc import Iterable
from pathlib import Path
from types import ModuleType

__all__ = ["drop_stale_caches"]

#: The file beside the caches that holds the digest of the sources they were built from.
DIGEST_NAME = "kernel-sources.sha256"


def sources_digest(files: Iterable[Path]) -> str:
    """SHA-256 of the files' names and contents, in sorted order."""
    h = hashlib.sha256()
    for f in sorted(files):
        h.update(f.name.encode())
        h.update(f.read_bytes())
    return h.hexdigest()


def drop_stale_caches(kernels: Iterable[ModuleType], laws: Iterable[ModuleType]) -> int:
    """Delete the cached kernels of ``kernels`` if any of their or the ``laws``' sources changed.

    Parameters
    ----------
    kernels
        The kernel modules, all in one directory (their caches share one cache path).
    laws
        The modules whose compiled functions the kernels call or inline.

    Returns
    -------
    int
        The number of cache files deleted (0 when the caches are current or the cache
        directory cannot be written, in which case numba cannot cache there either).
    """
    kernels = list(kernels)
    files = [Path(str(m.__file__)) for m in (*kernels, *laws)]
    digest = sources_digest(files)
    cache_dir = _cache_dir(kernels[0])
    stamp = cache_dir / DIGEST_NAME
    try:
        if stamp.read_text().strip() == digest:
            return 0
    except OSError:
        pass
    deleted = 0
    for m in kernels:
        stem = Path(str(m.__file__)).stem
        for pattern in (f"{stem}.*.nbi", f"{stem}.*.nbc"):
            for f in cache_dir.glob(pattern):
                try:
                    f.unlink()
                    deleted += 1
                except OSError:
                    pass
    try:
        cache_dir.mkdir(parents=True, exist_ok=True)
        stamp.write_text(digest + "\n")
    except OSError:
        pass
    return deleted


def _cache_dir(module: ModuleType) -> Path:
    """Where numba caches the kernels of ``module`` (the first cached dispatcher's path)."""
    for value in vars(module).values():
        cache = getattr(value, "_cache", None)
        path = getattr(cache, "_cache_path", None)
        if isinstance(path, str) and getattr(value, "__module__", None) == module.__name__:
            return Path(path)
    return Path(str(module.__file__)).parent / "__pycache__"
