"""The family object, its orbits (1:1 and any wall sequence) and its augmented systems."""
