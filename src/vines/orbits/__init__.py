"""Periodic orbits on the exact impact maps: maps with Jacobians, 1:1 orbits and their
stability, continuation of branches with events, stability maps over parameter planes."""
