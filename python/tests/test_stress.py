"""qverify.stress: a Python function audited on the stress sweeps (issue 19).

Each sweep runs one family with few sample points (a family is 13 points,
each computed by qverify in ten ways and measured against exact).
"""
import json
import re
import textwrap
from pathlib import Path

import numpy as np
import pytest

import qverify

README = Path(__file__).resolve().parents[2] / "README.md"


def candidate_runs(doc, family=0):
    """The function's run at every point of a family (the last run of each point)."""
    runs = [p["runs"][-1] for p in doc["families"][family]["points"]]
    assert all(r["source"] == "candidate" for r in runs)
    return runs


def naive_run(point):
    return next(r for r in point["runs"] if r["run"] == "double/direct/world (naive)")


def test_readme_stress_example(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)  # out/naive below
    # --- README stress example begin
    from pathlib import Path

    import numpy as np
    import qverify

    def naive_shadow(A, L):  # the code under test: the textbook formula in plain doubles
        AL = A @ L
        return (L @ AL) * A - np.outer(AL, AL)

    out_dir = Path("out/naive")
    doc = qverify.stress(naive_shadow, families=["thin-ellipsoid"], out=out_dir, name="naive")
    fam = doc["families"][0]  # an ellipsoid of aspect ratio 1 .. 1e12 lit by a lamp
    assert fam["candidate"]["breakdown"] == 1e4  # the first aspect where a check fails (P's shape)
    assert fam["candidate"]["failed_calls"] == 0
    assert (out_dir / "report.html").exists() and (out_dir / "thin-ellipsoid.svg").exists()
    assert (out_dir / "failures" / "naive-thin-ellipsoid-4.json").exists()  # the scene at aspect 1e4: a reproducer

    def careful_shadow(A, L):  # the same cone of the same doubles, computed exactly, then rounded
        return qverify.shadow(A, L, precision="exact").P

    doc = qverify.stress(careful_shadow, families=["thin-ellipsoid"])
    assert doc["families"][0]["candidate"]["breakdown"] is None  # within 1e-9 at every point
    # --- README stress example end


def test_readme_shows_the_example_as_run():
    """The README's qverify.stress example is the block above, word for word."""
    source = Path(__file__).read_text()
    block = re.search(r"# --- README stress example begin\n(.*?)    # --- README stress example end", source, re.S).group(1)
    assert textwrap.dedent(block) in README.read_text()


def test_the_report_on_disk_and_the_candidate_runs(tmp_path):
    def naive_shadow(A, L):
        AL = A @ L
        return (L @ AL) * A - np.outer(AL, AL)

    doc = qverify.stress(naive_shadow, families=["thin-ellipsoid"], out=tmp_path, name="naive", samples=4)
    assert json.loads((tmp_path / "report.json").read_text()) == doc
    assert "naive (candidate)" in (tmp_path / "report.html").read_text()
    runs = candidate_runs(doc)
    assert all(r["status"] == "unstated" and r["frame"] == "world" and r["precision"] == "double" for r in runs)
    # on the terminator the textbook P is right at every aspect (the geometric error: any quadric of the
    # pencil s A - c (A L)(A L)^T vanishes there), but from aspect 1e4 on it is not the cone from L: off
    # along its generator lines, which verify's check of P's shape (on_generators) fails
    assert [r["beyond_accuracy"] for r in runs] == [False] * 13
    assert doc["candidate"]["calls"] == 13 and doc["candidate"]["beyond_accuracy"] == 0
    assert [r["problems"] != [] for r in runs] == [k >= 4 for k in range(13)]
    assert all(any(p.startswith("on_generators") for p in r["problems"]) for r in runs[4:])
    assert doc["candidate"]["failed_checks"] == 9
    assert [r["status"] for r in doc["candidate"]["reproducers"]] == ["failed-checks"] * 9


def test_far_from_the_origin_the_world_frame_itself_breaks():
    """A world-frame matrix of a unit sphere at (d, 2, 1) cannot be accurate from d = 1e8 on.

    The naive formula and the exact cone of the same doubles, rounded, both
    break where qverify's own naive world-frame double does (README
    "stress"); qverify's default double path (local frame) never does.
    """

    def naive_shadow(A, L):
        AL = A @ L
        return (L @ AL) * A - np.outer(AL, AL)

    def exact_shadow(A, L):
        s = qverify.shadow(A, L, precision="exact")
        return {"P": s.P, "polar_plane": s.polar_plane, "R": s.R}

    for fn in (naive_shadow, exact_shadow):
        doc = qverify.stress(shadow=fn, families="far-from-origin", samples=4)
        fam = doc["families"][0]
        assert fam["candidate"]["breakdown"] == 1e8
        assert fam["breakdown"]["double/direct/world (naive)"] == 1e8
        assert fam["default_meets_target"]
        for p, r in zip(fam["points"], candidate_runs(doc)):
            if naive_run(p)["item_geometric_error"] <= 1e-9:
                assert r["item_geometric_error"] <= 1e-9, p["param"]


def test_a_reflection_function_returning_a_dict():
    def mirror_image(A, plane):
        n, d = plane[:3], plane[3]
        M = np.eye(4)
        M[:3, :] -= 2 * np.outer(n, np.append(n, d)) / (n @ n)
        return {"B": M.T @ A @ M, "M": M}

    doc = qverify.stress(reflection=mirror_image, families=["mirror-through-object"], samples=4)
    assert doc["families"][0]["item"] == "reflection B"
    assert doc["families"][0]["candidate"]["breakdown"] is None
    assert all(r["item_geometric_error"] <= 1e-9 for r in candidate_runs(doc))


