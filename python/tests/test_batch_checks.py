"""qverify.check_shadows / check_reflections: many items at once, each judged as if alone."""
from fractions import Fraction

import numpy as np
import pytest

import qverify
from conftest import sphere_at


def ellipsoids(n, seed=3):
    """n axis-aligned ellipsoids with random centres and radii (float64)."""
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        r = rng.uniform(0.5, 2.0, 3)
        c = rng.uniform(-5.0, 5.0, 3)
        D = np.diag(np.append(1.0 / r**2, -1.0))
        T = np.eye(4)
        T[:3, 3] = -c
        out.append(T.T @ D @ T)  # (x - c)^T diag(1/r^2) (x - c) = 1
    return np.array(out)


@pytest.fixture
def shadows():
    As = ellipsoids(12)
    Ls = np.array([[20.0 + k, -3.0, 15.0, 1.0] if k % 3 else [1.0, 2.0, -5.0, 0.0] for k in range(len(As))])
    res = [qverify.shadow(A, L) for A, L in zip(As, Ls)]
    return As, Ls, np.array([s.P for s in res]), np.array([s.polar_plane for s in res]), np.array([s.R for s in res])


def same_report(a, b):
    return (a.passed == b.passed and a.geometric_error == b.geometric_error and a.points == b.points
            and a.problems == b.problems and a.object_size == b.object_size
            and [c["name"] for c in a.checks] == [c["name"] for c in b.checks]
            and [c["worst"] for c in a.checks] == [c["worst"] for c in b.checks])


def test_each_report_is_the_one_its_item_gets_alone(shadows):
    As, Ls, Ps, polars, Rs = shadows
    Ps = Ps.copy()
    Ps[5, 0, 1] *= 1 + 1e-7  # item 5 is wrong (symmetry kept)
    Ps[5, 1, 0] = Ps[5, 0, 1]
    reps = qverify.check_shadows(As, Ls, P=Ps, polar_plane=polars, R=Rs, samples=32, seed=7)
    assert len(reps) == len(As) and all(isinstance(r, qverify.CheckReport) for r in reps)
    for k, rep in enumerate(reps):
        alone = qverify.check_shadow(As[k], Ls[k], P=Ps[k], polar_plane=polars[k], R=Rs[k], samples=32, seed=7)
        assert same_report(rep, alone), k
    assert [k for k, r in enumerate(reps) if not r] == [5]
    assert reps[5].geometric_error > 1e-9


def test_threads_do_not_change_the_reports(shadows):
    As, Ls, Ps, polars, Rs = shadows
    one = qverify.check_shadows(As, Ls, P=Ps, R=Rs, samples=16, threads=1)
    two = qverify.check_shadows(As, Ls, P=Ps, R=Rs, samples=16, threads=2)
    assert all(same_report(a, b) for a, b in zip(one, two))
    assert all(one)


def test_progress_counts_every_item_in_order(shadows):
    As, Ls, Ps, _, _ = shadows
    calls = []
    qverify.check_shadows(As, Ls, P=Ps, samples=8, threads=2, progress=lambda done, total: calls.append((done, total)))
    assert calls == [(k + 1, len(As)) for k in range(len(As))]


def test_an_exception_in_progress_reaches_the_caller(shadows):
    As, Ls, Ps, _, _ = shadows

    def stop(done, total):
        raise KeyError("stop here")

    with pytest.raises(KeyError, match="stop here"):
        qverify.check_shadows(As, Ls, P=Ps, samples=8, progress=stop)


def test_one_quadric_for_every_light(shadows):
    As, Ls, _, _, _ = shadows
    A = As[0]
    Ps = np.array([qverify.shadow(A, L).P for L in Ls])
    reps = qverify.check_shadows(A, Ls, P=Ps, samples=16)
    assert len(reps) == len(Ls) and all(reps)
    wrong = qverify.check_shadows(A, Ls, P=Ps[0], samples=16)  # the first light's cone for every light
    same_light = [bool(np.array_equal(L, Ls[0])) for L in Ls]
    assert [bool(r) for r in wrong] == same_light and same_light.count(False) >= 8


def test_reflections_match_their_single_checks():
    As = ellipsoids(8, seed=11)
    planes = np.array([[0.0, 0.0, 1.0, float(k)] if k % 2 else [1.0, -2.0, 0.5, 3.0] for k in range(len(As))])
    res = [qverify.reflection(A, p) for A, p in zip(As, planes)]
    Ms = np.array([r.M for r in res])
    Bs = np.array([r.B for r in res])
    Bs[2] = Bs[3]  # item 2 is given item 3's image
    reps = qverify.check_reflections(As, planes, M=Ms, B=Bs, samples=24, threads=2)
    for k, rep in enumerate(reps):
        assert same_report(rep, qverify.check_reflection(As[k], planes[k], M=Ms[k], B=Bs[k], samples=24)), k
    assert [k for k, r in enumerate(reps) if not r] == [2]


def test_exact_candidates_are_proofs():
    A = sphere_at([1, 2, 3], 2)
    Ls = [[9, 1, 1, 1], [Fraction(1, 3), 7, 2, 1]]
    Ps = [qverify.shadow(A, L, precision="exact").P for L in Ls]
    reps = qverify.check_shadows(A, Ls, P=Ps, samples=8)
    assert all(r.exact and r.passed and r.proved_exactly == 8 for r in reps)
    Ps[1][0][0] += Fraction(1, 10**30)
    assert not qverify.check_shadows(A, Ls, P=Ps, samples=8)[1]


