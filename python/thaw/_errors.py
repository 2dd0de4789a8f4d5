"""thaw's two kinds of error, as the command line has them (exit code 2 and exit code 3)."""


class UserError(Exception):
    """Bad input that is yours to fix: a scenario or scene key, a file, an argument.

    ``str(error)`` is the one line ``thaw`` prints after ``thaw: error:`` for the same input.

    Attributes:
        file: the file concerned ("" if none), e.g. ``"my.toml"``.
        key: where in it: ``"line 3, key 'shell.inner_radius_m'"``, a key or argument name,
            or "".
        problem: what is wrong, with the offending value where there is one.
    """

    def __init__(self, message, file="", key="", problem=""):
        super().__init__(message)
        self.file = file
        self.key = key
        self.problem = problem


class InternalError(RuntimeError):
    """A failure inside thaw that is not the input's fault (the command line's exit code 3).

    Please report it with the input that caused it.
    """
