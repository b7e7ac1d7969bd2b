"""
A rotor on two bearings with ROSS
=================================

*This page is not run when the site is built: ROSS takes about half a minute to load
and to compute the modes. The numbers quoted were measured with the code below.*

A flexible rotor, a 20 mm shaft carrying two disks between two 40 mm journals, runs on
two of the paper's C-GFBs at 150 V (``examples/rotor_two_disk.toml``, the user
guide's rotor format). Each bearing is its own case; the rotor file says at which node
it sits. The rotor's weight is shared between the bearings by statics, each bearing's
stiffness and damping are computed at its own load, and ROSS finds the rotor's modes
with each mode's coefficients taken at its own whirl frequency (``matched_whirl``).
Needs the ``ross`` extra (``pip install -c constraints.txt '.[ross]'``).

From the command line::

    $ foilbearing rotor examples/rotor_two_disk.toml --plot rotor_plots
      bearing A (node 0): carries 10.81 N
      bearing B (node 6): carries 9.63 N
      onset 46695 rpm, whirl 206.2 Hz

``--plot`` writes the Campbell diagram, the log decrements against speed and the
mode shapes; ``--orbit 30000rpm:60000rpm:500rad/s**2`` integrates both bearings'
films with the rotor through a speed-up instead.
"""

# %%
# From Python: the onset and the Campbell diagram
# -----------------------------------------------
# :func:`foilbearing.rotor.rotor_onset` scans the speeds given and refines the onset;
# it gave 46693 rpm at a whirl of 206.1 Hz, the command line's result.

import foilbearing as fb
from foilbearing.output.plots.rotor import plot_campbell
from foilbearing.rotor import load_rotor, rotor_onset

rotor = load_rotor("examples/rotor_two_disk.toml")
speeds = [k * 1e3 * fb.RPM for k in range(30, 61, 5)]
onset, whirl_hz, modes = rotor_onset(rotor, speeds)
print(f"onset {onset / fb.RPM:.0f} rpm, whirl {whirl_hz:.1f} Hz")
fig = plot_campbell(modes, onset)
fig.savefig("campbell.png")

# %%
# The rotor's unbalance response and its mode shapes come from
# :func:`foilbearing.rotor.unbalance_response` and :func:`foilbearing.rotor.mode_shapes`;
# ``foilbearing study examples/rotor_two_disk.toml`` puts all of it, with a nonlinear
# speed-up through the onset, in one ``report.html``.
