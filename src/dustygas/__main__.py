"""``python -m dustygas`` is the ``dustygas`` command."""

import sys

from .cli import main

if __name__ == "__main__":  # not when a spawned worker (multiprocessing, mpi4py.futures) imports it as __mp_main__
    sys.exit(main())
