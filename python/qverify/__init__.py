"""qverify: shadow volumes and mirror images of quadric surfaces, exact and verified.

After Hashimoto & Suenaga, "A study on the transformation of quadric
surfaces": the shadow volume of a quadric x^T A x = 0 lit by a point or
parallel light (a cone P with the light at its apex, cut by a quadric R
through the terminator) and its mirror image B = M^T A M in a plane mirror.

Every input number is taken exactly: a float is the dyadic rational it
holds, an int is itself, a fractions.Fraction is p/q, a string is a decimal
("0.1" is 1/10) or "p/q". Results are float64 numpy arrays, or nested lists
of Fraction with precision="exact".

Functions:
    shadow(A, L, ...)             P, polar plane and R of one quadric and light
    reflection(A, plane, ...)     M and B of one quadric and mirror plane
    check_shadow(A, L, P=..., polar_plane=..., R=...)
                                  checks any program's shadow on exact points
    check_reflection(A, plane, M=..., B=...)
                                  checks any program's mirror image
    check_shadows(As, Ls, P=Ps, ...), check_reflections(As, planes, B=Bs, ...)
                                  many items at once, on threads, with progress
    eval_scene(scene, ...)        the qverify-eval/1 document of a scene
    verify_scene(scene, ...)      the qverify-verify/1 document of a scene
    stress(fn, families=[...], out=DIR)
                                  audits your function on the stress sweeps
    stress_families()             the families of stress

Bad input raises qverify.InputError (a ValueError) whose `path` names the
offending value: "A[3][1]", "L", "precision", or a scene's JSON path.

Example:
    >>> import numpy as np, qverify
    >>> A = np.diag([1.0, 1.0, 1.0, -1.0])          # unit sphere
    >>> L = np.array([3.0, 4.0, 8.0, 1.0])           # point light (3, 4, 8)
    >>> s = qverify.shadow(A, L)
    >>> rep = qverify.check_shadow(A, L, P=s.P, polar_plane=s.polar_plane, R=s.R)
    >>> rep.passed
    True
"""

import json as _json
import math as _math
import numbers as _numbers
import os as _os
import tempfile as _tempfile
from fractions import Fraction as _Fraction

from ._qverify import (  # noqa: F401
    DEFAULT_ACCURACY,
    DEFAULT_SAMPLES,
    PRECISIONS,
    CheckReport,
    InputError,
    ReflectionResult,
    ShadowResult,
    _decimal,
    _eval_scene,
    _stress,
    _verify_scene,
    check_reflection,
    check_reflections,
    check_shadow,
    check_shadows,
    reflection,
    shadow,
    stress_families,
)

__version__ = "0.1.0"

__all__ = [
    "shadow",
    "reflection",
    "check_shadow",
    "check_reflection",
    "check_shadows",
    "check_reflections",
    "eval_scene",
    "verify_scene",
    "stress",
    "stress_families",
    "InputError",
    "ShadowResult",
    "ReflectionResult",
    "CheckReport",
    "DEFAULT_ACCURACY",
    "DEFAULT_SAMPLES",
    "PRECISIONS",
]


def _join(path, key):
    return key if not path else path + "." + key


