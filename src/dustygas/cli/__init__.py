"""The ``dustygas`` command line.

Each subcommand lives in its own module of this package and provides ``HELP`` (one line),
``add_arguments(parser)`` and ``main(args) -> int``; list it in :data:`COMMANDS`. Errors a user
can cause are :class:`~dustygas.errors.UserError`: printed as one line on stderr, exit 2.
"""

from __future__ import annotations

import argparse
import importlib
import sys
from typing import Sequence

from .._version import __version__
from ..errors import OutputError, SimulationError, UserError

#: subcommand name -> module (imported only when that subcommand runs or help is shown).
COMMANDS: dict[str, str] = {
    "run": "dustygas.cli.run",
    "problems": "dustygas.cli.problems",
    "reproduce": "dustygas.cli.reproduce",
    "info": "dustygas.cli.info",
    "linear": "dustygas.cli.linear",
    "analyze": "dustygas.cli.analyze",
    "export": "dustygas.cli.export",
    "plot": "dustygas.cli.plot",
}


class OneLineParser(argparse.ArgumentParser):
    """argparse, but usage errors are one line (``dustygas: error: ...``) and exit 2."""

    def error(self, message: str) -> None:  # type: ignore[override]
        raise UserError(f"{self.prog}: {message} (see {self.prog} --help)")


def build_parser() -> argparse.ArgumentParser:
    parser = OneLineParser(
        prog="dustygas",
        description="Dust and gas in protoplanetary disks: linear streaming-instability theory, "
        "a particle-gas shearing-box engine and a dusty SPH engine.",
    )
    parser.add_argument("--version", action="version", version=f"dustygas {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", parser_class=OneLineParser)
    for name, modname in COMMANDS.items():
        mod = importlib.import_module(modname)
        p = sub.add_parser(name, help=mod.HELP, description=getattr(mod, "DESCRIPTION", mod.HELP),
                           formatter_class=argparse.RawDescriptionHelpFormatter)
        mod.add_arguments(p)
        p.set_defaults(_module=mod)
    return parser


def _say(line: str) -> None:
    """An error line on stderr, once per run: from rank 0 only under MPI (every rank has it)."""
    from ..parallel.comm import is_writer

    if is_writer():
        print(line, file=sys.stderr)


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``dustygas`` and ``python -m dustygas``; returns the exit status."""
    try:
        parser = build_parser()
        args = parser.parse_args(argv)
        if not getattr(args, "command", None):
            parser.print_help()
            return 0
        if args.command != "run":  # an MPI rank holds its stop signals for the run loop only (dustygas._launch)
            from .._launch import release_stop_signals

            release_stop_signals()
        return int(args._module.main(args) or 0)
    except UserError as exc:
        _say(f"dustygas: error: {exc}")
        return exc.exit_code
    except SimulationError as exc:
        _say(f"dustygas: simulation stopped: {exc}")
        return exc.exit_code
    except OutputError as exc:
        _say(f"dustygas: output failed: {exc}")
        return exc.exit_code
    except KeyboardInterrupt:
        print("dustygas: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except BaseException:
        from ..parallel.comm import launched_under_mpi, world

        if not launched_under_mpi():
            raise
        import traceback

        traceback.print_exc()  # an unexpected error on one rank: stop every rank, do not hang them
        world().Abort(1)
        raise
