"""What the user reads: figures, summaries and the HTML report.

- ``summary``: the inputs and derived quantities of a case, in engineering units.
- ``figures``: writes the figures of each analysis (PNG), atomically.
- ``result``: a study's summary, folder and figures by section, as the report reads them.
- ``report``: the HTML report that sets the results beside the paper's.
- ``plots``: the figures themselves (matplotlib, imported lazily).
"""
