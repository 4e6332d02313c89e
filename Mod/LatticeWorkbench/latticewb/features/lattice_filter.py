"""Compatibility for documents saved before the layers: the proxy now lives in latticewb.objects."""
from latticewb.objects.lattice_filter import LatticeFilter  # noqa: F401
