"""Toolbar and menu commands of the workbench. Each command is a thin shell over latticewb.api, inside an undo
transaction; long work reports progress (see latticewb.utils.progress)."""
import os

import FreeCAD
import FreeCADGui

from latticewb.utils import resources, types


def _create(doc, transaction, make):
    """Runs make() and a recompute as one undo step (nothing stays behind when it raises), then selects the new
    object."""
    doc.openTransaction(transaction)
    try:
        obj = make()
        doc.recompute()
    except Exception:
        doc.abortTransaction()
        raise
    doc.commitTransaction()
    FreeCADGui.Selection.clearSelection()
    FreeCADGui.Selection.addSelection(obj)
    return obj


def _selected(predicate=None):
    objects = FreeCADGui.Selection.getSelection()
    return [o for o in objects if predicate is None or predicate(o)]


class NewLatticeCommand:
    """Creates a SteadyLattice and opens its task panel (live preview); Cancel removes it again."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("SteadyLattice"),
            "MenuText": "New steady lattice",
            "ToolTip": "Create a steady lattice from a preset cell (cubic, BCC, FCC, octet, diamond, Kelvin, "
                       "honeycomb) or a custom one, graded by taper, twist and bend per cell",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        from latticewb import api
        from latticewb.taskpanels.lattice_task_panel import LatticeTaskPanel
        doc = FreeCAD.ActiveDocument
        doc.openTransaction("New steady lattice")
        obj = api.make_lattice(doc)
        doc.recompute()
        FreeCADGui.Selection.clearSelection()
        FreeCADGui.Selection.addSelection(obj)
        if FreeCADGui.ActiveDocument and FreeCADGui.ActiveDocument.ActiveView:
            FreeCADGui.SendMsgToActiveView("ViewFit")
        FreeCADGui.Control.showDialog(LatticeTaskPanel(obj, transaction=None))


class NewCurvedLatticeCommand:
    """Creates a CurvedLattice; four selected vertices (sketch points, Draft points, vertices of a shape), in the
    order A, B, C, D, become its linked corners. A selected planar, cylindrical or conical face becomes its FaceLink:
    the lattice is laid on it (with three vertices A, B, D, or four, or none: corners spread over the face)."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("CurvedLattice"),
            "MenuText": "New curved lattice",
            "ToolTip": "Create a BeCOTS lattice that follows the cone or plane through four corners: select four "
                       "vertices (A = M(0,0), B = M(0,1), C = M(1,1), D = M(1,0)) to link them, or edit the "
                       "corners in the property editor. Select a planar, cylindrical or conical face too (with "
                       "A, B, D or none) to lay the lattice on it, in layers going into the body",
        }

    def IsActive(self):
        return FreeCAD.ActiveDocument is not None

    def Activated(self):
        from latticewb import api
        from latticewb.kernel import face_field
        links, faces = [], []
        for selection in FreeCADGui.Selection.getSelectionEx():
            names = [n for n in selection.SubElementNames if n.startswith("Vertex")]
            faces.extend((selection.Object, n) for n in selection.SubElementNames if n.startswith("Face"))
            if names:
                links.extend((selection.Object, n) for n in names)
            elif not selection.SubElementNames:
                shape = getattr(selection.Object, "Shape", None)
                if shape is not None and len(shape.Vertexes) == 1:  # a Draft point
                    links.append((selection.Object, ""))
        if len(faces) > 1:
            FreeCAD.Console.PrintError("Curved lattice: select one face to lay it on (got %d)\n" % len(faces))
            return
        face = faces[0] if faces else None
        if face is not None and len(links) == 3:
            links.insert(2, None)  # C is implied by the face's field (typed, unused on a curved face)
        if links and len(links) != 4:
            FreeCAD.Console.PrintError("Curved lattice: select four vertices (A, B, C, D), three with a face (A, B, "
                                       "D), or none (got %d)\n" % len(links))
            return
        corners = None
        if face is not None and not links:
            corners = face_field.corners_on(face[0].Shape.getElement(face[1]))
        doc = FreeCAD.ActiveDocument
        _create(doc, "New curved lattice",
                lambda: api.make_curved_lattice(doc, corners=corners, links=links or None, face=face))
        if FreeCADGui.ActiveDocument and FreeCADGui.ActiveDocument.ActiveView:
            FreeCADGui.SendMsgToActiveView("ViewFit")


