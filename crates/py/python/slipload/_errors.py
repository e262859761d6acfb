"""The exceptions slipload raises.

Every error slipload raises on purpose is a :class:`SlipLoadError`; its message is the one
the ``slipload`` command line prints for the same input (the file, the field or line, and
what was expected).
"""


class SlipLoadError(Exception):
    """Base class of every error slipload raises on purpose."""


class InputError(SlipLoadError, ValueError):
    """A file, field or argument is wrong: the message names it and says what was expected."""


class FileError(SlipLoadError, OSError):
    """A file or folder cannot be read or written (missing, not a file, busy, no space)."""


class SimulationError(SlipLoadError, RuntimeError):
    """A simulation failed on valid input (a response that is not finite, a solver that
    did not converge); the message names the design and record."""


class InternalError(SlipLoadError, RuntimeError):
    """A bug in slipload, caught before it could harm the interpreter. Please report it
    with the input that caused it."""


__all__ = ["SlipLoadError", "InputError", "FileError", "SimulationError", "InternalError"]
