"""qverify.shadow and qverify.check_shadow: real properties of the unit sphere's shadow."""
import threading
from fractions import Fraction

import numpy as np
import pytest

import qverify
from conftest import cone_reference, positive_factor, sphere_at


def test_unit_sphere_shadow_is_the_cone_from_the_light(sphere, light):
    s = qverify.shadow(sphere, light)
    assert isinstance(s, qverify.ShadowResult)
    assert s.status == "ok" and s.flags == [] and s.origin is None
    for M, shape in ((s.P, (4, 4)), (s.polar_plane, (4,)), (s.R, (4, 4))):
        assert isinstance(M, np.ndarray) and M.dtype == np.float64 and M.shape == shape
    # integer data: the double result is exact, a positive multiple of (L^T A L) A - (A L)(A L)^T
    ref = cone_reference(sphere.astype(int).tolist(), light.astype(int).tolist())
    assert positive_factor(s.P.tolist(), ref) is not None
    assert np.allclose(s.P @ light, 0)  # the light is the apex
    assert positive_factor(s.polar_plane.tolist(), [3, 4, 8, -1]) is not None  # A L
    assert np.allclose(s.R, s.R.T)
    assert s.error_bound is not None and 0 <= s.error_bound <= 1e-9
    assert s.precision == "double" and s.method == "direct"
    assert s.item["status"] == "ok" and "P" in s.item
    assert "ShadowResult(status='ok'" in repr(s)


def test_check_passes_for_qverify_result(sphere, light):
    s = qverify.shadow(sphere, light)
    rep = qverify.check_shadow(sphere, light, P=s.P, polar_plane=s.polar_plane, R=s.R, samples=64, seed=1,
                               accuracy=1e-9)
    assert isinstance(rep, qverify.CheckReport)
    assert rep.passed and bool(rep) and rep.problems == []
    assert not rep.exact and rep.kind == "shadow" and rep.exact_status == "ok"
    assert rep.points == 64
    assert rep.geometric_error <= 1e-9
    assert rep.object_size == pytest.approx(1.0)
    names = {c["name"] for c in rep.checks}
    assert {"on_P", "on_polar_plane", "on_R", "on_generators"} <= names
    for c in rep.checks:
        assert set(c) >= {"name", "geometric_error", "passed", "max_distance", "max_residual", "worst", "worst_approx"}
        assert isinstance(c["geometric_error"], float)
    assert isinstance(rep.summary, str) and rep.summary
    # a sphere: P, the polar plane and R are also bounded at every point of the terminator (R also on the
    # polar plane inside it); P's generator lines are a check of its shape, on samples (on_generators)
    assert rep.certified["results"] == ["P", "polar_plane", "R"]
    assert 0 <= rep.certified["geometric_error_attained"] <= rep.certified["geometric_error_bound"] <= 1e-9


def test_check_fails_for_perturbed_P(sphere, light):
    s = qverify.shadow(sphere, light)
    P = s.P.copy()
    delta = 1e-6 * np.abs(P).max()
    P[0, 1] += delta
    P[1, 0] += delta
    rep = qverify.check_shadow(sphere, light, P=P, polar_plane=s.polar_plane, R=s.R)
    assert not rep.passed and not bool(rep)
    assert rep.problems
    assert rep.geometric_error > 1e-9
    assert rep.certified["geometric_error_attained"] > 1e-9  # certainly off, at some point of the terminator
    worst = [c for c in rep.checks if not c["passed"]]
    assert worst and worst[0]["worst_approx"] is not None
    assert "FAILED" in repr(rep)


def test_check_fails_for_wrong_sign_of_the_rank_one_term(sphere, light):
    A, L = sphere, light
    AL = A @ L
    wrong = (L @ AL) * A + np.outer(AL, AL)  # + instead of -
    rep = qverify.check_shadow(A, L, P=wrong)
    assert not rep.passed
    right = (L @ AL) * A - np.outer(AL, AL)
    assert qverify.check_shadow(A, L, P=right).passed


def test_check_fails_for_negated_polar_plane(sphere, light):
    s = qverify.shadow(sphere, light)
    assert not qverify.check_shadow(sphere, light, polar_plane=-s.polar_plane).passed


def test_exact_precision_gives_fractions_and_a_proof(sphere, light):
    s = qverify.shadow(sphere, light, precision="exact")
    assert s.precision == "exact" and s.error_bound == 0
    for M in (s.P, s.R):
        assert isinstance(M, list) and len(M) == 4 and all(len(r) == 4 for r in M)
        assert all(isinstance(x, Fraction) for r in M for x in r)
    assert all(isinstance(x, Fraction) for x in s.polar_plane)
    assert positive_factor(s.P, cone_reference(sphere.astype(int).tolist(), light.astype(int).tolist())) is not None
    rep = qverify.check_shadow(sphere, light, P=s.P, polar_plane=s.polar_plane, R=s.R)
    assert rep.exact and rep.passed and rep.proved_exactly > 0
    assert rep.reference is not None and isinstance(rep.reference[0][0], Fraction)


