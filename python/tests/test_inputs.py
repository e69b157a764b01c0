"""Bad input raises qverify.InputError naming the offending value; nothing is computed from it."""
import json
from decimal import Decimal
from fractions import Fraction

import numpy as np
import pytest

import qverify
from conftest import SCENES

SCENE_FILE = SCENES / "ball-lamp-floor.json"

UNIT = [[1, 0, 0, 0], [0, 1, 0, 0], [0, 0, 1, 0], [0, 0, 0, -1]]
LIGHT = [3, 4, 8, 1]


class ZeroDenominator:
    """A Fraction look-alike with denominator 0 (fractions.Fraction refuses to be one)."""
    numerator = 1
    denominator = 0


def with_entry(i, j, value, symmetric=False):
    A = np.array(UNIT, dtype=object)
    A[i, j] = value
    if symmetric:
        A[j, i] = value
    return A


def path_of(call):
    with pytest.raises(qverify.InputError) as e:
        call()
    assert isinstance(e.value, ValueError)
    assert e.value.problem and e.value.path in str(e.value)
    return e.value.path


def test_input_error_is_a_value_error():
    assert issubclass(qverify.InputError, ValueError)
    assert qverify.InputError.__doc__


@pytest.mark.parametrize(
    "A, path",
    [
        (np.zeros((3, 4)), "A"),
        (np.zeros(16), "A"),
        ([[1, 0, 0, 0]] * 3, "A"),
        ([[1, 0, 0, 0], [0, 1, 0], [0, 0, 1, 0], [0, 0, 0, -1]], "A[1]"),
        ("not a matrix", "A"),
        (with_entry(3, 1, 0.5), "A[3][1]"),  # not symmetric: named below the diagonal (the message gives both)
        (with_entry(1, 3, 0.5), "A[3][1]"),
        (with_entry(2, 2, float("nan")), "A[2][2]"),
        (with_entry(0, 3, float("inf"), symmetric=True), "A[0][3]"),
        (with_entry(0, 0, ZeroDenominator()), "A[0][0]"),
        (with_entry(1, 1, "1/0"), "A[1][1]"),
        (with_entry(1, 1, "one"), "A[1][1]"),
        (with_entry(1, 1, None), "A[1][1]"),
        (with_entry(1, 1, True), "A[1][1]"),
        (with_entry(1, 1, Decimal("NaN")), "A[1][1]"),
        (with_entry(1, 1, np.float32("nan")), "A[1][1]"),
    ],
)
def test_bad_quadric(A, path):
    assert path_of(lambda: qverify.shadow(A, LIGHT)) == path
    assert path_of(lambda: qverify.check_shadow(A, LIGHT, P=np.eye(4))) == path
    assert path_of(lambda: qverify.reflection(A, [0, 0, 1, 0])) == path


def test_the_zero_matrix_is_a_degenerate_quadric_as_in_a_scene():
    zero = np.zeros((4, 4))
    assert qverify.shadow(zero, LIGHT).status == "degenerate-quadric"
    assert qverify.shadow(zero, LIGHT, precision="exact").status == "degenerate-quadric"
    assert qverify.reflection(zero, [0, 0, 1, 0]).status == "degenerate-quadric"


@pytest.mark.parametrize(
    "L, path",
    [
        ([0, 0, 0, 0], "L"),
        (np.zeros(4), "L"),
        ([1, 2, 3], "L"),
        (np.ones((2, 2)), "L"),
        ([1, float("nan"), 3, 1], "L[1]"),
        ([1, 2, float("-inf"), 1], "L[2]"),
        ([1, 2, 3, ZeroDenominator()], "L[3]"),
        ([1, 2, "x", 1], "L[2]"),
    ],
)
def test_bad_light(L, path):
    assert path_of(lambda: qverify.shadow(UNIT, L)) == path
    assert path_of(lambda: qverify.check_shadow(UNIT, L, P=np.eye(4))) == path


@pytest.mark.parametrize("plane, path", [([0, 0, 0, 1], "plane"), ([0.0, 0.0, 0.0, 0.0], "plane"),
                                         ([0, 0, float("nan"), 1], "plane[2]"), ([1, 2], "plane")])
def test_bad_mirror(plane, path):
    assert path_of(lambda: qverify.reflection(UNIT, plane)) == path
    assert path_of(lambda: qverify.check_reflection(UNIT, plane, B=np.eye(4))) == path


