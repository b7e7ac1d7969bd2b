"""
Waterfall of a speed-up through the onset
=========================================

The bump foil bearing of ``examples/bump_foil_bearing.toml`` sped up from 55 to
75 krpm at 1500 rad/s², through its linear onset (about 64 krpm on this grid).
The waterfall shows the synchronous (1X) line and, past the onset, the whirl at about
76 Hz that grows until the film closes. Coarse grid: the orbit on 48 × 4 cells.
"""

import dataclasses
from pathlib import Path

import foilbearing as fb
from foilbearing.case.model import Grid
from foilbearing.output.plots.orbit import plot_waterfall


def repository_file(name: str) -> Path:
    """A file of the repository, wherever the page is built from."""
    for folder in (Path.cwd(), *Path.cwd().parents):
        if (folder / name).is_file():
            return folder / name
    raise FileNotFoundError(name)


case = fb.load_case(repository_file("examples/bump_foil_bearing.toml"))
case = dataclasses.replace(case, grid=Grid(n_theta=48, n_z=6, orbit_n_z=4))
run = fb.simulate(case, fb.linear_ramp("55 krpm", "75 krpm", "1500 rad/s**2"))
analysis = fb.analyse_orbit(run)
head = analysis.headline(run)
print(run.message)
print(
    f"sub-synchronous onset {head['onset_speed_rpm']:.0f} rpm "
    f"at {head['whip_frequency_Hz']:.1f} Hz; contact at {head['divergence_speed_rpm']:.0f} rpm"
)
fig = plot_waterfall(analysis.waterfall, onset_whirl_hz=head["whip_frequency_Hz"])
