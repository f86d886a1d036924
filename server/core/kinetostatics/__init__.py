"""Force analysis by structural groups with friction in the pairs (seed 002, section 3)."""
