"""Test oracles: independent forms of the numerics that the tests check production against.
Tests and benchmarks import this package; no module of foilbearing outside it does
(``tests/test_architecture.py`` checks it).

===============  ===============================================================================
module           responsibility
===============  ===============================================================================
``twins``        the plain NumPy twin of each compiled kernel of ``reynolds/_kernels`` (those of
                 the transient Newton are the production SciPy fallback,
                 ``reynolds/fallback.py``, under the twins' names)
``block_twins``  the twins of the block cyclic factorisation and solve
``ivp_orbit``    the single bearing's orbit on ``scipy.integrate.solve_ivp`` (projected
                 lift-off), the reference of the BDF stepper
``ivp_rotor``    the nonlinear rotor on ``solve_ivp``, the reference of the rotor's stepper
===============  ===============================================================================
"""
