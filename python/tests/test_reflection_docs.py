"""qverify.reflection / check_reflection, and the documentation of the module."""
import inspect
from fractions import Fraction

import numpy as np

import qverify
from conftest import positive_factor, sphere_at


def test_reflection_of_a_ball_in_the_floor():
    A = sphere_at([1, 2, 3], 1)
    r = qverify.reflection(np.array(A, dtype=object), np.array([0.0, 0.0, 1.0, 0.0]))
    assert isinstance(r, qverify.ReflectionResult)
    assert r.status == "ok" and r.flags == []
    assert np.array_equal(r.M, np.diag([1.0, 1.0, -1.0, 1.0]))
    assert positive_factor(r.B.tolist(), sphere_at([1, 2, -3], 1)) is not None
    rep = qverify.check_reflection(A, [0, 0, 1, 0], M=r.M, B=r.B)
    assert rep.passed and rep.kind == "reflection" and rep.M_error == 0
    exact = qverify.reflection(A, [0, 0, 1, 0], precision="exact")
    assert isinstance(exact.B[0][0], Fraction)
    assert qverify.check_reflection(A, [0, 0, 1, 0], M=exact.M, B=exact.B).exact


def test_check_reflection_fails_for_wrong_results():
    A = sphere_at([1, 2, 3], 1)
    plane = [0, 0, 1, 0]
    r = qverify.reflection(A, plane)
    B = r.B.copy()
    B[2, 3] = B[3, 2] = B[2, 3] * (1 + 1e-6)
    assert not qverify.check_reflection(A, plane, B=B).passed
    M = r.M.copy()
    M[2, 3] = 1e-6
    assert not qverify.check_reflection(A, plane, M=M).passed
    assert not qverify.check_reflection(A, plane, B=-r.B).passed  # the image's sign matters


def test_default_reflection_is_in_world_coordinates():
    # an image far from the world origin: computed in a local frame, given in world coordinates
    A = sphere_at([300.1, -2.3, 400.7], Fraction(1, 1))
    plane = [0.6, 0, 0.8, -900.3]  # the image about 1300 radii away
    r = qverify.reflection(A, plane)
    assert r.origin is None and r.frame == "world" and r.flags == []
    assert qverify.reflection(A, plane, frame="local").origin is not None
    assert np.array_equal(r.M[3], [0, 0, 0, 1])
    n, d = np.array(plane[:3]), plane[3]
    M = np.eye(4)
    M[:3, :3] -= 2 * np.outer(n, n) / (n @ n)
    M[:3, 3] = -2 * d * n / (n @ n)
    assert np.allclose(r.M, M, rtol=0, atol=1e-12)
    assert qverify.check_reflection(A, plane, M=r.M, B=r.B).passed


def test_a_far_mirror_gives_the_reflection_itself():
    # M is never scaled like a projective result: a mirror 1e20 away keeps the last row 0 0 0 1
    A, plane = np.diag([1.0, 1, 1, -1]), [0, 0, 1, -1e20]
    r = qverify.reflection(A, plane)
    assert np.array_equal(r.M[3], [0, 0, 0, 1]) and r.M[2, 3] == 2e20
    assert qverify.check_reflection(A, plane, M=r.M).passed
    local = qverify.reflection(A, plane, frame="local")  # M in the image's frame (its centre, 2e20 up)
    assert np.array_equal(local.M[3], [0, 0, 0, 1]) and local.origin is not None
    assert qverify.check_reflection(A, plane, M=local.M, origin=local.origin).passed
    # (the image, 2e20 radii away, no world double matrix holds: flagged)
    assert "inaccurate" in qverify.reflection(A, plane).flags


def test_slanted_mirror_exact_plane():
    A = sphere_at([0, 0, 0], 1)
    plane = [Fraction(1, 3), Fraction(2, 3), Fraction(2, 3), -5]
    for precision in ("double", "exact"):
        r = qverify.reflection(A, plane, precision=precision)
        assert qverify.check_reflection(A, plane, M=r.M, B=r.B, origin=r.origin).passed


PUBLIC = ["shadow", "reflection", "check_shadow", "check_reflection", "eval_scene", "verify_scene"]
CLASSES = ["ShadowResult", "ReflectionResult", "CheckReport", "InputError"]


def test_every_public_name_has_a_docstring():
    assert qverify.__doc__ and "check_shadow" in qverify.__doc__
    for name in PUBLIC + CLASSES:
        doc = getattr(qverify, name).__doc__
        assert doc and len(doc) > 80, name
    for name in PUBLIC:
        assert "Args:" in inspect.getdoc(getattr(qverify, name)), name
    assert set(PUBLIC + CLASSES) <= set(qverify.__all__)


def test_help_of_check_shadow(capsys):
    help(qverify.check_shadow)
    text = capsys.readouterr().out
    for word in ("accuracy", "samples", "polar_plane", "CheckReport", "InputError"):
        assert word in text
    help(qverify.CheckReport)
    text = capsys.readouterr().out
    assert "geometric_error" in text and "summary" in text


def test_an_overflowed_reflection_keeps_the_exact_status():
    # a mirror plane of 1e-300 coefficients: interval, the paper's route and the world frame overflow double
    unit = np.diag([1.0, 1.0, 1.0, -1.0])
    plane = [1e-300, 0, 1e-300, -1e-300]
    assert qverify.reflection(unit, plane, precision="exact").status == "ok"
    for kwargs in ({"precision": "interval"}, {"method": "paper"}, {"frame": "world"}):
        r = qverify.reflection(unit, plane, **kwargs)
        assert r.status == "ok", kwargs
        assert "non-finite" in r.flags and "inaccurate" in r.flags, kwargs
        assert r.error_bound is None and r.reason, kwargs


def test_an_imaginary_quadric_reflected_must_stay_imaginary():
    # (x - c)^2 + y^2 + z^2 + 1/100 = 0 has no real point; float's paper route made its image a real
    # sphere of radius 5000, which was neither flagged nor failed (audit 38a F1)
    c = Fraction(10**8, 3) + Fraction(1, 7)
    A = np.array([[1, 0, 0, -c], [0, 1, 0, 0], [0, 0, 1, 0], [-c, 0, 0, c * c + Fraction(1, 100)]], dtype=object)
    plane = [0, 0, 1, -1]
    r = qverify.reflection(A, plane, precision="float", method="paper")
    eig = np.linalg.eigvalsh(np.array(r.B, dtype=float))
    real = eig.min() < 0 < eig.max()  # (by far: a sphere of radius 5000, or none)
    assert ("inaccurate" in r.flags) == real
    exact = qverify.reflection(A, plane, precision="exact")
    rep = qverify.check_reflection(A, plane, B=exact.B)
    assert rep.skipped and not rep.passed  # nothing to sample, nothing wrong
    B = np.array(exact.B, dtype=object)
    B[3, 3] -= 1  # |x - c'|^2 = 99/100: a real sphere
    rep = qverify.check_reflection(A, plane, B=B)
    assert not rep.passed and not rep.skipped
    assert any("B has real points" in p for p in rep.problems)
