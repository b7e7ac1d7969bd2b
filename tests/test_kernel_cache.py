"""A kernel's on-disk numba cache is dropped when a law it inlines changes (docs/numerics.md §3).

numba itself checks only the kernel's own file; ``reynolds/_kernels/_cache.py`` adds the
sources of the laws the kernels inline. Checked on stand-in modules in a temporary
directory (no numba compilation).
"""

from __future__ import annotations

from pathlib import Path
from types import ModuleType

from foilbearing.reynolds._kernels._cache import DIGEST_NAME, drop_stale_caches


def _module(path: Path, text: str) -> ModuleType:
    path.write_text(text)
    m = ModuleType(path.stem)
    m.__file__ = str(path)
    return m


def test_a_changed_law_drops_the_kernels_caches_and_only_then(tmp_path: Path) -> None:
    kernels_dir, laws_dir = tmp_path / "_kernels", tmp_path / "laws"
    kernels_dir.mkdir()
    laws_dir.mkdir()
    flux = _module(kernels_dir / "flux.py", "def rows(): pass\n")
    law = _module(laws_dir / "lift_off.py", "def smoothed_edge(): return 4.0\n")
    cache = kernels_dir / "__pycache__"
    cache.mkdir()

    def cached() -> list[Path]:
        for name in ("flux.rows-1.py313.nbi", "flux.rows-1.py313.1.nbc"):
            (cache / name).write_text("x")
        (cache / "other.f-1.py313.nbi").write_text("x")  # another module's: kept
        return sorted(cache.glob("flux.*"))

    cached()
    assert drop_stale_caches([flux], [law]) == 2  # no digest yet: built from unknown sources
    assert (cache / DIGEST_NAME).exists() and (cache / "other.f-1.py313.nbi").exists()
    cached()
    assert drop_stale_caches([flux], [law]) == 0  # nothing changed: the caches stay
    assert len(sorted(cache.glob("flux.*"))) == 2
    Path(str(law.__file__)).write_text("def smoothed_edge(): return 40.0\n")
    assert drop_stale_caches([flux], [law]) == 2  # the law alone changed
    assert not list(cache.glob("flux.*"))
