"""What the user reads: figures, summaries and the HTML report.

- ``summary``: the inputs and derived quantities of a case, in engineering units.
- ``figures``: writes the figures of each analysis (PNG), atomically.
- ``report``: the HTML report that sets the results beside the paper's.
- ``plots``: the figures themselves (matplotlib, imported lazily).
"""