@pytest.mark.parametrize(
    "kwargs, path",
    [
        ({"precision": "quad"}, "precision"),
        ({"precision": "mpfr:8"}, "precision"),
        ({"method": "fast"}, "method"),
        ({"accuracy": 0.0}, "accuracy"),
        ({"accuracy": -1e-9}, "accuracy"),
        ({"accuracy": float("nan")}, "accuracy"),
        ({"frame": "camera"}, "frame"),
        # a value of the wrong type is an InputError too (a ValueError), never pybind's TypeError
        ({"accuracy": "1e-9"}, "accuracy"),
        ({"accuracy": True}, "accuracy"),
        ({"accuracy": None}, "accuracy"),
        ({"precision": None}, "precision"),
        ({"precision": 64}, "precision"),
        ({"method": 1}, "method"),
        ({"frame": 3}, "frame"),
    ],
)
def test_bad_options(kwargs, path):
    assert path_of(lambda: qverify.shadow(UNIT, LIGHT, **kwargs)) == path
    assert path_of(lambda: qverify.reflection(UNIT, [0, 0, 1, 0], **kwargs)) == path
    assert path_of(lambda: qverify.eval_scene({"format": "qverify-scene/1"}, **kwargs)) == path


@pytest.mark.parametrize(
    "kwargs, path",
    [
        ({"samples": 64.0}, "samples"),
        ({"samples": "64"}, "samples"),
        ({"samples": True}, "samples"),
        ({"seed": 1.5}, "seed"),
        ({"seed": -1}, "seed"),
        ({"seed": 2**64}, "seed"),
        ({"accuracy": "x"}, "accuracy"),
        ({"method": None}, "method"),
        ({"exact": "yes"}, "exact"),
    ],
)
def test_wrongly_typed_check_options(kwargs, path):
    s = qverify.shadow(UNIT, LIGHT)
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, P=s.P, **kwargs)) == path
    assert path_of(lambda: qverify.check_shadows([UNIT], [LIGHT], P=[s.P], **kwargs)) == path
    if "method" not in kwargs:
        assert path_of(lambda: qverify.check_reflection(UNIT, [0, 0, 1, 0], B=UNIT, **kwargs)) == path


def test_numbers_of_any_numeric_type_are_options():
    s = qverify.shadow(UNIT, LIGHT, accuracy=np.float32(1e-6))
    rep = qverify.check_shadow(UNIT, LIGHT, P=s.P, samples=np.int64(8), seed=2**64 - 1, accuracy=Fraction(1, 10**9))
    assert rep.passed and rep.points == 8
    assert path_of(lambda: qverify.check_shadows([UNIT], [LIGHT], P=[s.P], threads="2")) == "threads"
    assert path_of(lambda: qverify.check_shadows([UNIT], [LIGHT], P=[s.P], threads=-1)) == "threads"
    assert path_of(lambda: qverify.eval_scene({"format": "qverify-scene/1", "quadrics": []}, tolerance="x")) == "tolerance"


def test_method_precision_and_accuracy_may_be_positional():
    assert qverify.shadow(UNIT, LIGHT, "paper").method == "paper"
    assert qverify.shadow(UNIT, LIGHT, "direct", "exact", 1e-9).precision == "exact"
    assert qverify.reflection(UNIT, [0, 0, 1, 0], "direct", "float").precision == "float"


def test_bad_check_arguments():
    P = np.eye(4)
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT)) == "P"  # nothing to check
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, P=np.eye(3))) == "P"
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, polar_plane=[1, 2, 3])) == "polar_plane"
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, R=with_entry(2, 0, float("nan")))) == "R[2][0]"
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, P=P, origin=[1, 2])) == "origin"
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, P=P, accuracy=0)) == "accuracy"
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, P=P, samples=0)) == "samples"
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, P=P, method="other")) == "method"
    assert path_of(lambda: qverify.check_reflection(UNIT, [0, 0, 1, 0])) == "B"
    assert path_of(lambda: qverify.check_reflection(UNIT, [0, 0, 1, 0], M=[[1]])) == "M"
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, P=P, status="")) == "status"  # (None: none reported)
    assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, P=P, status=3)) == "status"


