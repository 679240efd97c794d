"""``python -m escapement``: the command line of :mod:`escapement.cli`, as the ``escapement`` command."""

import sys

from .cli import MODULE_PROG, main

sys.exit(main(prog=MODULE_PROG))
