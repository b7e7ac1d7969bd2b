"""Errors a user can act on.

Every error that reaches the command line is one of these: it carries one line
that names where the bad value came from (file, field or line/column), the value
and what is allowed, and the CLI prints it without a traceback (exit code 2).
"""

from __future__ import annotations

__all__ = ["InputError", "SolverError"]


class InputError(Exception):
    """Bad user input.

    Parameters
    ----------
    message
        One line naming the field (or line/column), the value and what is allowed.
    source
        The file the value came from, if any; it is put in front of the message.
    """

    def __init__(self, message: str, *, source: str | None = None) -> None:
        self.source = source
        self.detail = message
        super().__init__(f"{source}: {message}" if source else message)


class SolverError(RuntimeError):
    """A numerical solve that did not converge: what failed, how far it got, what to try."""
