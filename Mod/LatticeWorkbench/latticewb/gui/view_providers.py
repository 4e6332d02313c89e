"""View providers: icons and display defaults of the workbench's features."""
from latticewb import resources


class ViewProviderSteadyLattice:
    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return resources.icon("SteadyLattice")

    def dumps(self):
        return None

    def loads(self, state):
        return None

    __getstate__ = dumps
    __setstate__ = loads
