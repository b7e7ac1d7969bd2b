"""The ``foilbearing`` command: :func:`~foilbearing.cli.main.main` and one module per subcommand family.

Every module here parses arguments and calls the library; the numerics are
imported when a subcommand runs, so ``foilbearing --help`` starts quickly.
"""
