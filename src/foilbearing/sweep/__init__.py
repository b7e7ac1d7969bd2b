"""Parameter sweeps, from a laptop to a Dask cluster.

- ``spec``: the sweep file (docs/sweep-format.md), read into a :class:`~foilbearing.sweep.spec.SweepSpec`.
- ``analyses``: what is computed at each point (static, coefficients, stability).
- ``runner``: :func:`~foilbearing.sweep.runner.run_sweep`, each point written as it finishes.
"""