def _exact_json(value, path):
    """A dict of a scene or candidate made JSON text that keeps every number exact.

    A float becomes the string "p/q" of the dyadic rational it holds (a JSON
    number would be read as the decimal it spells), a Fraction "p/q", a
    numpy array or scalar its list or number; NaN and inf are refused with
    the path.
    """
    try:
        import numpy as np
    except ImportError:  # pragma: no cover - numpy is a dependency of the module
        np = None
    if np is not None and isinstance(value, np.ndarray):
        value = value.tolist()
    if np is not None and isinstance(value, np.generic):
        value = value.item()
    if isinstance(value, dict):
        out = {}
        for k, v in value.items():
            if not isinstance(k, str):
                raise InputError("%s: keys must be strings, found %r" % (path or "(document)", k),
                                 path, "<dict>", "keys must be strings, found %r" % (k,))
            out[k] = _exact_json(v, _join(path, k))
        return out
    if isinstance(value, (list, tuple)):
        return [_exact_json(v, "%s[%d]" % (path, i)) for i, v in enumerate(value)]
    if isinstance(value, int) and not isinstance(value, bool) and value.bit_length() > 2000:
        return _decimal(value)  # (json.dumps would call str(), which refuses more than 4300 digits, or fewer)
    if isinstance(value, bool) or value is None or isinstance(value, (int, str)):
        return value
    if isinstance(value, float):
        if not _math.isfinite(value):
            problem = "not a finite number (%r)" % value
            raise InputError("<dict>: %s: %s" % (path, problem), path, "<dict>", problem)
        p, q = value.as_integer_ratio()
        return str(p) if q == 1 else "%d/%d" % (p, q)
    if isinstance(value, _Fraction) or (hasattr(value, "numerator") and hasattr(value, "denominator")):
        p, q = int(value.numerator), int(value.denominator)
        if q == 0:
            problem = "a fraction with zero denominator (%s/0)" % _decimal(p)
            raise InputError("<dict>: %s: %s" % (path, problem), path, "<dict>", problem)
        return _decimal(p) if q == 1 else "%s/%s" % (_decimal(p), _decimal(q))
    if hasattr(value, "as_integer_ratio"):  # decimal.Decimal, numpy long double
        try:
            p, q = value.as_integer_ratio()
        except (ValueError, OverflowError):
            problem = "not a finite number (%r)" % (value,)
            raise InputError("<dict>: %s: %s" % (path, problem), path, "<dict>", problem) from None
        return _decimal(p) if q == 1 else "%s/%s" % (_decimal(p), _decimal(q))
    problem = "not a JSON value: %s" % type(value).__name__
    raise InputError("<dict>: %s: %s" % (path or "(document)", problem), path, "<dict>", problem)


def _document_args(doc, what):
    """(path, text, name) for the C++ side: a file path, or a dict as exact JSON text."""
    if isinstance(doc, dict):
        try:
            return None, _json.dumps(_exact_json(doc, "")), "<dict>"
        except RecursionError:
            problem = "nested too deeply, or contains itself"
            raise InputError("<dict>: %s" % problem, "", "<dict>", problem) from None
    if isinstance(doc, (str, bytes, _os.PathLike)):
        return _os.fsdecode(doc), None, ""
    problem = "expected a file path or a dict, found %s" % type(doc).__name__
    raise InputError("%s: %s" % (what, problem), what, "", problem)


def eval_scene(scene, precision="double", method="direct", *, frame=None, accuracy=DEFAULT_ACCURACY, tolerance=None):
    """Evaluates a scene: the qverify-eval/1 document of `qverify eval SCENE --json`.

    Args:
        scene: a qverify-scene/1 file (path) or the scene as a dict
            ({"format": "qverify-scene/1", "quadrics": [...], ...}). In a
            dict a float is taken at its exact binary value; write a decimal
            string ("0.1") for a decimal number, or a Fraction.
        precision: "float", "double", "long-double", "float128", "mpfr:BITS",
            "interval" or "exact".
        method: "direct" or "paper".
        frame: None (default), "local" or "world".
        accuracy: the accuracy target of the items' error_bound.
        tolerance: adaptive mode (`eval --tolerance T`): each item escalates
            double -> interval -> mpfr -> exact until certified within T.

    Returns:
        dict: the document (format, scene, precision, method, frame,
        accuracy, shadows, reflections, skipped, inputs_rounded, ...), with
        numbers as the CLI writes them (exact entries as "p/q" strings).

    Raises:
        qverify.InputError: an invalid scene (`path` is the JSON path,
            `file` the file or "<dict>") or a bad argument.
        OSError-like RuntimeError: an unreadable file is an InputError too.
    """
    path, text, name = _document_args(scene, "scene")
    return _eval_scene(path, text, name, precision, method, frame, accuracy, tolerance)


