"""``python -m foilbearing`` is the ``foilbearing`` command."""

from foilbearing.cli.main import main

raise SystemExit(main())
