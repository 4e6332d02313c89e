"""The bottom layer: what every other layer may use (type tags, proxies' persistence, progress, resources)."""
