"""The Similarity API of the module: constructors against hand values, powers, frames, bad input."""
import math

import numpy as np
import pytest

import steadylattice as sl
from conftest import random_similarity


def test_constructors_match_hand_values():
    z = (0, 0, 1)
    assert np.allclose(sl.Similarity.rotation(math.pi / 2, z, (1, 0, 0)).apply((0, 0, 0)), (1, -1, 0))
    assert np.allclose(sl.Similarity.translation((1, 2, 3)).apply((1, 1, 1)), (2, 3, 4))
    assert np.allclose(sl.Similarity.dilation(2.0, (1, 1, 1)).apply((2, 1, 1)), (3, 1, 1))
    assert np.allclose(sl.Similarity.screw(math.pi, z, (1, 0, 0), 5.0).apply((0, 0, 0)), (2, 0, 5))
    s = sl.Similarity.swirl(math.pi / 2, z, (1, 1, 0), 3.0)
    assert np.allclose(s.apply((2, 1, 0)), (1, 4, 0))
    assert s.scale == pytest.approx(3.0)
    assert s.kind == "swirl"
    assert np.allclose(s.point, (1, 1, 0))
    assert sl.Similarity.identity().kind == "identity"
    assert sl.Similarity.translation((1, 0, 0)).kind == "translation"
    assert sl.Similarity.rotation(1.0, z).kind == "rotation"
    assert sl.Similarity.screw(1.0, z, (0, 0, 0), 1.0).kind == "screw"
    assert sl.Similarity.dilation(2.0).kind == "dilation"


def test_apply_is_vectorised_and_keeps_shape():
    s = sl.Similarity.swirl(0.3, (0, 1, 1), (1, 2, 3), 1.2)
    pts = np.random.default_rng(0).uniform(-5, 5, size=(1000, 3))
    out = s.apply(pts)
    assert out.shape == (1000, 3)
    m = s.matrix
    expected = pts @ m[:3, :3].T + m[:3, 3]
    assert np.abs(out - expected).max() < 1e-12
    assert s.apply(pts[0]).shape == (3,)


def test_powers_compose_and_invert(rng):
    worst = 0.0
    for trial in range(600):
        s = random_similarity(rng, trial)
        a, b = rng.uniform(-3, 3, size=2)
        pts = rng.uniform(-3, 3, size=(8, 3))
        worst = max(worst, np.abs((s.power(a) * s.power(b)).apply(pts) - s.power(a + b).apply(pts)).max())
        assert np.abs((s * s.inverse()).apply(pts) - pts).max() < 1e-11
        n = 1 + trial % 9
        root = s.power(1.0 / n)
        repeated = sl.Similarity.identity()
        for _ in range(n):
            repeated = repeated * root
        assert np.abs(repeated.apply(pts) - s.apply(pts)).max() < 1e-9
    assert worst < 1e-9


def test_composition_applies_right_operand_first():
    s = sl.Similarity.rotation(math.pi / 2, (0, 0, 1))
    t = sl.Similarity.translation((1, 0, 0))
    assert np.allclose((s * t).apply((0, 0, 0)), (0, 1, 0))
    assert np.allclose((t * s).apply((0, 0, 0)), (1, 0, 0))


def test_from_frames_recovers_random_similarities(rng):
    for trial in range(300):
        s = random_similarity(rng, trial)
        place = random_similarity(rng, 5)
        a = place.frame()
        b = (s * place).frame()
        r = sl.Similarity.from_frames(a, b)
        pts = rng.uniform(-3, 3, size=(5, 3))
        assert np.abs(r.apply(pts) - s.apply(pts)).max() < 1e-9
        assert r.angle <= math.pi + 1e-12


