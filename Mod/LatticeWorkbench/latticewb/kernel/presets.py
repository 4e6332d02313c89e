"""Preset unit cells: node positions in cell units and the beam patterns joining nearest neighbours.

A preset with `cells` (cu, cv, cw) becomes a steady lattice of (cu+1, cv+1, cw+1) groups, one group per cell
corner; nodes of the last layers that would lie outside the box of cells are omitted with their beams, so the
lattice ends on whole cells.
"""
import itertools
import math

# name -> (basis node positions as fractions of the cell, cell aspect (cell edge / CellSize per axis),
#          neighbour distance in CellSize units, which pairs to join)
_CORNER = (0.0, 0.0, 0.0)
_BODY = (0.5, 0.5, 0.5)
_FACES = [(0.5, 0.5, 0.0), (0.5, 0.0, 0.5), (0.0, 0.5, 0.5)]
_FCC = [_CORNER] + _FACES
_CUBE = (1.0, 1.0, 1.0)
# Kelvin foam (truncated octahedra packed body-centred): the vertices are the permutations of (0, 1/4 or 3/4, 1/2)
_KELVIN = sorted({tuple(p) for q in (0.25, 0.75) for p in itertools.permutations((0.0, q, 0.5))})
# honeycomb: hexagons of edge 1 in a rectangular cell 3 x sqrt(3), stacked along W at distance 1
_HONEYCOMB = [(0.0, 0.0, 0.0), (1.0 / 3.0, 0.0, 0.0), (0.5, 0.5, 0.0), (5.0 / 6.0, 0.5, 0.0)]

PRESETS = {
    # edges of the cube
    "cubic": ([_CORNER], _CUBE, 1.0, "all"),
    # body diagonals: the centre joined to the 8 corners
    "BCC": ([_CORNER, _BODY], _CUBE, math.sqrt(3) / 2, "all"),
    # face diagonals: each face centre joined to the 4 corners of its face
    "FCC": (_FCC, _CUBE, math.sqrt(2) / 2, "corner"),
    # octet truss: every FCC point joined to its 12 nearest neighbours
    "octet": (_FCC, _CUBE, math.sqrt(2) / 2, "all"),
    # diamond: two interpenetrating FCC lattices, each point joined to its 4 nearest neighbours
    "diamond": (_FCC + [(x + 0.25, y + 0.25, z + 0.25) for x, y, z in _FCC], _CUBE, math.sqrt(3) / 4, "all"),
    # Kelvin cell: the edges of the truncated octahedra, 4 per vertex
    "Kelvin": (_KELVIN, _CUBE, math.sqrt(2) / 4, "all"),
    # hexagonal honeycomb prisms: CellSize is the hexagon's edge and the layer height
    "honeycomb": (_HONEYCOMB, (3.0, math.sqrt(3.0), 1.0), 1.0, "all"),
}

PRESET_NAMES = list(PRESETS)

_DISTANCE_TOLERANCE = 1e-9  # positions are exact multiples of 1/2; any tolerance well below 1/2 works


def beam_patterns(basis, aspect, distance, which):
    """Patterns (n1, di, dj, dk, n2) joining basis nodes at `distance` (CellSize units), each pair once.

    which == "corner": keep only pairs with node 0 (the cell corner) at one end.
    """
    patterns = []
    for n1, n2 in itertools.product(range(len(basis)), repeat=2):
        for d in itertools.product((-1, 0, 1), repeat=3):
            if n1 == n2 and d == (0, 0, 0):
                continue
            delta = [(basis[n2][a] + d[a] - basis[n1][a]) * aspect[a] for a in range(3)]
            if abs(math.sqrt(sum(x * x for x in delta)) - distance) > _DISTANCE_TOLERANCE:
                continue
            if which == "corner" and 0 not in (n1, n2):
                continue
            # each pair once, written with a non-negative offset (lexicographically) for readability
            if d < (0, 0, 0) or (d == (0, 0, 0) and n1 > n2):
                continue
            patterns.append((n1, d[0], d[1], d[2], n2))
    return patterns


def preset_template(name):
    """(basis positions as fractions of the cell, cell aspect, beam patterns) of a preset."""
    if name not in PRESETS:
        raise ValueError("Preset: unknown preset %r (known: %s)" % (name, ", ".join(PRESET_NAMES)))
    basis, aspect, distance, which = PRESETS[name]
    return list(basis), aspect, beam_patterns(basis, aspect, distance, which)


def outside_nodes(basis, cells):
    """(i, j, k, n) of the nodes of groups 0..cells that lie outside the box of `cells` whole cells.
    Basis positions are fractions of the cell in [0, 1)."""
    omitted = set()
    counts = [c + 1 for c in cells]
    for n, b in enumerate(basis):
        for a in range(3):
            if b[a] == 0.0:
                continue  # only a node offset along axis a sticks out of the last layer along a
            ranges = [range(c) for c in counts]
            ranges[a] = [cells[a]]
            for i, j, k in itertools.product(*ranges):
                omitted.add((i, j, k, n))
    return sorted(omitted)
