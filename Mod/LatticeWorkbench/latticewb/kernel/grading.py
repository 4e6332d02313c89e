"""Grading in the terms a designer uses (taper % per cell, twist and bend in degrees per cell) mapped to the
steady similarity of one step.

The step along a direction is the exponential of a generator built from *rates per cell*: the translation rate
(the cell size along the direction), the rotation rate (twist about the direction, bend about the axis normal to the
bend plane) and the growth rate (ln of the taper scale). So a row of cells moves steadily: with only a bend it
follows a circle of radius cell/bend-angle, with only a twist it turns about the lattice's centre line, with a
taper it shrinks or grows geometrically toward that line, and any mix is one steady screw or swirl. At zero the step
is the plain translation by the cell size: the map is continuous in every parameter (no special cases).

The twist axis and the taper centre are the lattice's centre line along the direction (through the middle of its
cross-section); the bend bends that centre line.
"""
import math

AXES = "UVW"
_UNIT = {"U": (1.0, 0.0, 0.0), "V": (0.0, 1.0, 0.0), "W": (0.0, 0.0, 1.0)}


def _cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def _add(*vectors):
    return tuple(sum(v[c] for v in vectors) for c in range(3))


def _scaled(s, v):
    return tuple(s * x for x in v)


def grading_step(direction, cell_vector, centre, taper_percent=0.0, twist_degrees=0.0, bend_degrees=0.0,
                 bend_toward="V"):
    """The step similarity along `direction` ("U", "V" or "W").

    cell_vector: the translation of one step without grading (cell size along the direction, in mm).
    centre: a point of the lattice's centre line along the direction (mm).
    taper_percent: growth per cell (-3 makes each cell 3 % smaller than the previous).
    twist_degrees: rotation per cell about the centre line.
    bend_degrees: rotation per cell that bends the centre line toward `bend_toward` (another of U, V, W).
    """
    import steadylattice as sl

    if direction not in _UNIT:
        raise ValueError("direction: expected one of U, V, W (got %r)" % (direction,))
    scale = 1.0 + taper_percent / 100.0
    if not scale > 0.0:
        raise ValueError("Taper%s: must be > -100 %% per cell (got %g)" % (direction, taper_percent))
    if bend_toward not in _UNIT or bend_toward == direction:
        raise ValueError("Bend%sToward: must be another axis than %s (got %r)" % (direction, direction, bend_toward))
    e = _UNIT[direction]
    bend_normal = _cross(e, _UNIT[bend_toward])  # rotating about it turns e toward bend_toward
    sigma = math.log(scale)
    omega = _add(_scaled(math.radians(twist_degrees), e), _scaled(math.radians(bend_degrees), bend_normal))
    # The velocity field p -> v + omega x p + sigma p must move the centre point by the cell vector: then the
    # rotation and the growth happen about the centre line.
    velocity = _add(cell_vector, _scaled(-1.0, _cross(omega, centre)), _scaled(-sigma, centre))
    return sl.Similarity.from_generator(sigma, omega, velocity)
