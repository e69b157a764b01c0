"""The README's Python example ("Use it in your tests"), run as written between the markers."""


def test_readme_example():
    # --- README example begin
    import numpy as np
    import pytest
    import qverify

    A = np.diag([1.0, 1.0, 1.0, -1.0])  # the unit sphere x^2 + y^2 + z^2 = 1
    L = np.array([3.0, 4.0, 8.0, 1.0])  # a point light at (3, 4, 8)

    def my_shadow_cone(A, L):  # the code under test
        AL = A @ L
        return (L @ AL) * A - np.outer(AL, AL)

    rep = qverify.check_shadow(A, L, P=my_shadow_cone(A, L))
    assert rep.passed, rep.summary  # summary: which point, how far, the expected matrix

    wrong = qverify.check_shadow(A, L, P=my_shadow_cone(A, L) + 1e-6 * np.eye(4))
    assert not wrong.passed and wrong.geometric_error > 1e-9

    s = qverify.shadow(A, L, precision="exact")  # entries are fractions.Fraction
    proof = qverify.check_shadow(A, L, P=s.P, polar_plane=s.polar_plane, R=s.R)
    assert proof.exact and proof.passed  # every residual exactly zero

    with pytest.raises(qverify.InputError) as e:  # bad input: nothing is computed
        qverify.shadow(A[:3], L)
    assert e.value.path == "A"  # "A: expected a 4x4 matrix, found an array of shape (3, 4)"
    # --- README example end
