"""Closed-form shooting conditions of the 1:1 orbits with exact derivatives by Taylor jets."""
