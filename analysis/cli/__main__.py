"""``python -m strapdown.analysis.cli``: the ``strapdown`` command line."""

import sys

from . import main

if __name__ == "__main__":  # importing the module (documentation tools do) runs nothing
    sys.exit(main())
