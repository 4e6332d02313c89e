"""The scalable preview of a lattice: beam axes as one indexed line set, in Coin3D, fed from numpy arrays (pivy
copies them in C++), so 10^6 beams appear in well under a second. Nodes are drawn as points only when the lattice
has no beams (otherwise the beam ends show them, and a million extra points would double the frame time). A budget
bounds what is drawn: past it, an evenly spread subset of the beams (every k-th in the stable order) is shown."""
import math
import time

import numpy as np
from pivy import coin

BEAM_COLOUR = (0.25, 0.45, 0.75)
NODE_COLOUR = (0.1, 0.2, 0.45)


class LatticePreview:
    def __init__(self):
        self.switch = coin.SoSwitch()
        self.switch.whichChild = coin.SO_SWITCH_NONE
        root = coin.SoSeparator()
        self.coordinates = coin.SoCoordinate3()
        beam_colour = coin.SoBaseColor()
        beam_colour.rgb = BEAM_COLOUR
        node_colour = coin.SoBaseColor()
        node_colour.rgb = NODE_COLOUR
        style = coin.SoDrawStyle()
        style.lineWidth = 1.0  # wide lines cost much more per frame in software renderers
        style.pointSize = 3.0
        light = coin.SoLightModel()
        light.model = coin.SoLightModel.BASE_COLOR  # lines and points need no shading
        self.lines = coin.SoIndexedLineSet()
        self.points = coin.SoPointSet()
        self.points.numPoints = 0
        for child in (light, style, self.coordinates, beam_colour, self.lines, node_colour, self.points):
            root.addChild(child)
        self.switch.addChild(root)
        self.drawn_beams = 0
        self.seconds = 0.0

    def show(self, visible):
        self.switch.whichChild = 0 if visible else coin.SO_SWITCH_NONE

    def clear(self):
        self.points.numPoints = 0
        self.coordinates.point.setNum(0)
        self.lines.coordIndex.setNum(0)
        self.drawn_beams = 0
        self.show(False)

    def update(self, lattice, budget, ball_mask=None, beam_mask=None):
        """Fills the preview from a steadylattice.Lattice (only the balls and beams the masks keep, when given);
        returns the number of beams drawn."""
        start = time.perf_counter()
        centers, _ = lattice.balls()
        a, b, _, _ = lattice.beams()
        if beam_mask is not None:
            a, b = a[beam_mask], b[beam_mask]
        stride = max(1, math.ceil(len(a) / max(1, budget)))
        if stride > 1:
            a, b = a[::stride], b[::stride]
        points = np.ascontiguousarray(centers, dtype=np.float32)
        index = np.empty((len(a), 3), dtype=np.int32)
        index[:, 0] = a
        index[:, 1] = b
        index[:, 2] = -1  # end of a polyline
        self.coordinates.point.setNum(0)
        self.lines.coordIndex.setNum(0)
        if len(points):
            self.coordinates.point.setValues(0, len(points), points)
        if len(index):
            flat = index.reshape(-1)
            self.lines.coordIndex.setValues(0, len(flat), flat)
        # points only for a lattice of lone balls (all of them: a mask cannot thin an SoPointSet's prefix)
        self.points.numPoints = 0 if len(a) else (len(points) if ball_mask is None else 0)
        self.drawn_beams = len(a)
        self.seconds = time.perf_counter() - start
        return self.drawn_beams
