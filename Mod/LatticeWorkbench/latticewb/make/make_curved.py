"""make_curved_lattice: a CurvedLattice (a BeCOTS lattice through four corners), and its view provider when the GUI
is up."""
import FreeCAD

from latticewb.kernel.curved_lattice import CONNECTIVITIES, CORNERS, MAX_TURNS
from latticewb.objects.curved_lattice import CurvedLattice


def make_curved_lattice(doc, corners=None, links=None, connectivity="triangle", cells=(8, 6), layers=1,
                        layer_raise=0.0, join_layers=True, node_radius=1.0, beam_ratio=0.5, turns=(0, 0),
                        layer_offset=0.0, face=None, name="CurvedLattice"):
    """Adds a CurvedLattice to `doc` and returns it (recompute the document to build it).

    corners: four points A = M(0,0), B = M(0,1), C = M(1,1), D = M(1,0) (FreeCAD vectors or triples), or None for
    the defaults; links: four (object, "VertexN") pairs (or (object, "") for a Draft point, or None for a typed
    corner) giving the corners instead; connectivity: "triangle", "kagome" or "honeycomb"; cells: groups (along U, along V); layers and
    layer_raise (mm along the field's axis) and layer_offset (mm along the sheet's normal at A); join_layers (beams between the layers); node_radius (mm, at corner
    A); beam_ratio: beam over node radius (0: hulls of the balls); face: (object, "FaceN") of a planar, cylindrical or
    conical face the lattice is laid on (corners projected onto it, layer_offset going into the body); turns: whole turns (TurnsU, TurnsV) added to
    the U and V sides, each the way that side already turns (negative: the other way round); a ring whose group
    falls exactly on the first is closed, its repeats left out. Bad values raise ValueError naming the parameter."""
    if connectivity not in CONNECTIVITIES:
        raise ValueError("connectivity: expected one of %s (got %r)" % (", ".join(CONNECTIVITIES), connectivity))
    if corners is not None and len(corners) != 4:
        raise ValueError("corners: expected four points A, B, C, D (got %d)" % len(corners))
    if links is not None and len(links) != 4:
        raise ValueError("links: expected four (object, vertex name) pairs for A, B, C, D (got %d)" % len(links))
    cells = tuple(cells)
    if len(cells) != 2 or not all(isinstance(c, int) and c >= 1 for c in cells):
        raise ValueError("cells: expected two counts >= 1 (got %r)" % (cells,))
    turns = tuple(turns)
    if len(turns) != 2 or not all(isinstance(t, int) and abs(t) <= MAX_TURNS for t in turns):
        raise ValueError("turns: expected two whole numbers of turns within +-%d (got %r)" % (MAX_TURNS, turns))
    if not (isinstance(layers, int) and layers >= 1):
        raise ValueError("layers: expected a count >= 1 (got %r)" % (layers,))
    obj = doc.addObject("Part::FeaturePython", name)
    CurvedLattice(obj)
    try:
        if corners is not None:
            for corner, p in zip(CORNERS, corners):
                setattr(obj, corner, FreeCAD.Vector(*p))
        if links is not None:
            for corner, link in zip(CORNERS, links):
                if link is not None:  # None: that corner stays typed
                    target, sub = link
                    setattr(obj, corner + "Link", (target, [sub] if sub else []))
        if face is not None:
            obj.FaceLink = (face[0], [face[1]])
        obj.Connectivity = connectivity
        obj.CellsU, obj.CellsV = cells
        obj.Layers = layers
        obj.TurnsU, obj.TurnsV = turns
        obj.LayerRaise = layer_raise
        obj.LayerOffset = layer_offset
        obj.JoinLayers = bool(join_layers)
        obj.NodeRadius = node_radius
        obj.BeamRatio = beam_ratio
    except Exception:
        doc.removeObject(obj.Name)
        raise
    if FreeCAD.GuiUp:
        from latticewb.viewproviders import view_providers
        view_providers.ViewProviderCurvedLattice(obj.ViewObject)
    return obj
