"""``python -m webfem.cli``: the command line (as ``python -m webfem``)."""

import sys

from .main import main

sys.exit(main())
