"""View providers: icons, the lattice preview, and display defaults of the workbench's features."""
import FreeCAD
import FreeCADGui

from latticewb import resources


class ViewProviderSteadyLattice:
    """Draws a SteadyLattice: FreeCAD's own shape display for Solids, the scalable preview otherwise."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        from latticewb.gui.lattice_preview import LatticePreview
        self.Object = vobj.Object
        self.preview = LatticePreview()
        vobj.RootNode.addChild(self.preview.switch)

    def updateData(self, obj, prop):
        if prop != "Shape" or not hasattr(self, "preview"):
            return
        from latticewb.features import steady_lattice
        if steady_lattice.shows_solids(obj):
            self.preview.clear()
            return
        lattice = getattr(obj.Proxy, "lattice", None)
        if lattice is None:  # a document just opened: the kernel lattice is not saved, rebuild it
            try:
                lattice = steady_lattice.build_lattice(obj)
            except ValueError:
                self.preview.clear()
                return
        drawn = self.preview.update(lattice, obj.PreviewBudget)
        if drawn < lattice.beam_count:
            FreeCAD.Console.PrintMessage("%s: preview draws %d of %d beams (PreviewBudget)\n"
                                         % (obj.Label, drawn, lattice.beam_count))
        self.preview.show(obj.ViewObject.Visibility)

    def onChanged(self, vobj, prop):
        if prop == "Visibility" and hasattr(self, "preview"):
            from latticewb.features import steady_lattice
            self.preview.show(vobj.Visibility and not steady_lattice.shows_solids(vobj.Object))

    def getIcon(self):
        return resources.icon("SteadyLattice")

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None  # other modes (Transform, ...) are FreeCAD's own
        from latticewb.gui.lattice_task_panel import LatticeTaskPanel
        FreeCADGui.Control.showDialog(LatticeTaskPanel(vobj.Object))
        return True

    def unsetEdit(self, vobj, mode=0):
        return None if mode != 0 else True

    def doubleClicked(self, vobj):
        FreeCADGui.ActiveDocument.setEdit(vobj.Object.Name, 0)
        return True

    def dumps(self):
        return None

    def loads(self, state):
        return None

    __getstate__ = dumps
    __setstate__ = loads


class ViewProviderLatticePart:
    """A LatticePart shows its lattice and body as children in the tree (hidden, like a Boolean's inputs)."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def claimChildren(self):
        obj = self.Object
        return [o for o in (obj.Lattice, obj.Body) if o is not None]

    def onDelete(self, vobj, subelements):
        for child in self.claimChildren():
            if child.ViewObject:
                child.ViewObject.Visibility = True
        return True

    def getIcon(self):
        return resources.icon("LatticePart")

    def dumps(self):
        return None

    def loads(self, state):
        return None

    __getstate__ = dumps
    __setstate__ = loads
