"""Preview of a lattice of about 10^6 beams in a real FreeCAD window: time from a parameter change to the preview
drawn (recompute + Coin update + one redraw), and frame time while orbiting, against FreeCAD's own display of the
same lattice as separate Part solids at a size it can still handle (extrapolated per element).

Run: /usr/bin/python3 tests/bench/bench_preview.py [--long]   (starts FreeCAD under Xvfb by itself)
"""
import os
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.normpath(os.path.join(HERE, "..", ".."))


def launch():
    """Re-runs this file inside FreeCAD's GUI (via the GUI test launcher's environment)."""
    build = os.environ.get("STEADY_BUILD_DIR", os.path.join(ROOT, "build"))
    home = tempfile.mkdtemp()
    mods = os.path.join(home, ".local", "share", "FreeCAD", "Mod")
    os.makedirs(mods)
    os.symlink(os.path.join(ROOT, "Mod", "LatticeWorkbench"), os.path.join(mods, "LatticeWorkbench"))
    env = dict(os.environ, HOME=home, STEADY_BUILD_PYTHON=os.path.join(build, "python"),
               STEADY_BENCH_LONG="1" if "--long" in sys.argv else "0", QTWEBENGINE_CHROMIUM_FLAGS="--no-sandbox")
    out = subprocess.run(["xvfb-run", "-a", "-s", "-screen 0 1280x1024x24", "freecad", os.path.abspath(__file__)],
                         env=env, capture_output=True, text=True, timeout=3600)
    lines = [l for l in out.stdout.splitlines() if l.startswith("|") or l.startswith("bench:")]
    print("\n".join(lines))
    return 0 if any(l.startswith("bench: done") for l in lines) else 1


def measure():
    import time
    sys.path.insert(0, os.environ["STEADY_BUILD_PYTHON"])
    import FreeCAD
    import FreeCADGui
    from latticewb import api

    def median(values):
        values = sorted(values)
        return values[len(values) // 2]

    def frame_time(view, frames=12):
        cam = view.getCameraNode()
        times = []
        for f in range(frames):
            t = time.perf_counter()
            cam.orientation.setValue(FreeCAD.Rotation(FreeCAD.Vector(0, 0, 1), 3 * f).Q)
            view.redraw()
            FreeCADGui.updateGui()
            times.append(time.perf_counter() - t)
        return median(times)

    doc = FreeCAD.newDocument("Bench")
    view = FreeCADGui.activeDocument().activeView()
    rows = []
    sizes = [20, 35] + ([45] if os.environ.get("STEADY_BENCH_LONG") == "1" else [])
    obj = api.make_lattice(doc, preset="octet", cells=(10, 10, 10), cell_size=4.0, node_radius=0.6,
                           beam_radius=0.4, twist_w=1.0, representation="Preview")
    doc.recompute()
    view.viewIsometric()
    view.fitAll()
    for n in sizes:
        changes = []
        for repeat in range(3):
            t = time.perf_counter()
            obj.CellsU, obj.CellsV, obj.CellsW = n, n, n + repeat % 2  # a parameter change
            doc.recompute()
            view.redraw()
            FreeCADGui.updateGui()
            changes.append(time.perf_counter() - t)
        view.fitAll()
        rows.append(("preview", obj.BeamCount, median(changes), frame_time(view), obj.ViewObject.Proxy.preview.seconds))
    # the baseline: FreeCAD displaying the same lattice as Part solids (tessellated by FreeCAD), at a size it handles
    obj.Representation = "Elements"
    obj.CellsU, obj.CellsV, obj.CellsW = 4, 4, 4
    t = time.perf_counter()
    doc.recompute()
    view.redraw()
    FreeCADGui.updateGui()
    solid_change = time.perf_counter() - t
    view.fitAll()
    rows.append(("Part solids", obj.BeamCount, solid_change, frame_time(view), 0.0))
    print("| display | beams | change to drawn (s) | frame (s) | preview fill (s) | s per 10^6 beams |")
    print("|---|---|---|---|---|---|")
    for name, beams, change, frame, fill in rows:
        print("| %s | %d | %.2f | %.3f | %.2f | %.1f |" % (name, beams, change, frame, fill, change / beams * 1e6))
    per_beam_preview = rows[-2][2] / rows[-2][1]
    per_beam_solid = rows[-1][2] / rows[-1][1]
    print("| ratio (solids / preview, per beam) | | %.0fx | | | |" % (per_beam_solid / per_beam_preview))
    print("bench: done")
    sys.stdout.flush()
    os._exit(0)


if __name__ == "__main__":
    sys.exit(launch())
else:  # inside FreeCAD (the script's module is named after the file)
    measure()
