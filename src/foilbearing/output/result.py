"""What a study hands its report: the summary, the folder and the figures by section.

``foilbearing study`` builds a :class:`StudyResult` as it finishes and renders the
report from it, so the page needs no second reading of the folder to learn which
figure belongs to which section. The figure record is kept in ``summary.json``
under ``"figures"`` (file names by section, in the order written), so
:meth:`StudyResult.load` gives back the same result from the folder. Folders
written before the record existed are read as the report always read them: each
section's own ``"figures"`` list, and for the orbit section the ``orbit_*.png``
files of the folder. An orbit figure is told by its run's label
(``orbit_<label>_<kind>.png``), which the orbit stage's runs carry.
"""

from __future__ import annotations

import json
from collections.abc import Callable, Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from foilbearing.errors import InputError
from foilbearing.output.display import Summarised, format_value, split_unit

__all__ = [
    "FIGURE_RECORD_KEY",
    "ORBIT_KINDS",
    "StudyResult",
    "orbit_figure_order",
    "orbit_figure_run",
]


#: Top-level key of ``summary.json`` that holds the figure record.
FIGURE_RECORD_KEY = "figures"


#: The figures :func:`foilbearing.orbit.analysis.write_orbit_figures` writes of a run, in order.
ORBIT_KINDS = ("transient", "waterfall", "waterfall3d", "orbits")


def orbit_figure_run(
    name: str, runs: Sequence[Mapping[str, Any]]
) -> tuple[int, Mapping[str, Any], str] | None:
    """The speed-up that an orbit figure ``orbit_<label>_<kind>.png`` shows.

    Parameters
    ----------
    name
        The figure's file name.
    runs
        The orbit stage's runs, as ``summary["orbits"]["runs"]`` holds them (each
        with its ``label``).

    Returns
    -------
    tuple or None
        The run's index in ``runs``, the run, and the figure's kind (one of
        :data:`ORBIT_KINDS`); None if no run's figure has that name.
    """
    stem = Path(name).stem
    for index, run in enumerate(runs):
        label = run.get("label") if isinstance(run, Mapping) else None
        for kind in ORBIT_KINDS:
            if isinstance(label, str) and stem == f"orbit_{label}_{kind}":
                return index, run, kind
    return None


def orbit_figure_order(runs: Sequence[Mapping[str, Any]]) -> Callable[[Path], tuple[int, int, str]]:
    """Sort key of the speed-ups' figures in the report: the runs' order, kind, file name.

    Parameters
    ----------
    runs
        The orbit stage's runs in the protocol's order (see :func:`orbit_figure_run`).

    Returns
    -------
    callable
        Key of a figure path: the index of its run (after all runs for a figure
        of none), its kind in :data:`ORBIT_KINDS`, its file name.
    """

    def key(path: Path) -> tuple[int, int, str]:
        found = orbit_figure_run(path.name, runs)
        if found is None:
            return (len(runs), 0, path.name)
        return (found[0], ORBIT_KINDS.index(found[2]), path.name)

    return key


@dataclass(frozen=True, repr=False)
class StudyResult(Summarised):
    """A finished (or interrupted) study: its numbers, its folder, its figures.

    Printed, it shows one line per stage of ``summary`` (its first few numbers)
    and the folder, an HTML table in a notebook; :meth:`plot` opens a figure.

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

    def _summary(self) -> tuple[str, dict[str, Any], None]:
        rows: dict[str, Any] = {}
        for stage, value in self.summary.items():
            if isinstance(value, Mapping):
                numbers = {k: v for k, v in value.items() if isinstance(v, int | float | str)}
                shown = [(*split_unit(k), format_value(v)) for k, v in list(numbers.items())[:3]]
                rows[stage] = ", ".join(f"{q} {v} {u}".rstrip() for q, u, v in shown)
            else:
                rows[stage] = value
        n_fig = sum(len(p) for p in self.figures.values())
        return f"Study in {self.out_dir} ({n_fig} figures)", dict(list(rows.items())[:16]), None

    def plot(self, name: str | None = None) -> Any:
        """One of the study's figures as a matplotlib Figure (the PNG it wrote, shown
        without axes): ``name`` is its file name, default the first figure.

        Raises
        ------
        InputError
            No figure of that name (the message lists those there are).
        """
        import matplotlib.image as mpimg
        from matplotlib.figure import Figure

        paths = [p for group in self.figures.values() for p in group]
        chosen = [p for p in paths if name is None or p.name == name]
        if not chosen:
            names = ", ".join(p.name for p in paths) or "none"
            raise InputError(f"figure {name!r}: not among this study's figures ({names})")
        image = mpimg.imread(chosen[0])
        height, width = image.shape[:2]
        fig = Figure(figsize=(width / 100, height / 100))
        ax = fig.add_axes((0, 0, 1, 1))
        ax.imshow(image)
        ax.set_axis_off()
        return fig

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
            runs = orbits.get("runs") if isinstance(orbits, dict) else None
            order = orbit_figure_order(runs if isinstance(runs, list) else [])
            found = sorted(out_dir.glob("orbit_*.png"), key=order)
            extra = {"orbits": found} if isinstance(orbits, dict) and orbits else None
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
