"""Slices through the Python module: each layer equals point membership at every pixel center (the slow twin),
and the PNG layers read back by Pillow (an independent PNG decoder) equal the bitmaps."""
import os

import numpy as np
import pytest

import steadylattice as sl
from test_mesh import dense_octet


def test_layer_equals_point_membership_at_every_pixel():
    lat = dense_octet(ratio=0.7)
    for z in (0.35, 1.0, 2.63, 4.9):
        image, (x0, y0) = lat.slice(z, 0.02)
        h, w = image.shape
        xs = x0 + (np.arange(w) + 0.5) * 0.02
        ys = y0 + (np.arange(h) + 0.5) * 0.02
        X, Y = np.meshgrid(xs, ys)
        points = np.stack([X.ravel(), Y.ravel(), np.full(X.size, z)], axis=1)
        assert np.array_equal(image.astype(bool), lat.contains(points).reshape(h, w))
        assert image.sum() > 1000


def test_png_layers_read_back_by_pillow(tmp_path):
    from PIL import Image
    lat = dense_octet(ratio=0.6, counts=(2, 2, 2))
    stats = {}
    lat.write_slices(str(tmp_path), layer_height=0.2, pixel_size=0.025, svg=True, stats=stats)
    names = sorted(os.listdir(tmp_path))
    assert len([n for n in names if n.endswith(".png")]) == stats["layers"]
    assert len([n for n in names if n.endswith(".svg")]) == stats["layers"]
    k = stats["layers"] // 2
    with Image.open(tmp_path / ("layer_%05d.png" % k)) as png:
        assert png.size == (stats["width"], stats["height"]) and png.mode == "1"
        pixels = np.array(png, dtype=bool)[::-1]  # the file's first row is the highest y
    # the same layer from slice(): layer k is at z_min + (k + 1/2) layer_height of the box grown by a pixel
    centers, radii = lat.balls()
    z_min = (centers[:, 2] - radii).min() - 0.025
    image, _ = lat.slice(z_min + (k + 0.5) * 0.2, 0.025)
    assert pixels.shape == image.shape
    assert np.array_equal(pixels, image.astype(bool))


def test_bad_input_names_the_parameter(tmp_path):
    lat = dense_octet(ratio=0.6, counts=(1, 1, 1))
    with pytest.raises(ValueError, match="pixel_size"):
        lat.slice(1.0, 0.0)
    with pytest.raises(ValueError, match="layer_height"):
        lat.write_slices(str(tmp_path), -0.1, 0.05)
    with pytest.raises(ValueError, match="path"):
        lat.write_slices(str(tmp_path / "missing"), 0.1, 0.05)
    with pytest.raises(MemoryError):
        lat.slice(1.0, 1e-9)
    # progress is reported about every 0.1 s: a stack that takes longer than that, cancelled at its first report
    with pytest.raises(sl.Cancelled):
        dense_octet(ratio=0.6, counts=(4, 4, 4)).write_slices(str(tmp_path), 0.005, 0.005, progress=lambda f: False)
    assert os.listdir(tmp_path) == []