class LatticePartCommand:
    """Trims the selected lattice into the selected body (select the lattice, then the body) as one B-rep solid."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("LatticePart"),
            "MenuText": "Lattice part",
            "ToolTip": "Fill the selected body with the selected lattice: select a steady or curved lattice and then "
                       "a solid. Set the skin thickness and the trim policy (clip, whole hubs, or whole hubs "
                       "bridged to the wall) in the property editor",
        }

    def IsActive(self):
        return any(types.is_part_lattice(o) for o in FreeCADGui.Selection.getSelection())

    def Activated(self):
        from latticewb import api
        selection = FreeCADGui.Selection.getSelection()
        lattices = [o for o in selection if types.is_part_lattice(o)]
        bodies = [o for o in selection if not types.is_part_lattice(o) and hasattr(o, "Shape") and o.Shape.Solids]
        if len(lattices) != 1 or len(bodies) > 1:
            FreeCAD.Console.PrintError("Lattice part: select one steady or curved lattice and at most one solid "
                                       "body\n")
            return
        doc = FreeCAD.ActiveDocument
        _create(doc, "Lattice part", lambda: api.make_part(doc, lattices[0], bodies[0] if bodies else None))


class MeshCommand:
    """Meshes the selected lattice straight from the kernel: a closed mesh for printing or for lattices too large
    for a B-rep."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("LatticeMesh"),
            "MenuText": "Lattice mesh",
            "ToolTip": "Mesh the selected steady lattice straight from the kernel (no B-rep): one closed, oriented "
                       "mesh, every triangle within Tolerance of the exact surface. For printing (export STL or "
                       "3MF) and for lattices too large for a solid",
        }

    def IsActive(self):
        return any(types.is_lattice(o) for o in FreeCADGui.Selection.getSelection())

    def Activated(self):
        from latticewb import api
        lattices = [o for o in FreeCADGui.Selection.getSelection() if types.is_lattice(o)]
        if len(lattices) != 1:
            FreeCAD.Console.PrintError("Lattice mesh: select one steady lattice\n")
            return
        doc = FreeCAD.ActiveDocument
        _create(doc, "Lattice mesh", lambda: api.make_mesh(doc, lattices[0]))


class FilterCommand:
    """Filters the selected lattice. With a second lattice selected: Lattice-in-Lattice (keep the nodes whose balls
    meet it); with a solid selected: keep the nodes inside it; otherwise a stencil, editable in the property editor
    (also gyroid)."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("LatticeFilter"),
            "MenuText": "Filter / Lattice-in-Lattice",
            "ToolTip": "Thin the selected lattice: select a lattice, then optionally a coarse lattice "
                       "(Lattice-in-Lattice) or a solid (inside body); otherwise a stencil. Kind, stencil and gyroid "
                       "are in the property editor; filters cascade",
        }

    def IsActive(self):
        return any(types.is_lattice_source(o) for o in FreeCADGui.Selection.getSelection())

    def Activated(self):
        from latticewb import api
        selection = FreeCADGui.Selection.getSelection()
        source = selection[0]
        if not types.is_lattice_source(source):
            FreeCAD.Console.PrintError("Filter: select the lattice to filter first\n")
            return
        second = selection[1] if len(selection) > 1 else None
        doc = FreeCAD.ActiveDocument

        def make():
            if second is not None and types.is_lattice_source(second):
                return api.make_filter(doc, source, "lattice-in-lattice", coarse=second)
            if second is not None and hasattr(second, "Shape") and second.Shape.Solids:
                return api.make_filter(doc, source, "inside body", body=second)
            return api.make_filter(doc, source, "stencil")

        _create(doc, "Lattice filter", make)


class PropertiesCommand:
    """Reports volume, area, centroid, mass and inertia of the selected lattices and parts."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("Properties"),
            "MenuText": "Properties report",
            "ToolTip": "Volume, area, centroid, mass (from the Density property) and inertia tensor of the selected "
                       "lattices (closed form, exact) and parts (B-rep integration)",
        }

    def IsActive(self):
        return bool(FreeCADGui.Selection.getSelection())

    def Activated(self):
        from PySide import QtGui
        from latticewb import api
        from latticewb.kernel import mass
        texts = []
        for obj in FreeCADGui.Selection.getSelection():
            try:
                texts.append(mass.report_text(obj, api.properties(obj)))
            except ValueError as error:
                texts.append("%s: %s" % (obj.Label, error))
        text = "\n\n".join(texts)
        FreeCAD.Console.PrintMessage(text + "\n")
        box = QtGui.QMessageBox(FreeCADGui.getMainWindow())
        box.setWindowTitle("Lattice properties")
        box.setText("<pre>%s</pre>" % text)
        box.show()  # not modal: the numbers stay beside the model