def test_exact_proof_fails_for_a_rounded_cone():
    # a sphere of radius 1/3 with a light at (1/10, 2/7, 3): the exact cone has non-dyadic entries,
    # so any double P is off the exact terminator by a tiny but non-zero amount
    A = sphere_at([0, 0, 0], Fraction(1, 3))
    L = [Fraction(1, 10), Fraction(2, 7), 3, 1]
    exact = qverify.shadow(A, L, precision="exact")
    assert qverify.check_shadow(A, L, P=exact.P, polar_plane=exact.polar_plane, R=exact.R).passed
    P_double = [[float(x) for x in row] for row in exact.P]
    floating = qverify.check_shadow(A, L, P=P_double)
    assert floating.passed and not floating.exact  # a floating candidate is judged by the accuracy target
    proof = qverify.check_shadow(A, L, P=P_double, exact=True)
    assert proof.exact and not proof.passed


def test_inputs_of_every_kind_give_the_same_exact_result():
    A_float = np.diag([1.0, 1.0, 1.0, -1.0])
    forms = [
        A_float,
        A_float.astype(np.float32),
        A_float.astype(int),
        np.array([[Fraction(int(x)) for x in row] for row in A_float], dtype=object),
        [[str(int(x)) for x in row] for row in A_float],
        [[int(x) for x in row] for row in A_float],
    ]
    L_forms = [np.array([3.0, 4.0, 8.0, 1.0]), [3, 4, 8, 1], ["3", "4.0", "8/1", "1"], [Fraction(3), 4, 8.0, 1]]
    results = {repr(qverify.shadow(A, L, precision="exact").P) for A in forms for L in L_forms}
    assert len(results) == 1


def test_a_float_is_its_exact_binary_value():
    A = np.diag([1.0, 1.0, 1.0, -1.0])
    by_float = qverify.shadow(A, [0.1, 0, 3, 1], precision="exact")
    by_text = qverify.shadow(A, ["0.1", 0, 3, 1], precision="exact")
    assert by_text.polar_plane[0] == Fraction(1, 10)
    assert by_float.polar_plane[0] == Fraction(0.1) != Fraction(1, 10)


def test_parallel_light_and_negative_w(sphere):
    sun = np.array([0.0, 0.0, 1.0, 0.0])  # travelling along (0, 0, -1)
    s = qverify.shadow(sphere, sun)
    assert s.status == "ok"
    assert qverify.check_shadow(sphere, sun, P=s.P, polar_plane=s.polar_plane, R=s.R).passed
    L = np.array([-3.0, -4.0, -8.0, -1.0])  # the point (3, 4, 8) with w = -1
    s = qverify.shadow(sphere, L)
    assert positive_factor(s.polar_plane.tolist(), (sphere @ L).tolist()) is not None
    assert qverify.check_shadow(sphere, L, P=s.P, polar_plane=s.polar_plane, R=s.R).passed


@pytest.mark.parametrize("precision", ["float", "double", "long-double", "float128", "mpfr:128", "interval", "exact"])
@pytest.mark.parametrize("method", ["direct", "paper"])
def test_every_precision_and_method_passes_its_check(precision, method):
    A = sphere_at([1, 2, 3], 2)
    L = [4, 5, 9, 1]
    s = qverify.shadow(A, L, precision=precision, method=method)
    assert s.status == "ok" and s.precision == precision and s.method == method
    if precision == "exact":
        assert isinstance(s.P[0][0], Fraction)
    else:
        assert s.P.dtype == np.float64
    rep = qverify.check_shadow(A, L, P=s.P, polar_plane=s.polar_plane, R=s.R, origin=s.origin, method=method)
    # eval's flag and the check agree: float by the paper's route misses 1e-9 (and says so)
    assert rep.passed == ("inaccurate" not in s.flags), rep.summary
    assert rep.passed or (precision, method) == ("float", "paper")


def test_far_object_local_frame_and_world_frame():
    A = sphere_at([1e7 + 0.5, 0, 0], Fraction(1, 1000))
    L = [1e7, 1, 2, 1]
    s = qverify.shadow(A, L, frame="local")
    assert s.origin is not None and s.frame == "local"
    assert qverify.check_shadow(A, L, P=s.P, polar_plane=s.polar_plane, R=s.R, origin=s.origin).passed
    # the same matrices read in world coordinates are wrong
    assert not qverify.check_shadow(A, L, P=s.P, polar_plane=s.polar_plane, R=s.R).passed
    # by default the results are in world coordinates, where no double matrix holds this object
    # (1e10 radii from the origin): rounded once from the local ones, and flagged, as the check agrees
    w = qverify.shadow(A, L)
    assert w.origin is None and w.frame == "world" and "inaccurate" in w.flags
    assert not qverify.check_shadow(A, L, P=w.P, polar_plane=w.polar_plane, R=w.R).passed


