"""View providers: icons, the lattice preview, and display defaults of the workbench's features."""
import FreeCAD
import FreeCADGui

from latticewb.utils import resources
from latticewb.utils.proxies import StatelessProxy


class ViewProviderLatticePreview(StatelessProxy):
    """Draws a lattice feature: FreeCAD's own shape display when its Shape holds solids, the scalable preview
    otherwise. The feature's proxy gives the preview's data through preview_data(obj)."""

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        from latticewb.viewproviders.lattice_preview import LatticePreview
        self.Object = vobj.Object
        self.preview = LatticePreview()
        vobj.RootNode.addChild(self.preview.switch)

    def updateData(self, obj, prop):
        if prop != "Shape" or not hasattr(self, "preview"):
            return
        data = None if obj.Shape.Solids else obj.Proxy.preview_data(obj)
        if data is None:
            self.preview.clear()
            return
        lattice, ball_mask, beam_mask = data
        drawn = self.preview.update(lattice, getattr(obj, "PreviewBudget", 2000000), ball_mask, beam_mask)
        total = lattice.beam_count if beam_mask is None else int(beam_mask.sum())
        if drawn < total:
            FreeCAD.Console.PrintMessage("%s: preview draws %d of %d beams (PreviewBudget)\n" % (obj.Label, drawn, total))
        self.preview.show(obj.ViewObject.Visibility)

    def onChanged(self, vobj, prop):
        if prop == "Visibility" and hasattr(self, "preview"):
            self.preview.show(vobj.Visibility and not vobj.Object.Shape.Solids)


class ViewProviderSteadyLattice(ViewProviderLatticePreview):
    def getIcon(self):
        return resources.icon("SteadyLattice")

    def setEdit(self, vobj, mode=0):
        if mode != 0:
            return None  # other modes (Transform, ...) are FreeCAD's own
        from latticewb.taskpanels.lattice_task_panel import LatticeTaskPanel
        FreeCADGui.Control.showDialog(LatticeTaskPanel(vobj.Object))
        return True

    def unsetEdit(self, vobj, mode=0):
        return None if mode != 0 else True

    def doubleClicked(self, vobj):
        FreeCADGui.ActiveDocument.setEdit(vobj.Object.Name, 0)
        return True


class ViewProviderCurvedLattice(ViewProviderLatticePreview):
    def getIcon(self):
        return resources.icon("CurvedLattice")


class InputsAsChildren:
    """Shows the feature's input links (the names in `inputs`) as its children in the tree, hidden like a Boolean's
    inputs; deleting the feature shows them again."""
    inputs = ()

    def claimChildren(self):
        return [o for o in (getattr(self.Object, name) for name in self.inputs) if o is not None]

    def onDelete(self, vobj, subelements):
        for child in self.claimChildren():
            if child.ViewObject:
                child.ViewObject.Visibility = True
        return True


class ViewProviderLatticePart(InputsAsChildren, StatelessProxy):
    """A LatticePart shows its lattice and body as children."""
    inputs = ("Lattice", "Body")

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return resources.icon("LatticePart")


class ViewProviderLatticeMesh(InputsAsChildren, StatelessProxy):
    """A LatticeMesh shows its lattice as a child; the mesh draws itself (FreeCAD's mesh view provider)."""
    inputs = ("Lattice",)

    def __init__(self, vobj):
        vobj.Proxy = self

    def attach(self, vobj):
        self.Object = vobj.Object

    def getIcon(self):
        return resources.icon("LatticeMesh")


class ViewProviderLatticeFilter(InputsAsChildren, ViewProviderLatticePreview):
    inputs = ("Source", "Coarse")

    def getIcon(self):
        return resources.icon("LatticeFilter")
