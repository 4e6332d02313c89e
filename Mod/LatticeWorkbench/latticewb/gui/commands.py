"""Toolbar and menu commands of the workbench."""
import FreeCAD
import FreeCADGui

from latticewb import resources


class NewLatticeCommand:
    """Creates a SteadyLattice (octet preset) in the active document; edit it in the property editor."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("SteadyLattice"),
            "MenuText": "New steady lattice",
            "ToolTip": "Create a steady lattice (preset cubic, BCC, FCC, octet or a custom cell); "
                       "edit counts, radii and the U, V, W steps in the property editor",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        from latticewb import api
        doc = FreeCAD.ActiveDocument
        doc.openTransaction("New steady lattice")
        try:
            obj = api.make_lattice(doc)
            doc.recompute()
        finally:
            doc.commitTransaction()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(obj)
        if FreeCADGui.ActiveDocument and FreeCADGui.ActiveDocument.ActiveView:
            FreeCADGui.SendMsgToActiveView("ViewFit")


COMMANDS = {
    "Lattice_NewLattice": NewLatticeCommand(),
}

for _name, _command in COMMANDS.items():
    FreeCADGui.addCommand(_name, _command)

TOOLBAR = ["Lattice_NewLattice"]
MENU = ["Lattice_NewLattice"]
