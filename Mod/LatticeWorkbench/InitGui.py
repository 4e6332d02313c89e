# LatticeWorkbench, GUI side: registers the workbench. Commands live in latticewb.gui.commands.
import FreeCADGui


class LatticeWorkbench(FreeCADGui.Workbench):
    MenuText = "Lattice"
    ToolTip = "Steady lattices: balls and conical beams laid out by similarities, trimmed into CAD parts"

    def __init__(self):
        from latticewb.utils import resources
        self.__class__.Icon = resources.icon("LatticeWorkbench")

    def Initialize(self):
        from latticewb.gui import commands
        self.appendToolbar("Lattice", commands.TOOLBAR)
        self.appendMenu("&Lattice", commands.MENU)

    def GetClassName(self):
        return "Gui::PythonWorkbench"


FreeCADGui.addWorkbench(LatticeWorkbench())
