"""``python -m strapdown.analysis``: the ``strapdown`` command line."""

import sys

from .cli import main

sys.exit(main())
