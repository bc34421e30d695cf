"""``python -m leuven_friction``: the same command line as ``leuven-friction``."""

import sys

from leuven_friction.app.cli import main

sys.exit(main())