def test_memoryviews_are_read_as_the_arrays_they_view():
    # (a 2-d memoryview, indexed as a sequence, raised NotImplementedError: audit 37b F7)
    A = np.diag([1.0, 1.0, 1.0, -1.0])
    s = qverify.shadow(memoryview(A), memoryview(np.array(LIGHT, dtype=float)))
    assert s.status == "ok"
    assert np.array_equal(s.P, qverify.shadow(A, LIGHT).P)
    assert path_of(lambda: qverify.shadow(memoryview(np.eye(3)), LIGHT)) == "A"
    assert path_of(lambda: qverify.shadow(A, memoryview(np.zeros(3)))) == "L"
    assert path_of(lambda: qverify.shadow(memoryview(b"abcd"), LIGHT)) == "A"


def scene(**extra):
    d = {"format": "qverify-scene/1", "name": "t",
         "quadrics": [{"id": "q", "matrix": UNIT}],
         "lights": [{"id": "l", "position": [3, 4, 8]}],
         "mirrors": [{"id": "m", "plane": [0, 0, 1, 0]}]}
    d.update(extra)
    return d


def test_bad_scene_dict_names_the_json_path():
    bad = scene(quadrics=[{"id": "q", "matrix": with_entry(3, 1, 2).tolist()}])
    with pytest.raises(qverify.InputError) as e:
        qverify.eval_scene(bad)
    assert e.value.path == "quadrics[0].matrix[3][1]" and e.value.file == "<dict>"
    with pytest.raises(qverify.InputError) as e:
        qverify.verify_scene(scene(lights=[{"id": "l", "position": [0, float("nan"), 0]}]))
    assert e.value.path == "lights[0].position[1]"
    with pytest.raises(qverify.InputError) as e:
        qverify.eval_scene(scene(mirrors=[{"id": "m", "plane": [0, 0, 0, 1]}]))
    assert e.value.path == "mirrors[0].plane"
    with pytest.raises(qverify.InputError) as e:
        qverify.eval_scene(scene(lights=[{"id": "l", "position": [ZeroDenominator(), 0, 0]}]))
    assert e.value.path == "lights[0].position[0]"
    with pytest.raises(qverify.InputError) as e:
        qverify.eval_scene(scene(format="qverify-scene/9"))
    assert e.value.path == "format"
    with pytest.raises(qverify.InputError):
        qverify.eval_scene(42)


def test_bad_scene_file(tmp_path):
    f = tmp_path / "bad.json"
    f.write_text(json.dumps(scene(lights=[{"id": "l", "position": [1, 2]}])))
    with pytest.raises(qverify.InputError) as e:
        qverify.eval_scene(str(f))
    assert e.value.path == "lights[0].position" and e.value.file == str(f)
    with pytest.raises(qverify.InputError):
        qverify.eval_scene(tmp_path / "missing.json")


def test_bad_candidate(tmp_path):
    with pytest.raises(qverify.InputError) as e:
        qverify.verify_scene(scene(), candidate={"format": "qverify-eval/1", "shadows": 3})
    assert e.value.path == "shadows" and e.value.file == "<dict>"


def test_out_of_range_for_the_precision():
    # legal numbers beyond float's range: computed anyway (from the exact inputs, scaled), listed as
    # rounded, and the status is the exact inputs' in every precision; float cannot hold this sphere
    # (radius 1e-150) and says so
    A = np.diag([1e300, 1e300, 1e300, -1.0])
    s = qverify.shadow(A, LIGHT, precision="float")
    assert s.status == "ok" and "inaccurate" in s.flags and "A[0][0]" in s.inputs_rounded
    assert qverify.shadow(A, LIGHT, precision="double").flags == []
    assert qverify.shadow(A, LIGHT, precision="exact").status == "ok"


def test_exact_number_types_are_read_exactly():
    third = [Fraction(1, 3), "1/3", Decimal("0.25"), np.longdouble(0.5), np.float32(0.75), np.int64(2)]
    values = [Fraction(1, 3), Fraction(1, 3), Fraction(1, 4), Fraction(1, 2), Fraction(3, 4), Fraction(2)]
    for x, v in zip(third, values):
        s = qverify.shadow(UNIT, [x, 0, 3, 1], precision="exact")
        assert s.polar_plane[0] == v, x  # A L = (x, 0, 3, -1) for the unit sphere


