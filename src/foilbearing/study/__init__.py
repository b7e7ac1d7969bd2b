"""Studies: the paper's full analysis and the same analysis of any bearing.

- ``paper``: :func:`~foilbearing.study.paper.run_study`, the command ``foilbearing study``.
- ``plan``: the ``[study]`` table of a case file (speeds, voltages, orbits, references).
- ``bearing``: the stages of a study of any bearing.
- ``static``: the static sweep of the paper's voltages and speeds (Figs. 10-12).
- ``orbits``: the paper's speed-ups (Figs. 13-15) as study stages.
- ``schedule``: the voltage schedule as a study stage.
"""
