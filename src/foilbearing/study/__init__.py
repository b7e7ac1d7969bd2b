"""Studies: the paper's full analysis and the same analysis of any bearing.

===============  ===============================================================================
module           responsibility
===============  ===============================================================================
``paper``        the paper's analysis end to end on one case (``foilbearing study``)
``plan``         the study's plan for any bearing, from the case and its ``[study]`` table
``bearing``      the stages of the study of any bearing other than the paper's C-GFB
``static``       the static sweep of the paper's voltages and speeds (Figs. 9-12)
``orbits``       the paper's speed-ups (Figs. 13-15) as study stages
``queue``        one pool of speed-ups for the whole study
``runs``         one speed-up of the orbit stages, as a worker process runs it
``schedule``     the voltage schedule as a study stage, verified in speed-ups
``bifurcation``  the limit-cycle branches as a study stage
``converged``    the published onsets (×2 grid, κ 0.02) with their errors
``design``       what the stack's stiffness buys (150 V), its onsets with their errors
``envelopes``    the uncertainty envelopes of what the paper leaves open, as a study stage
``rotor``        the study of a rotor on two foil bearings (``foilbearing study ROTOR.toml``)
===============  ===============================================================================
"""