def verify_scene(scene, candidate=None, precision="double", method="direct", *, frame=None,
                 samples=DEFAULT_SAMPLES, seed=1, accuracy=DEFAULT_ACCURACY):
    """Verifies a scene on exact sample points: the qverify-verify/1 document of `qverify verify`.

    Without a candidate the scene is computed in `precision` by `method` and
    checked; with one, the candidate's results are checked (from any program).

    Args:
        scene: a qverify-scene/1 file (path) or a dict (see eval_scene).
        candidate: None, or a qverify-eval/1 document: a file path or a dict
            (e.g. what eval_scene returned, possibly altered). Its floats
            are taken exactly.
        precision: the precision to compute in (without a candidate); with a
            candidate, "exact" judges it in proof mode (every residual exactly
            zero, as `verify --precision exact --candidate`), and another
            only sets the information consistent_with_precision when the
            document does not name its precision.
        method, frame: as in eval_scene.
        samples, seed: exact points per item and the sampler's seed.
        accuracy: the accuracy target (0 in the document with precision
            "exact": a pass is then a proof).

    Returns:
        dict: the document (checks, passed, failed, skipped counts, ...).
        Each check has status "pass", "fail" or "skipped".

    Raises:
        qverify.InputError: an invalid scene or candidate (JSON path), or a
            bad argument.
    """
    path, text, name = _document_args(scene, "scene")
    if candidate is None:
        cpath, ctext, cname = None, None, ""
    else:
        cpath, ctext, cname = _document_args(candidate, "candidate")
    return _verify_scene(path, text, name, cpath, ctext, cname, precision, method, frame, samples, seed, accuracy)


def _argument_error(path, problem):
    return InputError("%s: %s" % (path, problem), path, "", problem)