def test_integers_beyond_pythons_str_limit_are_numbers_like_any_other():
    # Python's str() and int(text) refuse integers beyond 4300 digits; a scene's numbers may have
    # 10000. They once raised a bare ValueError, with no path.
    big = 10**5000
    assert qverify.shadow(with_entry(0, 0, big), LIGHT).status == "ok"
    assert qverify.shadow(with_entry(0, 0, Fraction(1, big)), LIGHT, precision="exact").status == "ok"
    assert qverify.shadow(with_entry(0, 0, -big), LIGHT).status == "ok"
    scene = {"format": "qverify-scene/1", "lights": [{"id": "l", "position": [3, 4, 8]}],
             "quadrics": [{"id": "a", "matrix": with_entry(0, 0, big).tolist()}]}
    assert qverify.eval_scene(scene)["shadows"][0]["status"] == "ok"
    scene["quadrics"][0]["matrix"][0][0] = Fraction(1, big)
    assert qverify.eval_scene(scene)["shadows"][0]["status"] == "ok"
    # beyond the scene format's 10000 digits: an InputError naming the entry
    assert path_of(lambda: qverify.shadow(with_entry(0, 0, 10**20000), LIGHT)) == "A[0][0]"
    scene["quadrics"][0]["matrix"][0][0] = 10**20000
    assert path_of(lambda: qverify.eval_scene(scene)) == "quadrics[0].matrix[0][0]"
    # and as options: named, not a bare ValueError from their repr()
    s = qverify.shadow(UNIT, LIGHT)
    for name in ("seed", "samples", "accuracy"):
        assert path_of(lambda: qverify.check_shadow(UNIT, LIGHT, P=s.P, **{name: 10**5000})) == name


def test_exact_results_beyond_a_scenes_digit_limit_come_back():
    # a legal light at 1e9000 gives a cone with entries of 36,000 digits: qverify's own results are
    # read back without the scene format's 10000-digit limit (it raised a RuntimeError)
    A = np.diag([1, 1, 1, -1])
    s = qverify.shadow(A, [3, 4, "1e9000", 1], precision="exact")
    assert s.status == "ok" and s.P[2][2] != 0
    assert qverify.shadow(A, [3, 4, "1e9000", 1], precision="mpfr:64").status == "ok"
    big = 10**5000
    assert qverify.reflection(A, [0, 0, 1, big], precision="exact").status == "ok"


def test_file_paths(tmp_path):
    # a name that is no UTF-8 is a path like any other; a NUL, which the system would cut the path
    # at, is an InputError naming the argument
    good = SCENE_FILE.read_bytes()
    f = tmp_path / "sc\udcff.json"  # (the byte 0xff, as Python spells it in a str)
    f.write_bytes(good)
    raw = bytes(tmp_path) + b"/sc\xff.json"
    assert qverify.eval_scene(raw)["format"] == "qverify-eval/1"
    cand = bytes(tmp_path) + b"/cand\xff.json"
    with open(cand, "w") as out:
        json.dump(qverify.eval_scene(raw), out)
    assert qverify.verify_scene(raw, candidate=cand)["failed"] == 0  # (its name in the document: escaped)
    with pytest.raises(qverify.InputError) as e:  # a missing one: its name in the error, as os.fsdecode gives it
        qverify.eval_scene(bytes(tmp_path) + b"/missing\xff.json")
    assert e.value.file.endswith("missing\udcff.json")
    assert path_of(lambda: qverify.eval_scene(str(SCENE_FILE) + "\0/etc/passwd")) == "scene"
    assert path_of(lambda: qverify.verify_scene(str(SCENE_FILE), candidate=str(SCENE_FILE) + "\0x")) == "candidate"
    assert path_of(lambda: qverify.stress(lambda A, L: None, families=["light-far"], out=str(tmp_path / "st\0x"))) == "out"
    assert not (tmp_path / "st").exists()


def test_accuracy_errors_show_the_value_given():
    with pytest.raises(qverify.InputError) as e:
        qverify.shadow(UNIT, LIGHT, accuracy=-1e-12)
    assert "-1e-12" in str(e.value)
    with pytest.raises(qverify.InputError) as e:
        qverify.shadow(UNIT, LIGHT, accuracy=Fraction(1, 10**400))
    assert "0 as a double" in str(e.value)


def test_a_dict_scene_that_contains_itself():
    d = {"format": "qverify-scene/1", "quadrics": []}
    d["quadrics"].append(d)
    with pytest.raises(qverify.InputError):
        qverify.eval_scene(d)
