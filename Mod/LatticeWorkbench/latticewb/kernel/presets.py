"""Preset unit cells: the kernel's (steadylattice.preset), in the form the workbench reads.

A preset with `cells` (cu, cv, cw) becomes a steady lattice of (cu+1, cv+1, cw+1) groups, one group per cell
corner; nodes of the last layers that would lie outside the box of cells are omitted with their beams, so the
lattice ends on whole cells.
"""
import steadylattice as sl

PRESET_NAMES = list(sl.preset_names())


def _entry(name):
    cell = sl.preset(name)
    return (cell["basis"], cell["aspect"], cell["neighbour_distance"],
            "corner" if cell["corner_beams_only"] else "all")


# name -> (basis node positions as fractions of the cell, cell aspect (cell edge / CellSize per axis),
#          neighbour distance in CellSize units, which pairs are joined: "all" or only those with the "corner")
PRESETS = {name: _entry(name) for name in PRESET_NAMES}


def preset_template(name):
    """(basis positions as fractions of the cell, cell aspect, beam patterns) of a preset."""
    if name not in PRESETS:
        raise ValueError("Preset: unknown preset %r (known: %s)" % (name, ", ".join(PRESET_NAMES)))
    cell = sl.preset(name)
    return list(cell["basis"]), cell["aspect"], list(cell["patterns"])


def outside_nodes(name, cells):
    """(i, j, k, n) of the nodes of groups 0..cells that lie outside the box of `cells` whole cells."""
    return [tuple(node) for node in sl.preset_outside_nodes(name, tuple(cells))]
