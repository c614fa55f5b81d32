"""Solver studies: how accurate and how converged the exact solver's measures are.

* :mod:`vines.studies.workprecision`: error against cost of the exact and RK solvers,
  measured against the high-precision reference (``vines.reference.hiprec``);
* :mod:`vines.studies.convergence`: the measures against run length and window, sticking
  threshold v_stick and grid resolution;
* :mod:`vines.studies.contours`: contour geometry of the grid-resolution study;
* :mod:`vines.studies.design` (``vines.design``): a VI NES design for a frequency band and
  base amplitudes against the LO alone and the optimal TMD (:mod:`vines.studies.tmd`),
  inputs checked by :mod:`vines.studies.design_checks` (docs/design.md).

The studies return plain results (numpy arrays in small dataclasses, with the settings that
describe them); ``vines.data.builders`` builds their CF datasets.
"""
from .contours import area_above, contour_distance, contour_lines, nested_axis
from .convergence import (
                          STUDIES,
                          GridConvergence,
                          VStickConvergence,
                          WindowConvergence,
                          grid_convergence,
                          vstick_convergence,
                          window_convergence,
)
from .workprecision import WorkPrecisionResult, errors, timed, visible, work_precision

__all__ = [
    "STUDIES", "GridConvergence", "VStickConvergence", "WindowConvergence",
    "WorkPrecisionResult", "area_above", "contour_distance", "contour_lines", "errors",
    "grid_convergence", "nested_axis", "timed", "visible", "vstick_convergence",
    "window_convergence", "work_precision",
]
