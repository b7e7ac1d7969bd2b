"""Figures of each stage written as PNG files: shared by the command line and the study."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from foilbearing.case import Case

__all__ = [
    "write_identification_figures",
    "write_static_figures",
    "write_structure_figures",
    "write_uncertainty_figures",
]


def write_structure_figures(case: Case, folder: Path) -> list[Path]:
    """Figs. 7 and 8 as PNG files in ``folder``; returns their paths."""
    from foilbearing.io import save_figure
    from foilbearing.output.plots.structure import plot_preloads, plot_stiffness_function

    paths: list[Path] = []
    if case.actuators is not None and case.foil is not None:
        paths.append(
            save_figure(plot_stiffness_function(case), folder / "fig07_stiffness_function.png")
        )
        paths.append(save_figure(plot_preloads(case), folder / "fig08_preloads.png"))
    return paths


def write_identification_figures(
    result: Any,
    folder: Path,
    names: tuple[str, str] = ("fig05b_stack_displacement.png", "fig06_stack_stiffness.png"),
) -> list[Path]:
    """Figs. 5b and 6b-c as PNG files in ``folder`` (``names``: the no-load figure's and
    the stiffness figure's file names)."""
    from foilbearing.io import save_figure
    from foilbearing.output.plots.identification import plot_no_load, plot_stiffness

    return [
        save_figure(plot_no_load(result.no_load_data, result.no_load), folder / names[0]),
        save_figure(plot_stiffness(result.stiffness_data, result.stiffness), folder / names[1]),
    ]


def write_static_figures(ds: Any, folder: Path) -> list[Path]:
    """Figs. 9-12 from a static sweep dataset, as PNG files in ``folder``."""
    from foilbearing.io import save_figure
    from foilbearing.output.plots import static as sp

    speed = 50.0 if 50.0 in ds.speed.values else float(ds.speed.values[len(ds.speed) // 2])
    return [
        save_figure(sp.plot_midplane(ds, speed), folder / "fig09_midplane.png"),
        save_figure(sp.plot_actuator_pressure(ds), folder / "fig10_actuator_pressure.png"),
        save_figure(sp.plot_preload(ds), folder / "fig11_preload.png"),
        save_figure(sp.plot_eccentricity(ds), folder / "fig12_eccentricity.png"),
    ]


def write_uncertainty_figures(ds: Any, folder: Path) -> list[Path]:
    """The uncertainty bands and indices (a ``foilbearing uncertainty`` dataset) as PNG files.

    The paper's points are drawn on the bands only when the sample's case is the
    built-in one (the paper's C-GFB).
    """
    from foilbearing.case import is_default_case_file
    from foilbearing.io import save_figure
    from foilbearing.output.plots.uncertainty import plot_bands, plot_indices
    from foilbearing.paper import PAPER

    paper = PAPER if is_default_case_file(ds.attrs.get("case_file")) else None
    return [
        save_figure(plot_bands(ds, paper), folder / "uncertainty_bands.png"),
        save_figure(plot_indices(ds), folder / "uncertainty_indices.png"),
    ]