def test_an_empty_batch_checks_nothing():
    assert qverify.check_shadows(np.zeros((0, 4, 4)), np.zeros((0, 4)), P=np.zeros((0, 4, 4))) == []


@pytest.mark.parametrize("change, path", [
    (lambda a: a["P"].__setitem__((7, 0, 1), np.nan), "P[7][0][1]"),
    (lambda a: a["A"].__setitem__((3, 0, 1), 5.0), "A[3][1][0]"),  # a pair named below the diagonal
    (lambda a: a["L"].__setitem__(4, np.zeros(4)), "L[4]"),
    (lambda a: a.__setitem__("L", a["L"][:5]), "L"),
    (lambda a: a.__setitem__("P", np.zeros((12, 3, 4))), "P[0]"),
    (lambda a: a.__setitem__("A", np.zeros((12, 4))), "A"),
    (lambda a: a.__setitem__("P", None), "P"),
    (lambda a: a.__setitem__("progress", 3), "progress"),
    (lambda a: a.__setitem__("threads", -1), "threads"),
    (lambda a: a.__setitem__("accuracy", 0.0), "accuracy"),
])
def test_bad_input_names_the_item_and_computes_nothing(shadows, change, path):
    As, Ls, Ps, _, _ = shadows
    calls = []
    args = {"A": As.copy(), "L": Ls.copy(), "P": Ps.copy(), "progress": lambda d, t: calls.append(d)}
    change(args)
    with pytest.raises(qverify.InputError) as err:
        qverify.check_shadows(args.pop("A"), args.pop("L"), samples=8, **args)
    assert err.value.path == path
    assert calls == []  # nothing was checked


def test_nested_lists_are_read_entry_by_entry_as_a_single_check_reads_them():
    A = sphere_at([1, 2, 3], 2)  # Fractions
    Ls = [[9, 1, 1, 1], [2**60 + 1, 0.5, 3, 1]]  # an int beyond a double's 53 bits beside a float
    exact_P = qverify.shadow(A, Ls[0], precision="exact").P  # Fractions: proof mode for item 0
    float_P = qverify.shadow(A, Ls[1]).P.tolist()               # floats: judged at the target for item 1
    reps = qverify.check_shadows(A, Ls, P=[exact_P, float_P], samples=8)
    assert reps[0].exact and not reps[1].exact
    for k, P in enumerate([exact_P, float_P]):
        assert same_report(reps[k], qverify.check_shadow(A, Ls[k], P=P, samples=8)), k


def test_a_ragged_list_names_its_item():
    A = sphere_at([0, 0, 0], 1)
    with pytest.raises(qverify.InputError) as err:
        qverify.check_shadows(A, [[3, 4, 8, 1], [3, 4, 8]], P=[np.eye(4), np.eye(4)])
    assert err.value.path == "L[1]"


def test_status_words_are_checked_item_by_item(shadows):
    # the batch doors took no status word, so could not fail a wrong one as check_shadow does
    As, Ls, Ps, polars, Rs = shadows
    words = [s.status for s in (qverify.shadow(A, L) for A, L in zip(As, Ls))]
    assert all(qverify.check_shadows(As, Ls, P=Ps, status=words, samples=8))
    assert all(qverify.check_shadows(As, Ls, P=Ps, status="ok", samples=8))
    wrong = list(words)
    wrong[3] = "light-on-surface"
    wrong[4] = None  # none reported: nothing to check
    reps = qverify.check_shadows(As, Ls, P=Ps, status=wrong, samples=8)
    assert [k for k, r in enumerate(reps) if not r] == [3]
    alone = qverify.check_shadow(As[3], Ls[3], P=Ps[3], status="light-on-surface", samples=8)
    assert same_report(reps[3], alone)
    # (an empty word is no word: it passed as "none reported", audit 37b F8; None is that)
    for bad, path in ((["ok"] * 3, "status"), (words[:-1] + [7], "status[11]"), (5, "status"), ("", "status"),
                      (words[:-1] + [""], "status[11]")):
        with pytest.raises(qverify.InputError) as e:
            qverify.check_shadows(As, Ls, P=Ps, status=bad)
        assert e.value.path == path
    planes = np.array([[0.0, 0.0, 1.0, 3.0]] * len(As))
    Bs = np.array([qverify.reflection(A, p).B for A, p in zip(As, planes)])
    reps = qverify.check_reflections(As, planes, B=Bs, status=["ok"] * 5 + ["degenerate-quadric"] + ["ok"] * 6, samples=8)
    assert [k for k, r in enumerate(reps) if not r] == [5]


def test_memoryviews_are_read_as_the_arrays_they_view(shadows):
    # (the batch doors indexed a 3-d memoryview as a sequence: NotImplementedError; review of 1da4b1b)
    As, Ls, Ps, polars, Rs = shadows
    As = np.ascontiguousarray(As, dtype=float)
    viewed = qverify.check_shadows(memoryview(As), memoryview(np.ascontiguousarray(Ls)), P=memoryview(np.ascontiguousarray(Ps)), samples=8)
    plain = qverify.check_shadows(As, Ls, P=Ps, samples=8)
    assert [same_report(a, b) for a, b in zip(viewed, plain)] == [True] * len(plain)
    with pytest.raises(qverify.InputError) as e:
        qverify.check_shadows(memoryview(np.zeros((3, 4, 3))), Ls[:3], P=Ps[:3])
    assert e.value.path == "A[0]"  # (its first item is not 4 x 4)
