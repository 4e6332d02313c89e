"""Screenshots of the 3D view, and the checks that they show something."""
import os
import tempfile

import FreeCADGui


def screenshot_dir():
    folder = os.environ.get("STEADY_SCREENSHOT_DIR") or os.path.join(tempfile.gettempdir(), "lattice-screenshots")
    os.makedirs(folder, exist_ok=True)
    return folder


def save_view(name, width=800, height=600, isometric=True):
    view = FreeCADGui.activeDocument().activeView()
    if isometric:
        view.viewIsometric()
    view.fitAll()
    FreeCADGui.updateGui()
    path = os.path.join(screenshot_dir(), name + ".png")
    view.saveImage(path, width, height, "White")
    return path


def ink_fraction(path):
    """Fraction of pixels that differ clearly from the white background, and the number of distinct colours."""
    from PySide2 import QtGui
    image = QtGui.QImage(path)
    if image.isNull():
        raise AssertionError("%s is not a readable image" % path)
    inked = 0
    colours = set()
    step = 2  # every other pixel in each direction: plenty for coverage, 4x faster
    samples = 0
    for y in range(0, image.height(), step):
        for x in range(0, image.width(), step):
            c = QtGui.QColor(image.pixel(x, y))
            samples += 1
            if min(c.red(), c.green(), c.blue()) < 230:
                inked += 1
                colours.add((c.red() // 16, c.green() // 16, c.blue() // 16))
    return inked / samples, len(colours)


def save_window(name):
    """The whole main window (tree, property editor, task panel and 3D view), for the user guide."""
    from PySide import QtCore, QtGui
    window = FreeCADGui.getMainWindow()
    # a wider task dock, as a user would drag it, so the panels show whole
    docks = [d for d in window.findChildren(QtGui.QDockWidget) if d.objectName() == "Combo View" and d.isVisible()]
    if docks:
        window.resizeDocks(docks, [400], QtCore.Qt.Horizontal)
    for _ in range(5):
        QtGui.QApplication.processEvents()
    path = os.path.join(screenshot_dir(), name + ".png")
    screen = QtGui.QApplication.primaryScreen()
    pixmap = screen.grabWindow(window.winId()) if screen is not None else window.grab()
    pixmap.save(path)
    return path
