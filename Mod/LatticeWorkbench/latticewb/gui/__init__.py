"""GUI side of the workbench: commands and view providers (imported only when the GUI is up)."""
