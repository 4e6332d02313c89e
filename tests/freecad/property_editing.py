"""What the nonsense-property tests share (test_nonsense_properties.py, test_nonsense_feature_properties.py): how a
refused value is told apart from the value put back, and the report view's warnings that name the property."""
import FreeCAD


def same(a, b):
    """Property values compared, NaN equal to NaN (a restored value must not compare equal to the nonsense)."""
    return repr(a) == repr(b)


class Warnings:
    """The report view's warnings while inside the block."""

    def __enter__(self):
        self.texts = []
        self._print = FreeCAD.Console.PrintWarning
        FreeCAD.Console.PrintWarning = self.texts.append
        return self

    def __exit__(self, *exc):
        FreeCAD.Console.PrintWarning = self._print
