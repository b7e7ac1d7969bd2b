"""Figures. Imported lazily: physics modules never import matplotlib; each function returns its Figure.

==================  ============================================================================
module              responsibility
==================  ============================================================================
``structure``       the stiffness function (Fig. 7) and C-GFB against shimmed preloads (Fig. 8)
``identification``  the PZT stack identification: no-load curves (Fig. 5b), stiffness (Figs.
                    6b-c)
``static``          static figures from a static sweep (Figs. 9-12)
``dynamics``        the linear analysis: coefficients against frequency, the stability map
``orbit``           the speed-up orbit: transient, waterfalls, sub-synchronous amplitude, orbits
``bifurcation``     the whirl branch: limit-cycle amplitude against speed, with its stability
``bearing``         the study of any bearing: readouts, preloads, coefficients and log decrement
``schedule``        a voltage schedule: voltages, log decrement and power loss against speed
``rotor``           the rotor: Campbell diagram, unbalance response, mode shapes
``rotor_orbit``     the nonlinear rotor's run: each journal's displacement against time and
                    speed
``uncertainty``     an uncertainty analysis: percentile bands and sensitivity indices
==================  ============================================================================
"""
