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
from ..errors import SimulationError, UserError

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


def main(argv: Sequence[str] | None = None) -> int:
    """Entry point of ``dustygas`` and ``python -m dustygas``; returns the exit status."""
    try:
        parser = build_parser()
        args = parser.parse_args(argv)
        if not getattr(args, "command", None):
            parser.print_help()
            return 0
        return int(args._module.main(args) or 0)
    except UserError as exc:
        print(f"dustygas: error: {exc}", file=sys.stderr)
        return exc.exit_code
    except SimulationError as exc:
        print(f"dustygas: simulation stopped: {exc}", file=sys.stderr)
        return exc.exit_code
    except KeyboardInterrupt:
        print("dustygas: interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
