"""
A rotor on two bearings with ROSS
=================================

A flexible rotor, a 20 mm shaft carrying two disks between two 40 mm journals, runs on
two of the paper's C-GFBs at 150 V (``examples/rotor_two_disk.toml``, the user
guide's rotor format). Each bearing is its own case; the rotor file says at which node
it sits. The rotor's weight is shared between the bearings by statics, each bearing's
stiffness and damping are computed at its own load, and ROSS finds the rotor's modes
with each mode's coefficients taken at its own whirl frequency (``matched_whirl``).
Needs the ``ross`` extra (``pip install -c constraints.txt '.[ross]'``).

This page runs the bearings on a coarse 48 × 6 grid (the built-in one is 96 × 12),
so that it builds in well under a minute; on the built-in grid the onset lies about
2 % higher. From the command line, on the built-in grid::

    $ foilbearing rotor examples/rotor_two_disk.toml --plot rotor_plots

``--plot`` writes the Campbell diagram, the log decrements against speed and the
mode shapes; ``--orbit 30000rpm:60000rpm:500rad/s**2`` integrates both bearings'
films with the rotor through a speed-up instead.
"""

# %%
# The rotor file
# --------------
# :func:`foilbearing.rotor.load_rotor` reads the shaft, the disks and the bearings;
# :meth:`~foilbearing.rotor.RotorCase.loaded_cases` gives each bearing's case at the
# load it carries. Here every bearing's case also gets the page's coarse grid.

import dataclasses
from pathlib import Path

import foilbearing as fb
from foilbearing.case.model import Grid
from foilbearing.output.plots.rotor import plot_campbell
from foilbearing.rotor import load_rotor, rotor_onset


def repository_file(name: str) -> Path:
    """A file of the repository, wherever the page is built from."""
    here = Path.cwd()
    for folder in (here, *here.parents):
        if (folder / name).is_file():
            return folder / name
    raise FileNotFoundError(name)


rotor = load_rotor(repository_file("examples/rotor_two_disk.toml"))
coarse = Grid(n_theta=48, n_z=6)  # see above
rotor = dataclasses.replace(
    rotor,
    bearings=tuple(
        dataclasses.replace(site, case=dataclasses.replace(site.case, grid=coarse))
        for site in rotor.bearings
    ),
)
for site, case in zip(rotor.bearings, rotor.loaded_cases(), strict=True):
    print(f"{site.label} (node {site.node}): carries {case.operation.load:.2f} N")

# %%
# The onset and the Campbell diagram
# ----------------------------------
# :func:`foilbearing.rotor.rotor_onset` tabulates each bearing's coefficients over
# the speeds given × whirl frequencies, finds the rotor's four lowest modes at each
# speed, and refines the speed where the least stable one's log decrement turns
# negative. The rotor whirls there at a fraction of its running speed, as a rotor on
# gas bearings does.

speeds = [k * 1e3 * fb.RPM for k in range(30, 61, 5)]
onset, whirl_hz, modes = rotor_onset(rotor, speeds)
speed_hz = onset / fb.RPM / 60.0
print(f"onset {onset / fb.RPM:.0f} rpm, whirl {whirl_hz:.1f} Hz")
print(f"whirl ratio {whirl_hz / speed_hz:.3f} (whirl frequency / running speed)")
fig = plot_campbell(modes, onset)

# %%
# Each marker is a mode at a speed, coloured by its log decrement (blue: damped, red:
# growing); the dashed line is the running speed, 1X. The rotor's unbalance response
# and its mode shapes come from :func:`foilbearing.rotor.unbalance_response` and
# :func:`foilbearing.rotor.mode_shapes`; ``foilbearing study
# examples/rotor_two_disk.toml`` puts all of it, with a nonlinear speed-up through the
# onset, in one ``report.html``.
