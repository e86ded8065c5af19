"""Exceptions that the command line turns into one-line messages.

Every error a user can cause by what they type or write in a configuration file is a
:class:`UserError`. The CLI prints ``dustygas: error: <message>`` on stderr and exits with
status 2, without a traceback, and nothing is written to disk (the run directory is only
created after the configuration and the initial state have been validated).

Errors that happen while a simulation is running (NaN, a smoothing-length iteration that
does not converge, overlapping particles) are :class:`SimulationError`; the run loop writes a
dump of the offending state next to the run before the CLI reports the one-line diagnostic
and exits with status 3. A file that cannot be written while a run goes on (disk full, quota,
a directory removed under the run) is an :class:`OutputError`: the temporary file is removed,
the loop writes a checkpoint if it still can, and the CLI exits with status 3 as well.

Exit statuses of ``dustygas run``:

=====  =========================================================================================
0      finished (``tlim`` or ``max_cycles`` reached; the run ends with a checkpoint)
2      refused before anything was written: bad input, a locked run directory, no usable checkpoint
3      stopped: invalid simulation state (``crash.h5`` dumped) or an output that could not be written
75     stopped at the wall-clock limit after writing a checkpoint (``EX_TEMPFAIL`` of BSD's
       sysexits.h: "try again"); a job script resubmits ``dustygas run --restart RUN``
128+N  stopped by signal N after writing a checkpoint (130 for Ctrl-C, 143 for SIGTERM)
=====  =========================================================================================
"""

from __future__ import annotations

__all__ = ["UserError", "ConfigError", "SetupError", "SimulationError", "OutputError", "EXIT_WALLTIME"]

#: ``dustygas run``'s exit status after a wall-clock stop (see the module docstring).
EXIT_WALLTIME = 75


class UserError(Exception):
    """Something the user asked for cannot be done; the message is one line and says why."""

    exit_code = 2


class ConfigError(UserError):
    """A configuration value is malformed, unknown, of the wrong type or out of range."""


class SetupError(UserError):
    """A problem set-up is inconsistent (e.g. particles overlap, box holds no wavelength)."""


class SimulationError(Exception):
    """A running simulation reached an invalid state (NaN, failed iteration, ...).

    Parameters
    ----------
    message
        One-line diagnostic.
    state
        Optional mapping of array name -> array with the offending state; the run loop dumps it
        to ``<run>/crash.h5``.
    """

    exit_code = 3

    def __init__(self, message: str, state: dict | None = None):
        super().__init__(message)
        self.state = state or {}


class OutputError(Exception):
    """A file of a running simulation could not be written (one line: which file and why)."""

    exit_code = 3
