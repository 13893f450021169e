"""``python -m strapdown.analysis``: the ``strapdown`` command line."""

from .cli import script

if __name__ == "__main__":  # importing the module (documentation tools do) runs nothing
    script()