def test_from_frames_failure_cases_of_the_paper():
    unit = ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1))
    axis = np.array([1.0, -1.0, 0.0]) / math.sqrt(2)  # orthogonal to I + J + K
    truth = sl.Similarity.swirl(0.7, axis, (0.3, 0.2, 0.1), 1.2)
    r = sl.Similarity.from_frames(unit, truth.frame())
    assert np.allclose(r.angle * r.axis, 0.7 * axis, atol=1e-14)
    neg = sl.Similarity.from_frames(unit, sl.Similarity.rotation(-0.7, (0, 0, 1)).frame())
    assert np.allclose(neg.angle * neg.axis, (0, 0, -0.7), atol=1e-15)


def test_fractional_power_oracle():
    total = sl.Similarity.swirl(math.pi / 2, (0, 0, 1), (0, 0, 0), 8.0)
    step = total.power(1 / 3)
    assert step.scale == pytest.approx(2.0, rel=1e-15)
    assert step.angle == pytest.approx(math.pi / 6, rel=1e-14)
    assert np.allclose(step.apply((1, 0, 0)), (math.sqrt(3), 1, 0), atol=1e-15)


def test_windings_are_kept():
    half = sl.Similarity.rotation(3 * math.pi, (0, 0, 1), (1, 0, 0)).power(1 / 3)
    assert np.allclose(half.apply((0, 0, 0)), (2, 0, 0), atol=1e-14)


def test_json_round_trip_of_a_similarity():
    s = sl.Similarity.screw(7.0, (0, 1, 0), (1, 2, 3), 0.5)
    t = sl.Similarity.from_json(s.to_json())
    assert t.generator[0] == s.generator[0]
    assert np.array_equal(t.generator[1], s.generator[1]) and np.array_equal(t.generator[2], s.generator[2])


def test_from_matrix_round_trip():
    s = sl.Similarity.swirl(1.1, (1, 2, 3), (0, 1, 0), 0.8)
    assert sl.Similarity.from_matrix(s.matrix).approx_equal(s, 1e-12)
    with pytest.raises(ValueError, match="matrix"):
        sl.Similarity.from_matrix(np.diag([1.0, 1.0, -1.0, 1.0]))


def test_similarity2_point_pairs():
    s = sl.Similarity2.from_point_pairs((0, 0), (1, 0), (2, 2), (2, 4))
    assert np.allclose(s.apply((0, 0)), (2, 2)) and np.allclose(s.apply((1, 0)), (2, 4))
    assert s.scale == pytest.approx(2.0) and s.angle == pytest.approx(math.pi / 2)
    assert s.kind == "spiral"
    root = s.power(0.5)
    assert np.allclose((root * root).apply((3, -1)), s.apply((3, -1)))
    with pytest.raises(ValueError, match="distinct"):
        sl.Similarity2.from_point_pairs((1, 1), (1, 1), (0, 0), (1, 0))


@pytest.mark.parametrize("call, field", [
    (lambda: sl.Similarity.rotation(1.0, (0, 0, 0)), "rotation.axis"),
    (lambda: sl.Similarity.dilation(-1.0), "dilation.scale"),
    (lambda: sl.Similarity.swirl(1.0, (0, 0, 1), (0, 0, 0), 0.0), "swirl.scale"),
    (lambda: sl.Similarity.translation((float("nan"), 0, 0)), "v"),
    (lambda: sl.Similarity.translation((1, 2)), "v"),
    (lambda: sl.Similarity.identity().power(float("inf")), "power exponent"),
    (lambda: sl.Similarity.identity().apply([[0, 0, float("nan")]]), "points"),
    (lambda: sl.Similarity.identity().apply([[0, 0]]), "points"),
    (lambda: sl.Similarity.from_frames(((0, 0, 0), (1, 0, 0), (0, 2, 0), (0, 0, 1)),
                                       ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1))), "a"),
    (lambda: sl.Similarity.from_frames(((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, -1)),
                                       ((0, 0, 0), (1, 0, 0), (0, 1, 0), (0, 0, 1))), "right-handed"),
])
def test_bad_input_is_a_value_error_naming_the_parameter(call, field):
    with pytest.raises(ValueError, match=field.replace(".", r"\.")):
        call()
