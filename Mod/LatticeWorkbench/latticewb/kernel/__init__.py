"""Turning document objects into kernel lattices, parts and files: the layer between FreeCAD's objects and the
steadylattice module. It reads objects' properties and calls the kernel; it knows nothing of proxies' callbacks,
view providers or commands."""
