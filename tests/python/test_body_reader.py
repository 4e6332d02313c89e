"""Issue 16: bodies from outside (BREP text, STEP files) are read in a reader process of their own, so that the
inputs on which OpenCASCADE's own readers crash (SIGSEGV, found by tests/fuzz, kept in tests/fuzz/findings) give a
ValueError naming the parameter instead of ending the Python process; good bodies read as before."""
import os

import pytest

import steadylattice as sl

SOURCE = os.environ.get("STEADY_SOURCE_DIR", os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
FINDINGS = os.path.join(SOURCE, "tests", "fuzz", "findings")
DATA = os.path.join(os.path.dirname(os.path.abspath(__file__)), "data")


def text(path):
    with open(path, encoding="latin-1") as f:  # the fuzzed files hold bytes that are not UTF-8
        return f.read()


def cubic(n=3):
    t = sl.Similarity.translation
    beams = [(0, 1, 0, 0, 0, 0.1, 0.1), (0, 0, 1, 0, 0, 0.1, 0.1), (0, 0, 0, 1, 0, 0.1, 0.1)]
    return sl.Lattice([((0, 0, 0), 0.25)], beams, (n, n, n), t((1, 0, 0)), t((0, 1, 0)), t((0, 0, 1)))


CRASHING_BREP = os.path.join(FINDINGS, "brep_offset_curve_without_basis.brep")


@pytest.mark.parametrize("call,field", [
    (lambda t: sl.brep_properties(t), "text"),
    (lambda t: sl.InsideBody(t), "body"),
    (lambda t: cubic().brep(body=t), "body"),
], ids=["brep_properties", "InsideBody", "brep_body"])
def test_a_brep_text_that_crashes_the_reader_is_a_value_error(call, field):
    with pytest.raises(ValueError) as e:
        call(text(CRASHING_BREP))
    message = str(e.value)
    assert message.startswith(field + ": the BREP text crashed OpenCASCADE's BREP reader ("), message
    assert "it is corrupt" in message


def test_a_step_file_that_crashes_the_reader_is_a_value_error():
    path = os.path.join(FINDINGS, "step_edge_loop_check.step")
    with pytest.raises(ValueError) as e:
        sl.read_step(path)
    assert str(e.value).startswith("path: '%s' crashed OpenCASCADE's STEP reader (" % path), str(e.value)


def test_good_bodies_read_with_the_same_volume(tmp_path):
    cylinder = text(os.path.join(DATA, "cylinder.brep"))
    props = sl.brep_properties(cylinder)
    assert props["valid"] and props["solids"] == 1
    lat = cubic()
    stats = {}
    part = lat.brep(body=cylinder, stats=stats)
    assert sl.brep_properties(part)["volume"] == pytest.approx(stats["volume"], rel=1e-9)
    path = str(tmp_path / "part.step")
    lat.write_step(path, body=cylinder)
    parts = sl.read_step(path)
    assert [p["name"] for p in parts] == ["Lattice"]
    # Through STEP, curved faces come back within a few 1e-6 (docs/brep.md); the reader process changes nothing.
    assert parts[0]["volume"] == pytest.approx(stats["volume"], rel=1e-5)
    # The filter reads the same body: the nodes it keeps are those whose centres are inside the cylinder.
    kept = lat.filtered(sl.InsideBody(cylinder)).ball_mask()
    assert 0 < kept.sum() < len(kept)
