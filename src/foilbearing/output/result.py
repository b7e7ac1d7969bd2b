"""What a study hands its report: the summary, the folder and the figures by section.

``foilbearing study`` builds a :class:`StudyResult` as it finishes and renders the
report from it, so the page needs no second reading of the folder to learn which
figure belongs to which section. The figure record is kept in ``summary.json``
under ``"figures"`` (file names by section, in the order written), so
:meth:`StudyResult.load` gives back the same result from the folder. Folders
written before the record existed are read as the report always read them: each
section's own ``"figures"`` list, and for the orbit section the ``orbit_*.png``
files of the folder.
"""

from __future__ import annotations

import json
import re
from collections.abc import Iterable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from foilbearing.errors import InputError

__all__ = ["FIGURE_RECORD_KEY", "StudyResult", "orbit_figure_order"]


#: Top-level key of ``summary.json`` that holds the figure record.
FIGURE_RECORD_KEY = "figures"


#: File stem of a speed-up's figure, ``orbit_<volts>V_<kind>``, as
#: :func:`foilbearing.orbit.analysis.write_orbit_figures` names it for a label ``<volts>V``.
#: The study's labels now carry the imbalance too (``orbit_0V_8.5gmm_transient``), which
#: this does not match: those figures sort, and are captioned, by file name.
_ORBIT_FIG = re.compile(r"orbit_(?P<v>[0-9.]+)V_(?P<kind>transient|waterfall3d|waterfall|orbits)")


_ORBIT_KINDS = ("transient", "waterfall", "waterfall3d", "orbits")


def orbit_figure_order(path: Path) -> tuple[float, int, str]:
    """Sort key of the speed-ups' figures in the report: voltage, kind, then file name.

    Parameters
    ----------
    path
        A figure file; only its name counts.

    Returns
    -------
    tuple
        Final voltage (V; infinite for a name without one), the figure's kind in
        the order they are written, the file name.
    """
    m = _ORBIT_FIG.fullmatch(path.stem)
    if m is None:
        return (float("inf"), 0, path.name)
    return (float(m["v"]), _ORBIT_KINDS.index(m["kind"]), path.name)


@dataclass(frozen=True)
class StudyResult:
    """A finished (or interrupted) study: its numbers, its folder, its figures.

    Attributes
    ----------
    summary
        The headline numbers of every stage (``summary.json``), unit-named keys.
    out_dir
        The output folder; the figures are read from it by file name.
    figures
        The PNG files each stage wrote, by the stage's key in ``summary`` (for
        example ``"structure"``, ``"orbits"``), in the order the report shows them.
    """

    summary: dict[str, Any]
    out_dir: Path
    figures: Mapping[str, tuple[Path, ...]] = field(default_factory=dict)

    def figure_record(self) -> dict[str, list[str]]:
        """The figure record as ``summary.json`` keeps it: file names by section.

        Returns
        -------
        dict
            Section key to the figures' file names (relative to ``out_dir``).
        """
        return {key: [p.name for p in paths] for key, paths in self.figures.items()}

    @classmethod
    def from_stages(
        cls,
        summary: dict[str, Any],
        out_dir: Path,
        extra: Mapping[str, Iterable[Path]] | None = None,
    ) -> StudyResult:
        """The result of a study from its stages' own ``"figures"`` lists.

        Parameters
        ----------
        summary
            The study's summary: each stage's dict lists the figures it wrote.
        out_dir
            The output folder.
        extra
            Figures a stage wrote beyond its own list, by stage key: they follow it.

        Returns
        -------
        StudyResult
            With every section that wrote a figure in ``figures``.
        """
        extra = extra or {}
        figures: dict[str, tuple[Path, ...]] = {}
        for key, data in summary.items():
            listed = data.get("figures") if isinstance(data, dict) else None
            paths = [Path(str(p)) for p in listed] if isinstance(listed, list) else []
            paths += [Path(p) for p in extra.get(key, ())]
            if paths:
                figures[key] = tuple(paths)
        return cls(summary, Path(out_dir), figures)

    @classmethod
    def from_summary(cls, summary: dict[str, Any], out_dir: Path) -> StudyResult:
        """The result of a study folder from its summary, as ``summary.json`` has it.

        Parameters
        ----------
        summary
            The study's summary. With a figure record (``"figures"`` at the top
            level) that record is the result's; without one (folders written before
            it, or by an interrupted study), each section's own ``"figures"`` list
            and, for ``"orbits"``, the folder's ``orbit_*.png`` files in
            :func:`orbit_figure_order`.
        out_dir
            The study folder (it may have moved since: figures go by file name).

        Returns
        -------
        StudyResult
            The figures as paths in ``out_dir``.
        """
        out_dir = Path(out_dir)
        record = summary.get(FIGURE_RECORD_KEY)
        if not isinstance(record, dict):
            orbits = summary.get("orbits")
            runs = sorted(out_dir.glob("orbit_*.png"), key=orbit_figure_order)
            extra = {"orbits": runs} if isinstance(orbits, dict) and orbits else None
            record = cls.from_stages(summary, out_dir, extra).figure_record()
        figures = {
            str(key): tuple(out_dir / Path(str(name)).name for name in names)
            for key, names in record.items()
            if isinstance(names, list) and names
        }
        return cls(summary, out_dir, figures)

    @classmethod
    def load(cls, out_dir: str | Path) -> StudyResult:
        """Read a study folder written by ``foilbearing study``.

        Parameters
        ----------
        out_dir
            The folder with ``summary.json`` and the PNG figures.

        Returns
        -------
        StudyResult
            See :meth:`from_summary`.

        Raises
        ------
        InputError
            If ``summary.json`` is missing or not a JSON object.
        """
        out_dir = Path(out_dir)
        path = out_dir / "summary.json"
        if not path.is_file():
            raise InputError(
                "no summary.json; run `foilbearing study --out DIR`", source=str(out_dir)
            )
        try:
            summary = json.loads(path.read_text(encoding="utf-8"))
        except json.JSONDecodeError as exc:
            raise InputError(f"not valid JSON ({exc})", source=str(path)) from exc
        if not isinstance(summary, dict):
            raise InputError("expected a JSON object at the top level", source=str(path))
        return cls.from_summary(summary, out_dir)
