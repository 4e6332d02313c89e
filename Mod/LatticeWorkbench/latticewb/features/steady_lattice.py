"""Compatibility for documents saved before the layers: the proxy now lives in latticewb.objects."""
from latticewb.objects.steady_lattice import SteadyLattice  # noqa: F401
