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


def check_cancelled(report, fraction):
    """For Python loops: report progress and raise steadylattice.Cancelled when the user cancelled."""
    if report is not None and report(fraction) is False:
        import steadylattice
        raise steadylattice.Cancelled("cancelled")
