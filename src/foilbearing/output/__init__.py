"""What the user reads: figures, summaries and the HTML report.

===========  ===================================================================================
module       responsibility
===========  ===================================================================================
``summary``  headline numbers of a case: what ``foilbearing case show`` prints
``display``  a result as a person reads it: a few text lines, or an HTML table in a notebook
``figures``  the figures of each stage written as PNG files, atomically
``result``   what a study hands its report: summary, folder and figures by section
``plots/``   the figures themselves (matplotlib, imported lazily)
``report/``  the HTML report that sets the results beside the paper's
===========  ===================================================================================
"""
