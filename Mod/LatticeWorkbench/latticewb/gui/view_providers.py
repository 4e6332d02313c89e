"""Compatibility for GUI documents saved before the layers: the view providers now live in
latticewb.viewproviders."""
from latticewb.viewproviders.view_providers import (  # noqa: F401
    ViewProviderLatticeFilter, ViewProviderLatticePart, ViewProviderLatticePreview, ViewProviderSteadyLattice)