class DensityTargetCommand:
    """Scales the radii of the selected lattice to reach a relative density or a mass."""

    def GetResources(self):
        return {
            "Pixmap": resources.icon("DensityTarget"),
            "MenuText": "Density target...",
            "ToolTip": "Scale every radius of the selected lattice so that it reaches a relative density (of its "
                       "box of cells) or a mass; solved with the closed-form volume",
        }

    def IsActive(self):
        return any(types.is_lattice(o) for o in FreeCADGui.Selection.getSelection())

    def Activated(self):
        from PySide import QtGui
        from latticewb import api
        obj = [o for o in FreeCADGui.Selection.getSelection() if types.is_lattice(o)][0]
        choice, ok = QtGui.QInputDialog.getItem(FreeCADGui.getMainWindow(), "Density target", "Target:",
                                                ["relative density (%)", "mass (g)"], 0, False)
        if not ok:
            return
        value, ok = QtGui.QInputDialog.getDouble(FreeCADGui.getMainWindow(), "Density target", choice, 20.0, 1e-6,
                                                 1e9, 4)
        if not ok:
            return
        doc = obj.Document
        doc.openTransaction("Density target")
        try:
            if choice.startswith("relative"):
                scale = api.target_density(obj, relative_density=value / 100.0)
            else:
                scale = api.target_density(obj, mass=value / 1000.0)
            doc.recompute()
        except ValueError as error:
            doc.abortTransaction()
            FreeCAD.Console.PrintError("Density target: %s\n" % error)
            return
        doc.commitTransaction()
        FreeCAD.Console.PrintMessage("%s: radii scaled by %.6g\n" % (obj.Label, scale))


class ExportCommand:
    """Exports the selected objects to STEP (one named part per object), BREP or a lattice file (JSON)."""

    FILTERS = ("STEP (*.step *.stp);;BREP (*.brep *.brp);;Lattice file (*.json);;STL mesh (*.stl);;OBJ mesh (*.obj);;"
               "3MF beam lattice (*.3mf)")

    def GetResources(self):
        return {
            "Pixmap": resources.icon("Export"),
            "MenuText": "Export lattice...",
            "ToolTip": "Export the selected lattices and parts: STEP (named parts), BREP, the lattice file (JSON), or "
                       "for printers STL, OBJ and 3MF beam lattices straight from the lattice",
        }

    def IsActive(self):
        return bool(FreeCADGui.Selection.getSelection())

    def Activated(self):
        from PySide import QtGui
        from latticewb import api
        objects = _selected()
        start = os.path.join(os.path.expanduser("~"), objects[0].Label + ".step")
        path, _ = QtGui.QFileDialog.getSaveFileName(FreeCADGui.getMainWindow(), "Export lattice", start, self.FILTERS)
        if not path:
            return
        import steadylattice
        try:
            api.export(objects, path)
        except steadylattice.Cancelled:
            FreeCAD.Console.PrintWarning("Export cancelled: %s was not written\n" % path)
            return
        except (ValueError, RuntimeError) as error:
            FreeCAD.Console.PrintError("Export: %s\n" % error)
            return
        FreeCAD.Console.PrintMessage("Exported %d object(s) to %s\n" % (len(objects), path))


COMMANDS = {
    "Lattice_NewLattice": NewLatticeCommand(),
    "Lattice_NewCurvedLattice": NewCurvedLatticeCommand(),
    "Lattice_Part": LatticePartCommand(),
    "Lattice_Mesh": MeshCommand(),
    "Lattice_Filter": FilterCommand(),
    "Lattice_Properties": PropertiesCommand(),
    "Lattice_DensityTarget": DensityTargetCommand(),
    "Lattice_Export": ExportCommand(),
}

for _name, _command in COMMANDS.items():
    FreeCADGui.addCommand(_name, _command)

TOOLBAR = ["Lattice_NewLattice", "Lattice_NewCurvedLattice", "Lattice_Filter", "Lattice_Part", "Lattice_Mesh",
           "Separator", "Lattice_Properties",
           "Lattice_DensityTarget", "Separator", "Lattice_Export"]
MENU = TOOLBAR