def test_wider_precisions_do_not_overflow_float64():
    # a result that float128 holds but float64 does not (entries 1e400): the projective results are
    # returned scaled by a power of two, finite, and still pass their check
    A = np.diag([1.0, 1, 1, -1]) * 1e200
    for precision in ("float128", "mpfr:128"):
        s = qverify.shadow(A, LIGHT4, precision=precision)
        assert s.flags == [] and np.all(np.isfinite(s.P)) and np.all(np.isfinite(s.R)), (precision, s)
        assert qverify.check_shadow(A, LIGHT4, P=s.P, polar_plane=s.polar_plane, R=s.R).passed
    # M is M itself (never scaled): beyond float64's range it is flagged
    r = qverify.reflection(np.diag([1.0, 1, 1, -1]), [0, 0, 1, "-1e400"], precision="float128")
    assert "non-finite" in r.flags and np.all(np.isfinite(r.B))


LIGHT4 = [3.0, 4.0, 8.0, 1.0]


@pytest.mark.parametrize("centre", [[100.3, -7.1, 0.2], [0.1, 700.7, 3.3]])
def test_default_results_are_in_world_coordinates(centre):
    # The contract's flow, shadow() then check_shadow() of its arrays with no origin, on objects far
    # enough from the world origin (about 130 and 930 radii) for the robust path to use local frames.
    # (Far beyond, no double matrix in world coordinates holds the object: the test above.)
    A = sphere_at(centre, Fraction(3, 4))
    for L in ([centre[0] + 5, centre[1] - 2, centre[2] + 9, 1], [1, 0.5, -2, 0]):
        s = qverify.shadow(A, L)
        assert s.origin is None and s.frame == "world" and s.flags == [], s
        assert qverify.shadow(A, L, frame="local").origin is not None
        rep = qverify.check_shadow(A, L, P=s.P, polar_plane=s.polar_plane, R=s.R)
        assert rep.passed and rep.geometric_error <= s.error_bound, rep.summary
        # P is the textbook cone up to a positive factor: compare up to scale with the same formula in
        # plain doubles, entry by entry relative to the largest
        Ad, Ld = np.asarray(A, dtype=float), np.asarray(L, dtype=float)
        P0 = (Ld @ Ad @ Ld) * Ad - np.outer(Ad @ Ld, Ad @ Ld)
        k = np.unravel_index(np.argmax(abs(P0)), P0.shape)
        assert np.allclose(s.P / s.P[k], P0 / P0[k], rtol=0, atol=1e-6)


def test_special_statuses(sphere):
    inside = qverify.shadow(sphere, [0.25, 0, 0, 1])
    assert inside.status == "no-real-silhouette" and inside.error_bound is None and inside.reason
    on = qverify.shadow(sphere, [1, 0, 0, 1])
    assert on.status == "light-on-surface"
    flat = qverify.shadow(np.diag([1.0, 1.0, 0.0, 0.0]), [3, 4, 8, 1])
    assert flat.status == "degenerate-quadric"
    paper = qverify.shadow(sphere, [3, 4, 0, 1], method="paper")
    assert "singular-frame" in paper.flags and paper.fallback
    rep = qverify.check_shadow(sphere, [0.25, 0, 0, 1], P=inside.P)
    assert rep.skipped and rep.exact_status == "no-real-silhouette"
    # nothing judged: no error (verify's JSON writes none), not a perfect 0.0
    assert rep.geometric_error is None and not rep.passed and "skipped" in repr(rep)


def test_judge_without_points_gives_a_verdict_where_verify_skips(sphere):
    # a lamp inside the sphere: no real terminator point. judge_without_points=True judges the results
    # as matrices against the exact ones (as the C++ test matchers do): right passes, wrong fails
    inside = [0.25, 0, 0, 1]
    s = qverify.shadow(sphere, inside)
    rep = qverify.check_shadow(sphere, inside, P=s.P, polar_plane=s.polar_plane, R=s.R, judge_without_points=True)
    assert rep.passed and not rep.skipped, rep.summary
    off = s.P.copy()
    off[0, 1] = off[1, 0] = 1e-6
    rep = qverify.check_shadow(sphere, inside, P=off, judge_without_points=True)
    assert not rep.passed and not rep.skipped and "judged as matrices" in rep.summary
    reps = qverify.check_shadows(sphere, inside, P=np.stack([s.P, off]), judge_without_points=True)
    assert [r.passed for r in reps] == [True, False]
    imaginary = np.eye(4)  # x^2 + y^2 + z^2 + 1 = 0
    r = qverify.reflection(imaginary, [0, 0, 1, 2])
    assert qverify.check_reflection(imaginary, [0, 0, 1, 2], M=r.M, B=r.B).skipped
    assert qverify.check_reflection(imaginary, [0, 0, 1, 2], M=r.M, B=r.B, judge_without_points=True).passed
    assert not qverify.check_reflections(imaginary, [0, 0, 1, 2], B=imaginary, judge_without_points=True)[0].passed
    with pytest.raises(qverify.InputError) as e:
        qverify.check_shadow(sphere, inside, P=s.P, judge_without_points=1)
    assert e.value.path == "judge_without_points"


