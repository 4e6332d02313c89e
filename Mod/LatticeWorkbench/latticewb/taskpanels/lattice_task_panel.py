"""Task panel that creates and edits a SteadyLattice with a live preview.

Every change is written to the object and recomputed after a short pause (so typing does not recompute on every
key). The whole session is one transaction: OK keeps it, Cancel rolls the document back to where it was (removing
the lattice if the panel created it)."""
import FreeCAD
import FreeCADGui
from PySide import QtCore, QtGui

from latticewb.objects import steady_lattice

# Pause after the last edit before recomputing: long enough to type a number, short enough to feel live.
_RECOMPUTE_DELAY_MS = 250

active_panel = None  # the panel on screen, for tests and macros


def _combo(values, current):
    box = QtGui.QComboBox()
    box.addItems(values)
    box.setCurrentIndex(values.index(current))
    return box


def _double(value, minimum, maximum, suffix, decimals=3, step=0.1):
    box = QtGui.QDoubleSpinBox()
    box.setRange(minimum, maximum)
    box.setDecimals(decimals)
    box.setSingleStep(step)
    box.setSuffix(suffix)
    box.setValue(value)
    return box


def _integer(value, minimum, maximum):
    box = QtGui.QSpinBox()
    box.setRange(minimum, maximum)
    box.setValue(value)
    return box


class LatticeTaskPanel:
    def __init__(self, obj, transaction="Edit steady lattice"):
        """transaction: the name of the undo step this session opens, or None when the caller opened it (the
        creating command: then Cancel also removes the new object)."""
        global active_panel
        self.obj = obj
        self.doc = obj.Document
        if transaction:
            self.doc.openTransaction(transaction)
        self.form = QtGui.QWidget()
        self.form.setWindowTitle("Steady lattice")
        self.fields = {}  # property -> (widget, read value from widget)
        self._build()
        self.timer = QtCore.QTimer()
        self.timer.setSingleShot(True)
        self.timer.timeout.connect(self.apply)
        for widget, _ in self.fields.values():
            signal = widget.currentIndexChanged if isinstance(widget, QtGui.QComboBox) else widget.valueChanged
            signal.connect(self._changed)
        self._refresh()
        active_panel = self

    # --- layout ---------------------------------------------------------------------------------------
    def _build(self):
        obj = self.obj
        layout = QtGui.QVBoxLayout(self.form)
        cell = QtGui.QFormLayout()
        self._add(cell, "Preset", "Cell", _combo(obj.getEnumerationsOfProperty("Preset"), obj.Preset))
        self._add(cell, "CellSize", "Cell size", _double(obj.CellSize.Value, 0.001, 1e6, " mm", step=1.0))
        counts = QtGui.QHBoxLayout()
        for axis in "UVW":
            box = _integer(getattr(obj, "Cells" + axis), 1, 1000000)
            box.setToolTip("Cells along " + axis)
            self.fields["Cells" + axis] = (box, box.value)
            counts.addWidget(box)
        cell.addRow("Cells U, V, W", counts)
        self._add(cell, "NodeRadius", "Node radius", _double(obj.NodeRadius.Value, 0.001, 1e6, " mm"))
        self._add(cell, "BeamRadius", "Beam radius", _double(obj.BeamRadius.Value, 0.0, 1e6, " mm"))
        self._add(cell, "Layout", "Layout", _combo(steady_lattice.LAYOUTS, obj.Layout))
        self._add(cell, "Representation", "Show as", _combo(steady_lattice.REPRESENTATIONS, obj.Representation))
        layout.addLayout(cell)

        # one column per direction, one row per parameter: narrow enough for the task dock
        self.grading = QtGui.QGroupBox("Grading per cell")
        grid = QtGui.QGridLayout(self.grading)
        for column, axis in enumerate("UVW", start=1):
            grid.addWidget(QtGui.QLabel(axis), 0, column, QtCore.Qt.AlignCenter)
        rows = [("Taper", "Taper %", lambda a: _double(getattr(obj, "Taper" + a), -99.0, 1000.0, "%", 2, 0.5)),
                ("Twist", "Twist °", lambda a: _double(getattr(obj, "Twist" + a).Value, -180.0, 180.0, "°", 2, 0.5)),
                ("Bend", "Bend °", lambda a: _double(getattr(obj, "Bend" + a).Value, -180.0, 180.0, "°", 2, 0.5)),
                ("Toward", "toward", lambda a: _combo(obj.getEnumerationsOfProperty("Bend%sToward" % a),
                                                      getattr(obj, "Bend%sToward" % a)))]
        for row, (kind, label, make) in enumerate(rows, start=1):
            grid.addWidget(QtGui.QLabel(label), row, 0)
            for column, axis in enumerate("UVW", start=1):
                prop = "Bend%sToward" % axis if kind == "Toward" else kind + axis
                widget = make(axis)
                widget.setMinimumWidth(10)
                grid.addWidget(widget, row, column)
                self.fields[prop] = (widget, widget.currentText if isinstance(widget, QtGui.QComboBox) else widget.value)
        layout.addWidget(self.grading)
        self.other_layout = QtGui.QLabel("Edit the Steps or Frames group in the property editor; the lattice's own "
                                         "Placement (and Transform) moves the whole lattice.")
        self.other_layout.setWordWrap(True)
        layout.addWidget(self.other_layout)
        self.status = QtGui.QLabel()
        layout.addWidget(self.status)

    def _add(self, form, prop, label, widget):
        getter = widget.currentText if isinstance(widget, QtGui.QComboBox) else widget.value
        self.fields[prop] = (widget, getter)
        form.addRow(label, widget)

    # --- behaviour --------------------------------------------------------------------------------------
    def _changed(self, *_):
        self.timer.start(_RECOMPUTE_DELAY_MS)

    def _refresh(self):
        grading = self.fields["Layout"][1]() == "grading"
        self.grading.setVisible(grading)
        self.other_layout.setVisible(not grading)
        if "Invalid" in self.obj.State:
            self.status.setText("The lattice does not build: see the report view.")
        else:
            self.status.setText("%d balls, %d beams (applied order %s)"
                                % (self.obj.BallCount, self.obj.BeamCount, self.obj.AppliedOrder))

    def apply(self):
        """Writes the widgets into the object and recomputes it (the live preview)."""
        self.timer.stop()
        for prop, (_, read) in self.fields.items():
            value = read()
            current = getattr(self.obj, prop)
            current = current.Value if hasattr(current, "Value") else current
            if value != current:
                setattr(self.obj, prop, value)
        self.doc.recompute()
        # properties may have been clamped by the object's checks: show what was kept
        for prop, (widget, _) in self.fields.items():
            current = getattr(self.obj, prop)
            current = current.Value if hasattr(current, "Value") else current
            widget.blockSignals(True)
            if isinstance(widget, QtGui.QComboBox):
                widget.setCurrentIndex(max(0, widget.findText(str(current))))
            else:
                widget.setValue(current)
            widget.blockSignals(False)
        self._refresh()

    def _close(self):
        global active_panel
        active_panel = None
        FreeCADGui.Control.closeDialog()
        if FreeCADGui.ActiveDocument:
            FreeCADGui.ActiveDocument.resetEdit()

    def accept(self):
        self.apply()
        self.doc.commitTransaction()
        self._close()
        return True

    def reject(self):
        self.timer.stop()
        self.doc.abortTransaction()
        self.doc.recompute()
        self._close()
        return True

    def getStandardButtons(self):
        return int(QtGui.QDialogButtonBox.Ok | QtGui.QDialogButtonBox.Cancel)
