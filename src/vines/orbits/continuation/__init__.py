"""Continuation of branches of periodic orbits with events and branch switching."""
