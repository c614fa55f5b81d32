"""Impact maps with exact Jacobians, the one Newton on composed maps, affine-form seeds."""
