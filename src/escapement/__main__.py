"""``python -m escapement``: the command line of :mod:`escapement.cli`."""

import sys

from .cli import main

sys.exit(main())