def test_exceptions_and_bad_results_are_failed_calls_and_the_sweep_goes_on(tmp_path):
    calls = []

    def flaky(A, L):
        k = len(calls)
        calls.append((A.shape, L.shape, A.dtype, L.dtype))
        if k == 0:
            raise ZeroDivisionError("float division by zero")
        if k == 1:
            return np.zeros((3, 4))
        if k == 2:
            return {"P": np.eye(4), "Q": 1}
        if k == 3:
            P = np.eye(4)
            P[1, 2] = np.nan
            return P
        if k == 4:
            return {"polar_plane": A @ L}
        AL = A @ L
        return (L @ AL) * A - np.outer(AL, AL)

    doc = qverify.stress(shadow=flaky, families=["far-from-origin"], out=tmp_path, name="flaky", samples=4)
    assert len(calls) == 13 and calls[0] == ((4, 4), (4,), np.float64, np.float64)
    runs = candidate_runs(doc)
    reasons = [
        "shadow (obj, light): ZeroDivisionError: float division by zero",
        "shadow (obj, light): the function returned P: expected a 4x4 matrix, found an array of shape (3, 4)",
        'shadow (obj, light): the function returned a dict with the unknown key "Q" (expected P, polar_plane, R)',
        "shadow (obj, light): the function returned P[1][2]: not a finite number (NaN)",
        "shadow (obj, light): the function returned no P (the shadow cone is required)",
    ]
    for k, reason in enumerate(reasons):
        assert runs[k]["status"] == "candidate-failed"
        assert runs[k]["error"] == reason
        assert runs[k]["item_geometric_error"] is None
        assert (tmp_path / ("failures/flaky-far-from-origin-%d.json" % k)).exists()
    assert all(r["status"] == "unstated" for r in runs[5:])
    assert doc["families"][0]["candidate"]["failed_calls"] == 5
    assert doc["families"][0]["candidate"]["breakdown"] == 1.0
    # the exception's traceback is in the reproducer's log
    log = (tmp_path / "failures/flaky-far-from-origin-0.log").read_text()
    assert "Traceback" in log and "ZeroDivisionError" in log


def test_keyboard_interrupt_stops_the_sweep():
    def interrupted(A, L):
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        qverify.stress(shadow=interrupted, families=["far-from-origin"], samples=1)


@pytest.mark.parametrize(
    "kwargs, path",
    [
        (dict(shadow=42), "shadow"),
        (dict(fn="not a function", families=["far-from-origin"]), "fn"),
        (dict(fn=lambda A, L: A), "families"),  # fn alone: which families?
        (dict(fn=lambda A, L: A, shadow=lambda A, L: A, families=["far-from-origin"]), "fn"),
        (dict(), "fn"),
        (dict(shadow=lambda A, L: A, families=["far-from-origin", "no-such-family"]), "families[1]"),
        (dict(shadow=lambda A, L: A, families=["mirror-far"]), "families[0]"),  # a reflection family
        (dict(reflection=lambda A, p: A, families=["light-far"]), "families[0]"),
        (dict(shadow=lambda A, L: A, families=[3]), "families[0]"),
        (dict(shadow=lambda A, L: A, families=[]), "families"),
        (dict(shadow=lambda A, L: A, name="has space"), "name"),
        (dict(shadow=lambda A, L: A, samples=0), "samples"),
        (dict(shadow=lambda A, L: A, samples=2.5), "samples"),
        (dict(shadow=lambda A, L: A, accuracy=-1.0), "accuracy"),
        (dict(shadow=lambda A, L: A, out=3), "out"),
    ],
)
def test_bad_arguments_name_the_argument(kwargs, path):
    with pytest.raises(qverify.InputError) as e:
        qverify.stress(**kwargs)
    assert e.value.path == path, str(e.value)
    assert str(e.value).startswith(path + ": ")


def test_an_unwritable_out_is_an_error_naming_the_path(tmp_path):
    blocker = tmp_path / "a-file"
    blocker.write_text("not a directory")
    with pytest.raises(OSError) as e:
        qverify.stress(shadow=lambda A, L: A, families=["far-from-origin"], out=blocker / "report")
    assert str(blocker / "report") in str(e.value)
    assert e.value.filename == str(blocker / "report")
    assert e.value.strerror == "Not a directory"


@pytest.mark.parametrize(
    "blocker, error",
    [("report.json", IsADirectoryError),  # a directory where the report goes
     ("failures", NotADirectoryError)],  # a file where the reproducers go
)
def test_an_unwritable_output_fails_before_the_function_is_called(tmp_path, blocker, error):
    if error is IsADirectoryError:
        (tmp_path / blocker).mkdir()
    else:
        (tmp_path / blocker).write_text("not a directory")
    calls = []

    def shadow(A, L):
        calls.append(1)
        return A

    with pytest.raises(error) as e:
        qverify.stress(shadow=shadow, families=["far-from-origin"], out=tmp_path)
    assert e.value.filename == str(tmp_path / blocker)
    assert str(e.value) == "[Errno %d] %s: '%s'" % (e.value.errno, e.value.strerror, tmp_path / blocker)
    assert calls == []
    assert sorted(p.name for p in tmp_path.iterdir()) == [blocker]


def test_stress_families_lists_both_kinds():
    fams = qverify.stress_families()
    kinds = {f["name"]: f["kind"] for f in fams}
    assert kinds["far-from-origin"] == "shadow" and kinds["mirror-far"] == "reflection"
    assert len(fams) == 13
    assert all(len(f["values"]) > 0 for f in fams)
