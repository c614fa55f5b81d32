"""Shared preamble of the figure scripts: this checkout's vines first, the job log, and a
clear one-line failure (no empty figure) when an input dataset does not pass its checks."""
import sys
import traceback
from pathlib import Path

SRC = Path(__file__).resolve().parents[3] / "src"
if (SRC / "vines").is_dir() and str(SRC) not in sys.path:
    sys.path.insert(0, str(SRC))

from vines.plotting.draw import FigureInputError  # noqa: E402


def run(sm, main):
    """Call ``main(sm)`` with stdout/stderr in the job log; on bad input, fail clearly."""
    name = Path(sm.output.png).stem
    err = sys.stderr
    with open(sm.log[0], "w") as log:
        sys.stdout = sys.stderr = log
        try:
            main(sm)
        except FigureInputError as exc:
            msg = f"vines figures: {name}: bad input: {exc}"
            print(msg, file=log)
            print(msg, file=err)
            sys.exit(1)
        except Exception:
            traceback.print_exc(file=log)
            raise
        finally:
            sys.stdout, sys.stderr = sys.__stdout__, err
