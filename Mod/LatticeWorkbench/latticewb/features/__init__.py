"""Kept so that documents saved before the workbench's layers load: their proxies name the modules
latticewb.features.steady_lattice, .lattice_filter and .lattice_part. New code uses latticewb.objects."""
