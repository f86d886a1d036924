"""Elastic machine models: two- and three-mass chains, elastic linkages, stiff numerics."""
