"""Force analysis by structural groups with friction in the pairs (Chaika–Vasylenko, section 3)."""
