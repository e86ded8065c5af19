"""``python -m dustygas`` is the ``dustygas`` command."""

import sys

from .cli import main

sys.exit(main())
