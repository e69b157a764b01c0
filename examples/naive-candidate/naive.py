#!/usr/bin/env python3
"""A deliberately naive implementation of qverify's transforms, to be audited by
`qverify stress --candidate-cmd` and `qverify audit --candidate-cmd`.

    python3 naive.py SCENE OUT

reads a qverify-scene/1 file and writes a qverify-eval/1 document to OUT. It does
what a first implementation does: every number straight into a double (a "p/q"
string as p / q), the formulas in world coordinates, no scaling, no checks,
every status "ok". It is right for a unit ball near the origin and wrong far from
it, for small objects given in decimals, and for a light far away."""
import json
import sys


def num(v):
    if isinstance(v, str) and "/" in v:
        p, q = v.split("/")
        return float(p) / float(q)
    return float(v)


def quadric(q):  # the 4x4 matrix A of x^T A x = 0, negative inside
    if "matrix" in q:
        return [[num(x) for x in row] for row in q["matrix"]]
    if "coefficients" in q:
        c = {k: num(v) for k, v in q["coefficients"].items()}
        g = lambda k: c.get(k, 0.0)
        return [[g("xx"), g("xy") / 2, g("xz") / 2, g("x") / 2], [g("xy") / 2, g("yy"), g("yz") / 2, g("y") / 2],
                [g("xz") / 2, g("yz") / 2, g("zz"), g("z") / 2], [g("x") / 2, g("y") / 2, g("z") / 2, g("c")]]
    (shape, s), = ((k, v) for k, v in q.items() if k != "id" and not k.startswith("x-"))
    if shape == "sphere":
        c, K, rhs = [num(x) for x in s["center"]], [[1.0 * (i == j) for j in range(3)] for i in range(3)], num(s["radius"]) ** 2
    elif shape == "ellipsoid":  # K = (F F^T)^-1, F = axes diag(radii)
        c, r = [num(x) for x in s["center"]], [num(x) for x in s["radii"]]
        ax = [[num(x) for x in row] for row in s.get("axes", [[1, 0, 0], [0, 1, 0], [0, 0, 1]])]
        G = [[sum(ax[i][k] * r[k] ** 2 * ax[j][k] for k in range(3)) for j in range(3)] for i in range(3)]
        det = sum(G[0][i] * (G[1][(i + 1) % 3] * G[2][(i + 2) % 3] - G[1][(i + 2) % 3] * G[2][(i + 1) % 3]) for i in range(3))
        K = [[(G[(j + 1) % 3][(i + 1) % 3] * G[(j + 2) % 3][(i + 2) % 3] - G[(j + 1) % 3][(i + 2) % 3] * G[(j + 2) % 3][(i + 1) % 3]) / det
              for j in range(3)] for i in range(3)]
        rhs = 1.0
    else:  # cylinder (|x - p|^2 - (a.(x - p))^2 / |a|^2 = r^2) or cone (apex, tan_half_angle t)
        c, a = [num(x) for x in s["point" if shape == "cylinder" else "apex"]], [num(x) for x in s["axis"]]
        f = 1.0 if shape == "cylinder" else 1.0 + num(s["tan_half_angle"]) ** 2
        aa = sum(x * x for x in a)
        K = [[1.0 * (i == j) - f * a[i] * a[j] / aa for j in range(3)] for i in range(3)]
        rhs = num(s["radius"]) ** 2 if shape == "cylinder" else 0.0
    Kc = [sum(K[i][j] * c[j] for j in range(3)) for i in range(3)]
    return [K[i] + [-Kc[i]] for i in range(3)] + [[-x for x in Kc] + [sum(c[i] * Kc[i] for i in range(3)) - rhs]]


def mul(X, Y):
    return [[sum(X[i][k] * Y[k][j] for k in range(4)) for j in range(4)] for i in range(4)]


def pairs(scene, kind, other):
    ids = [o["id"] for o in scene.get(other, [])]
    req = scene.get("requests", {}).get(kind, "all")
    if req == "all":
        return [(q["id"], o) for q in scene["quadrics"] for o in ids]
    order = {q["id"]: i for i, q in enumerate(scene["quadrics"])}
    return sorted(((r["quadric"], r[other[:-1]]) for r in req), key=lambda p: (order[p[0]], ids.index(p[1])))


scene = json.load(open(sys.argv[1]))
A = {q["id"]: quadric(q) for q in scene["quadrics"]}
lights = {l["id"]: ([num(x) for x in l["position"]] + [1.0]) if "position" in l else ([-num(x) for x in l["direction"]] + [0.0])
          for l in scene.get("lights", [])}
planes = {m["id"]: [num(x) for x in m["plane"]] for m in scene.get("mirrors", [])}
shadows, reflections = [], []
for qid, lid in pairs(scene, "shadows", "lights"):
    a, L = A[qid], lights[lid]
    AL = [sum(a[i][j] * L[j] for j in range(4)) for i in range(4)]
    LAL = sum(L[i] * AL[i] for i in range(4))
    h = [0.0, 0.0, 1.0, -L[2]] if L[3] != 0 else [0.0, 0.0, 0.0, 1.0]
    shadows.append({"quadric": qid, "light": lid, "status": "ok",
                    "P": [[LAL * a[i][j] - AL[i] * AL[j] for j in range(4)] for i in range(4)], "polar_plane": AL,
                    "R": [[AL[i] * h[j] + h[i] * AL[j] for j in range(4)] for i in range(4)]})
for qid, mid in pairs(scene, "reflections", "mirrors"):
    n, nn = planes[mid], sum(x * x for x in planes[mid][:3])
    M = [[1.0 * (i == j) - 2 * n[i] * n[j] / nn for j in range(4)] for i in range(3)] + [[0.0, 0.0, 0.0, 1.0]]
    B = mul([list(r) for r in zip(*M)], mul(A[qid], M))
    reflections.append({"quadric": qid, "mirror": mid, "status": "ok", "M": M, "B": B})
json.dump({"format": "qverify-eval/1", "scene": scene.get("name", ""), "precision": "double", "method": "direct",
           "shadows": shadows, "reflections": reflections, "skipped": []}, open(sys.argv[2], "w"))
