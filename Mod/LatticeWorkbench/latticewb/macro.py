"""Running a macro from `freecad -c`: FreeCAD exits 0 when a script raises, so a macro's failure must be
turned into an exit status explicitly. In the GUI the error goes to the report view and FreeCAD stays open."""
import sys
import traceback

import FreeCAD


def run_macro(main, name):
    try:
        main()
    except Exception as error:
        FreeCAD.Console.PrintError("%s failed: %s\n" % (name, error))
        if not FreeCAD.GuiUp:
            traceback.print_exc()
            sys.stdout.flush()
            sys.exit(1)
        return
    if not FreeCAD.GuiUp:
        sys.stdout.flush()
        sys.exit(0)
