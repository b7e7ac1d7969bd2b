"""A sphinx-gallery image scraper for the figures that foilbearing's results draw.

``StaticResult.plot()`` and the other ``.plot()`` methods return a
:class:`matplotlib.figure.Figure` made without pyplot, which sphinx-gallery's own
scraper (it reads ``pyplot.get_fignums()``) does not see. This one saves every Figure
a block left in the script's variables that no earlier block saved, in the order the
variables were bound; pyplot's figures are left to the standard scraper.
"""

from __future__ import annotations

from pathlib import PurePosixPath
from typing import Any

#: The figures already on the page, per script (kept alive, so that an id is not reused).
_SHOWN: dict[str, list[Any]] = {}


def result_figures(block: Any, block_vars: dict[str, Any], gallery_conf: dict[str, Any]) -> str:
    """Save the new Figures among the script's variables; their reStructuredText."""
    from matplotlib.figure import Figure
    from sphinx_gallery.scrapers import figure_rst

    shown = _SHOWN.setdefault(block_vars["src_file"], [])
    new = [
        v
        for v in block_vars["example_globals"].values()
        if isinstance(v, Figure)
        and v.canvas.manager is None  # pyplot's: the standard scraper's
        and not any(v is s for s in shown)
    ]
    paths = []
    for fig, path in zip(new, block_vars["image_path_iterator"], strict=False):
        fig.savefig(path, dpi=100)
        shown.append(fig)
        paths.append(PurePosixPath(path))
    return figure_rst(paths, gallery_conf["src_dir"])