def test_a_wrong_status_fails(sphere, light):
    s = qverify.shadow(sphere, light)
    assert qverify.check_shadow(sphere, light, P=s.P, status="ok").passed
    assert not qverify.check_shadow(sphere, light, P=s.P, status="light-on-surface").passed


def test_calls_in_threads_agree(sphere, light):
    """The GIL is released in the computation: concurrent calls (mpfr at different widths too) agree."""
    expected = {}
    for precision in ("double", "exact", "mpfr:64", "mpfr:300"):
        expected[precision] = repr(qverify.shadow(sphere, light, precision=precision).P)
    got, errors = [], []

    def work(precision):
        try:
            for _ in range(3):
                got.append((precision, repr(qverify.shadow(sphere, light, precision=precision).P)))
                assert qverify.check_shadow(sphere, light, P=qverify.shadow(sphere, light).P).passed
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(p,)) for p in expected for _ in range(2)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors
    assert len(got) == 3 * len(threads)
    assert all(expected[p] == r for p, r in got)


def test_gil_is_released_during_a_long_check():
    """Another Python thread runs while a long exact check is computing."""
    A = sphere_at([0, 0, 0], Fraction(1, 3))
    L = [Fraction(1, 10), Fraction(2, 7), 3, 1]
    s = qverify.shadow(A, L, precision="exact")
    ticks = []
    done = threading.Event()

    def ticker():
        while not done.is_set():
            ticks.append(1)
            done.wait(0.001)

    t = threading.Thread(target=ticker)
    t.start()
    try:
        while not ticks:  # the ticker runs
            done.wait(0.001)
        before = len(ticks)
        rep = qverify.check_shadow(A, L, P=s.P, polar_plane=s.polar_plane, R=s.R, samples=2000)
        during = len(ticks) - before  # a call holding the GIL would let the ticker run at most once
    finally:
        done.set()
        t.join()
    assert rep.passed
    assert during >= 10


@pytest.mark.parametrize("kwargs", [{"precision": "interval"}, {"method": "paper"}])
def test_an_overflowed_result_keeps_the_exact_status(kwargs):
    # a light at 1e200: interval arithmetic and the paper's frame overflow double, exact says "ok"
    unit = np.diag([1.0, 1.0, 1.0, -1.0])
    far = [1e200, 2e200, 3e200, 1]
    assert qverify.shadow(unit, far, precision="exact").status == "ok"
    r = qverify.shadow(unit, far, **kwargs)
    assert r.status == "ok"
    assert "non-finite" in r.flags and "inaccurate" in r.flags
    assert r.error_bound is None and r.reason


def test_a_parallel_lights_second_plane_is_judged_where_the_terminator_is():
    # Under a parallel light R's second plane (the plane at infinity) was judged at the core point
    # nearest the candidate's origin: a cylinder's R whose second plane z = 1 crosses the terminator
    # passed with its origin put 1e12 up the axis (review of 29fa6a5). It fails at every origin.
    F = Fraction
    A = [[F(1), 0, 0, 0], [0, F(1), 0, 0], [0, 0, 0, 0], [0, 0, 0, F(-1)]]
    L = [F(1), F(0), F(0), F(0)]
    pi = [F(1), F(0), F(0), F(0)]       # A L: the plane x = 0
    h = [F(0), F(0), F(1), F(-1)]       # z = 1, through the terminator (the lines x = 0, y = +-1)
    R = [[pi[i] * h[j] + h[i] * pi[j] for j in range(4)] for i in range(4)]
    for o in ([0, 0, 0], [0, 0, 10**12], [0, 0, -(10**12)], [5, 7, 10**6]):
        T = [[F(int(i == j)) for j in range(4)] for i in range(4)]
        for i in range(3):
            T[i][3] = F(o[i])
        RT = [[sum(R[i][k] * T[k][j] for k in range(4)) for j in range(4)] for i in range(4)]
        local = [[float(sum(T[k][i] * RT[k][j] for k in range(4))) for j in range(4)] for i in range(4)]
        rep = qverify.check_shadow(A, L, R=local, origin=o)
        assert not rep.passed, o
        assert any("plane h" in p for p in rep.problems), (o, rep.problems)
