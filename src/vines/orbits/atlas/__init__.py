"""Which families exist at a point, and stability maps over (eta, omega)."""
