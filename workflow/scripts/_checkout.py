"""Import the vines of this checkout (src layout) in every job, whatever copy is installed:
the code version the Snakefile computed is the hash of exactly these sources.
Imported first by every script (the scripts directory is on sys.path)."""
import sys
from pathlib import Path

SRC = Path(__file__).resolve().parents[2] / "src"
if (SRC / "vines").is_dir() and str(SRC) not in sys.path:
    sys.path.insert(0, str(SRC))
