"""Solver studies: how accurate and how converged the exact solver's measures are.

* :mod:`vines.studies.workprecision`: error against cost of the exact and RK solvers,
  measured against the high-precision reference (``vines.reference.hiprec``);
* :mod:`vines.studies.convergence`: the measures against run length and window, sticking
  threshold v_stick and grid resolution;
* :mod:`vines.studies.contours`: contour geometry of the grid-resolution study;
* :mod:`vines.studies.design` (``vines.design``): a VI NES design for a frequency band and
  base amplitudes against the LO alone and the optimal TMD (:mod:`vines.studies.tmd`),
  inputs checked by :mod:`vines.studies.design_checks` (docs/design.md).
* :mod:`vines.studies.shock`: free decay after a shock, the VI NES against the TMD and the
  LO alone (``vines shock``, docs/design.md).

The studies return plain results (numpy arrays in small dataclasses, with the settings that
describe them); ``vines.data.builders`` builds their CF datasets. The names below are
imported on first use, so that ``vines.studies.design_checks`` (the design defaults the CLI's
``--help`` shows) does not load numba and scipy.
"""
from .._lazy import lazy_attributes

#: public names loaded on first access, and their modules
_LAZY = {
    **dict.fromkeys(("area_above", "contour_distance", "contour_lines", "nested_axis"),
                    ".contours"),
    **dict.fromkeys(("STUDIES", "GridConvergence", "VStickConvergence", "WindowConvergence",
                     "grid_convergence", "vstick_convergence", "window_convergence"),
                    ".convergence"),
    **dict.fromkeys(("WorkPrecisionResult", "errors", "timed", "visible", "work_precision"),
                    ".workprecision"),
}

__all__ = sorted(_LAZY)


__getattr__, __dir__ = lazy_attributes(__name__, _LAZY)
