"""The ``foilbearing`` command: :func:`~foilbearing.cli.main.main` and one module per subcommand family.

Every module here parses arguments and calls the library; the numerics are
imported when a subcommand runs, so ``foilbearing --help`` starts quickly.

================  ==============================================================================
module            responsibility
================  ==============================================================================
``main``          the ``foilbearing`` command: a thin layer over the library, its exit codes
``common``        pieces shared by the subcommands
``reading``       ``--preload-response`` and ``--actuator-dynamics``: the actuator's reading
``run_args``      an orbit run's voltage programs, ``--stop-time``, ``--checkpoint-every``
``case``          ``foilbearing case show``
``structure``     ``foilbearing structure``
``identify``      ``foilbearing identify``
``static``        ``foilbearing static``
``coefficients``  ``foilbearing coefficients``
``stability``     ``foilbearing stability``
``check``         ``foilbearing check``
``orbit``         ``foilbearing orbit``
``bifurcation``   ``foilbearing bifurcation``
``optimize``      ``foilbearing optimize``
``schedule``      ``foilbearing schedule``
``rotor``         ``foilbearing rotor``
``study``         ``foilbearing study``
``sweep``         ``foilbearing sweep``
``uncertainty``   ``foilbearing uncertainty``
================  ==============================================================================
"""
