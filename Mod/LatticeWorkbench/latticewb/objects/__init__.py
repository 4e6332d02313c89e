"""App-side document objects (proxies) of the workbench: usable from freecadcmd, no GUI."""
