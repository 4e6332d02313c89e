"""make_* functions: create a document object, and attach its view provider when the GUI is up."""
