"""``python -m vines`` runs the command-line interface (same as the ``vines`` command)."""
import sys

from .cli import main

if __name__ == "__main__":
    sys.exit(main())
