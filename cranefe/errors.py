"""Exceptions with the messages users see.

`ModelError` is a user's mistake in an input file (exit status 2); `AnalysisError` is a
computation that cannot give a meaningful answer for a valid file (exit status 1).
"""


class ModelError(Exception):
    """Bad input: names the file, the entry and what to change."""

    def __init__(self, message, file=None, entry=None):
        self.file = file
        self.entry = entry
        self.message = message
        super().__init__(str(self))

    def __str__(self):
        where = ": ".join(str(p) for p in (self.file, self.entry) if p)
        return f"{where}: {self.message}" if where else self.message


class AnalysisError(Exception):
    """A valid model for which the requested analysis has no meaningful answer."""
