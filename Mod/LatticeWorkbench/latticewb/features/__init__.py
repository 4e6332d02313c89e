"""App-side document objects of the workbench (no GUI needed)."""
