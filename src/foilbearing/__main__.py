"""``python -m foilbearing`` is the ``foilbearing`` command."""

from foilbearing.cli import main

raise SystemExit(main())
