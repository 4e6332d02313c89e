"""View providers (GUI): icons, the scalable preview and display defaults of the workbench's objects."""
