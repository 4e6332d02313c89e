"""Long work made visible and cancellable.

    with LongOperation("Trimming lattice") as report:
        kernel_call(..., progress=report)      # report(fraction) -> False when the user cancelled

FreeCAD's progress bar (Base.ProgressIndicator) shows the fraction; in the GUI a dialog with a Cancel button
appears when the work lasts more than a second. Cancelling makes report() return False: kernel calls then raise
steadylattice.Cancelled and change nothing; Python loops should raise it themselves (see check_cancelled)."""
import FreeCAD

# Show the cancel dialog only for work that lasts: quick recomputes must not flash a window.
_DIALOG_DELAY_MS = 1000
_STEPS = 100  # resolution of FreeCAD's progress bar


class LongOperation:
    current = None  # the operation under way, for tests and macros that cancel it

    def __init__(self, title):
        self.title = title
        self.cancelled = False
        self._indicator = None
        self._dialog = None
        self._step = 0

    def __enter__(self):
        LongOperation.current = self
        self._indicator = FreeCAD.Base.ProgressIndicator()
        self._indicator.start(self.title, _STEPS)
        if FreeCAD.GuiUp:
            import FreeCADGui
            from PySide import QtCore, QtGui
            self._dialog = QtGui.QProgressDialog(self.title, "Cancel", 0, _STEPS, FreeCADGui.getMainWindow())
            self._dialog.setWindowModality(QtCore.Qt.WindowModal)
            self._dialog.setMinimumDuration(_DIALOG_DELAY_MS)
            self._dialog.setValue(0)
        return self

    def __call__(self, fraction):
        """Reports progress; False once the user has cancelled."""
        target = min(_STEPS, int(fraction * _STEPS))
        while self._step < target:
            self._step += 1
            self._indicator.next()
        if self._dialog is not None:
            from PySide import QtGui
            self._dialog.setValue(target)
            QtGui.QApplication.processEvents()
            if self._dialog.wasCanceled():
                self.cancelled = True
        return not self.cancelled

    def cancel(self):
        """Cancels from code (tests, macros) as the Cancel button would."""
        self.cancelled = True

    def __exit__(self, *exc):
        LongOperation.current = None
        self._indicator.stop()
        if self._dialog is not None:
            self._dialog.reset()
            self._dialog.deleteLater()
        return False


def keep_previous_shape(obj, what):
    """For a feature's execute() when the user cancelled: returning normally (no error, so no traceback in the
    report view) keeps the previous shape; this says so in the report view, and touches the object once the
    recompute is over, so it shows as needing recompute (FreeCAD clears a touch made inside execute())."""
    FreeCAD.Console.PrintWarning("%s: %s cancelled; the previous shape is kept (recompute to try again)\n"
                                 % (obj.Label, what))
    global _toucher
    if _toucher is None:
        _toucher = _TouchAfterRecompute()
        FreeCAD.addDocumentObserver(_toucher)
    _toucher.pending.setdefault(obj.Document.Name, set()).add(obj.Name)


class _TouchAfterRecompute:
    """Document observer: touches the objects whose recompute was cancelled when their document's recompute ends."""

    def __init__(self):
        self.pending = {}  # document name -> names of objects to touch

    def slotRecomputedDocument(self, doc):
        for name in self.pending.pop(doc.Name, ()):
            obj = doc.getObject(name)
            if obj is not None:
                obj.touch()


_toucher = None


def check_cancelled(report, fraction):
    """For Python loops: report progress and raise steadylattice.Cancelled when the user cancelled."""
    if report is not None and report(fraction) is False:
        import steadylattice
        raise steadylattice.Cancelled("cancelled")
