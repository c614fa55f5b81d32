"""Codimension-one curves (fold, flip, Neimark-Sacker, symmetry-breaking, grazing) in (eta, omega)."""
