"""Shared fixtures of the qverify Python tests (run by CTest as python_pytest)."""
import os
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest

import qverify

SCENES = Path(os.environ.get("QVERIFY_SCENES", Path(__file__).resolve().parents[2] / "examples" / "scenes"))


@pytest.fixture
def sphere():
    """The unit sphere x^2 + y^2 + z^2 = 1."""
    return np.diag([1.0, 1.0, 1.0, -1.0])


@pytest.fixture
def light():
    """A point light at (3, 4, 8)."""
    return np.array([3.0, 4.0, 8.0, 1.0])


def sphere_at(center, radius):
    """Exact matrix (Fractions) of the sphere |x - c| = r."""
    c = [Fraction(x) for x in center]
    r = Fraction(radius)
    A = [[Fraction(0)] * 4 for _ in range(4)]
    for i in range(3):
        A[i][i] = Fraction(1)
        A[i][3] = A[3][i] = -c[i]
    A[3][3] = sum(x * x for x in c) - r * r
    return A


def cone_reference(A, L):
    """(L^T A L) A - (A L)(A L)^T, exactly (A, L as Fractions or ints)."""
    A = [[Fraction(x) for x in row] for row in A]
    L = [Fraction(x) for x in L]
    AL = [sum(A[i][j] * L[j] for j in range(4)) for i in range(4)]
    s = sum(L[i] * AL[i] for i in range(4))
    return [[s * A[i][j] - AL[i] * AL[j] for j in range(4)] for i in range(4)]


def positive_factor(X, Y):
    """The factor f > 0 with X == f Y entrywise (exact Fractions), or None."""
    f = None
    for x, y in zip(np.ravel(np.array(X, dtype=object)), np.ravel(np.array(Y, dtype=object))):
        if y == 0:
            if x != 0:
                return None
            continue
        g = Fraction(x) / Fraction(y)
        if f is None:
            f = g
        elif g != f:
            return None
    return f if f is not None and f > 0 else None
