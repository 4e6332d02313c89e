"""Compatibility for documents saved before the layers: the proxy now lives in latticewb.objects."""
from latticewb.objects.lattice_part import LatticePart  # noqa: F401
