"""The REFERENCE.md comparison set derived with SymPy: the cube about a corner with its
eigenvalues and its centre tensor by the parallel-axis theorem, the flat and the tilted hoop
(general alpha) with the tilted hoop's eigenvalues, and the symmetric-top residual.

Prints the best of N wall times in seconds (the cache is cleared before each run) and checks the
results, so that a wrong derivation cannot be fast by accident.
"""
import sys
import time

import sympy as sp
from sympy.core.cache import clear_cache


def tensor(integrand_of, limits):
    return sp.Matrix(3, 3, lambda j, k: sp.simplify(sp.integrate(integrand_of(j, k), *limits)))


def cube():
    x, y, z, a, m = sp.symbols("x y z a m", positive=True)
    rho = m / a**3
    r = [x, y, z]
    r2 = x**2 + y**2 + z**2
    corner = tensor(
        lambda j, k: rho * (r2 * (1 if j == k else 0) - r[j] * r[k]),
        [(x, 0, a), (y, 0, a), (z, 0, a)],
    )
    eig = corner.eigenvals()
    d = sp.Matrix([a / 2, a / 2, a / 2])
    centre = sp.simplify(corner - m * (d.dot(d) * sp.eye(3) - d * d.T))
    assert corner[0, 0] == sp.Rational(2, 3) * m * a**2
    assert centre == sp.Rational(1, 6) * m * a**2 * sp.eye(3)
    assert sorted(eig.values()) == [1, 2]
    return corner, eig, centre


def hoop(tilted):
    th, R, M, alpha = sp.symbols("theta R M alpha", positive=True)
    lam = M / (2 * sp.pi * R)
    p = sp.Matrix([R * sp.cos(th), R * sp.sin(th), 0])
    if tilted:
        rot = sp.Matrix(
            [[sp.cos(alpha), 0, sp.sin(alpha)], [0, 1, 0], [-sp.sin(alpha), 0, sp.cos(alpha)]]
        )
        p = rot * p
    r2 = sp.simplify(p.dot(p))
    t = tensor(
        lambda j, k: lam * R * (r2 * (1 if j == k else 0) - p[j] * p[k]),
        [(th, 0, 2 * sp.pi)],
    )
    eig = {sp.simplify(k): v for k, v in t.eigenvals().items()} if tilted else None
    if tilted:
        assert eig == {M * R**2: 1, M * R**2 / 2: 2}, eig
    else:
        assert t == sp.diag(M * R**2 / 2, M * R**2 / 2, M * R**2)
    return t, eig


def symmetric_top():
    I1, I3, w3, A, t, theta = sp.symbols("I1 I3 w3 A t theta", positive=True)
    beta = (I3 - I1) / I1
    w = [A * sp.cos(beta * w3 * t + theta), A * sp.sin(beta * w3 * t + theta), w3]
    inertia = [I1, I1, I3]
    L = [inertia[i] * w[i] for i in range(3)]
    cross = [w[1] * L[2] - w[2] * L[1], w[2] * L[0] - w[0] * L[2], w[0] * L[1] - w[1] * L[0]]
    residual = [sp.simplify(inertia[i] * sp.diff(w[i], t) + cross[i]) for i in range(3)]
    assert residual == [0, 0, 0], residual
    return residual


def run_all():
    cube()
    hoop(False)
    hoop(True)
    symmetric_top()


def main():
    runs = int(sys.argv[1]) if len(sys.argv) > 1 else 3
    times = []
    for _ in range(runs):
        clear_cache()
        start = time.perf_counter()
        run_all()
        times.append(time.perf_counter() - start)
    print(f"sympy {sp.__version__}: best {min(times):.4f} s of {runs} ({', '.join(f'{t:.4f}' for t in times)})")


if __name__ == "__main__":
    main()