def stress(fn=None, *, shadow=None, reflection=None, families=None, out=None, name="candidate", samples=None,
           accuracy=None):
    """Audits your own function on the stress sweeps of `qverify stress`: no files, no process.

    Every point of each family (one parameter pushed over many decades
    towards a breaking point: an object 1e12 from the origin, a light 1e-15
    from the surface, ...) is computed by qverify in several precisions and
    by your function, and each result is measured against exact: the
    geometric error (the largest first-order distance of exact sample points
    from the returned quadric, relative to the object's size). This is
    `qverify stress --candidate-cmd` with a Python function as the candidate.

    Your function is called once per point with float64 numpy arrays: the
    scene's exact inputs, each entry correctly rounded to double,

    * shadow families: fn(A, L) with A the quadric's 4x4 matrix and L the
      light, (x, y, z, 1) for a point light or (-d, 0) for a parallel light
      along d; it returns P, the shadow cone (L^T A L) A - (A L)(A L)^T up to
      a positive factor, as a 4x4 array-like, or a dict
      {"P": ..., "polar_plane": ... (A L), "R": ...} (polar_plane and R
      optional: left out, they are not measured);
    * reflection families: fn(A, plane) with plane = (a, b, c, d) of the
      mirror a x + b y + c z + d = 0; it returns B = M^T A M up to a positive
      factor, or a dict {"B": ..., "M": ...} (M optional).

    Returned values are taken exactly (floats, ints, Fractions ...) and
    rounded to double. An exception raised by the function (any Exception),
    a missing or malformed result or a NaN / inf entry is that point's
    failed call: status "candidate-failed" with "error" (e.g. "shadow (obj,
    light): ZeroDivisionError: float division by zero"), and the sweep goes
    on. KeyboardInterrupt stops it. There is no time-out: a function that
    never returns hangs the sweep. The sweep runs without the GIL; it is
    taken back for each call of the function.

    Args:
        fn: the function for the families named in `families` (required
            with fn): called as fn(A, L) on shadow families and fn(A, plane)
            on reflection families.
        shadow: a shadow function fn(A, L) (instead of fn).
        reflection: a reflection function fn(A, plane) (instead of fn); with
            shadow= and reflection= both, the families of both kinds run.
        families: a family name or a list of them (stress_families() lists
            them with their kind); None: every family of the kinds given.
        out: None, or a directory (created when missing) where report.json
            (the returned document), report.html (self-contained, with the
            plots), one FAMILY.svg per family and, for every point where the
            function failed or its error exceeds `accuracy`, a reproducer
            failures/NAME-FAMILY-K.json (the point's scene) with
            NAME-FAMILY-K.log (the reason; a raised exception's traceback)
            are written. With None nothing is kept (the document's
            reproducer paths then name files that were not kept).
        name: the candidate's name in the report (letters, digits, '.', '_',
            '-'; default "candidate").
        samples: exact sample points per item (default 8).
        accuracy: the accuracy target of the function's geometric error
            (default 1e-9): a point beyond it is a reproducer.

    Returns:
        dict: the qverify-stress/1 document. families[i]["points"][k]["runs"]
        holds qverify's runs and, last, the function's run ("source":
        "candidate": status, error, item_geometric_error, beyond_accuracy,
        seconds, reproducer); families[i]["candidate"] its breakdown (the
        first parameter where it failed or exceeded the target) and counts;
        ["candidate"] the totals (calls, failed_calls, beyond_accuracy,
        reproducers).

    Raises:
        qverify.InputError: a bad argument, nothing run: fn not callable
            (path "fn", "shadow" or "reflection"), an unknown family or one
            of a kind without a function ("families[1]"), a bad name,
            samples or accuracy.
        OSError: `out`, a report file in it or its failures/ directory
            cannot be created or written
            (errno, strerror and `filename` set, the subclass by errno:
            IsADirectoryError, PermissionError ...); raised before the sweep,
            from a check that the directory can be made and takes the files.

    Example:
        >>> def naive_shadow(A, L):  # world coordinates, plain doubles
        ...     AL = A @ L
        ...     return (L @ AL) * A - np.outer(AL, AL)
        >>> doc = qverify.stress(naive_shadow, families=["far-from-origin"], out="out/naive")
        >>> doc["families"][0]["candidate"]["breakdown"]  # the first offset where it breaks
        100000000.0
    """
    for arg, value in (("fn", fn), ("shadow", shadow), ("reflection", reflection)):
        if value is not None and not callable(value):
            raise _argument_error(arg, "expected a callable, found %s" % type(value).__name__)
    if fn is not None:
        if shadow is not None or reflection is not None:
            raise _argument_error("fn", "give fn, or shadow= and reflection=, not both")
        if families is None:
            raise _argument_error("families", "name the families to run fn on (qverify.stress_families() lists them), "
                                              "or pass it as shadow= or reflection= to run every family of that kind")
        shadow = reflection = fn
    if shadow is None and reflection is None:
        raise _argument_error("fn", "no function to audit: give fn, shadow= or reflection=")
    if families is not None:
        if isinstance(families, str):
            families = [families]
        try:
            families = list(families)
        except TypeError:
            raise _argument_error("families", "expected a family name or a list of them, found %s"
                                  % type(families).__name__) from None
        for i, f in enumerate(families):
            if not isinstance(f, str):
                raise _argument_error("families[%d]" % i, "expected a family name (str), found %s" % type(f).__name__)
    if not isinstance(name, str):
        raise _argument_error("name", "expected a str, found %s" % type(name).__name__)
    if samples is not None and (isinstance(samples, bool) or not isinstance(samples, _numbers.Integral)):
        raise _argument_error("samples", "expected an int, found %s" % type(samples).__name__)
    if accuracy is not None and (isinstance(accuracy, bool) or not isinstance(accuracy, _numbers.Real)):
        raise _argument_error("accuracy", "expected a number, found %s" % type(accuracy).__name__)
    if out is None:
        with _tempfile.TemporaryDirectory(prefix="qverify-stress-") as tmp:
            return _stress(shadow, reflection, families, _os.fsencode(tmp), False, name, samples, accuracy)
    if not isinstance(out, (str, bytes, _os.PathLike)):
        raise _argument_error("out", "expected a directory path or None, found %s" % type(out).__name__)
    if b"\0" in _os.fsencode(out):  # (the system would cut the path there)
        raise _argument_error("out", "a directory path with a NUL character")
    return _stress(shadow, reflection, families, _os.fsencode(out), True, name, samples, accuracy)
