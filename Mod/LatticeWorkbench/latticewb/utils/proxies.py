"""What the Python proxies of the workbench's document objects and view providers share."""


class StatelessProxy:
    """Everything lives in the object's properties: the proxy saves nothing, so documents move between FreeCAD
    versions and between versions of the workbench. FreeCAD >= 0.21 calls dumps/loads, 0.20 the pickle names."""

    def dumps(self):
        return None

    def loads(self, state):
        return None

    __getstate__ = dumps
    __setstate__ = loads


def add_missing_properties(obj, table):
    """Adds the properties of `table` [(type, name, group, tooltip)] that obj lacks (a new object, or one from a
    document of an older version) and returns their names, so that the caller sets defaults for those only."""
    fresh = {name for _, name, _, _ in table if name not in obj.PropertiesList}
    for kind, name, group, tip in table:
        if name in fresh:
            obj.addProperty(kind, name, group, tip)
    return fresh
