"""SymPy's own derivation of tests/classics/*.toml, written to tests/fixtures/classics_sympy.json.

Each problem from its Lagrangian alone: the Euler–Lagrange equations by sympy's
euler_equations, the mass and stiffness matrices by differentiating them at rest, the modes as
the square roots of the eigenvalues of M⁻¹K, accelerations by solve, a state of rest by solve
of the static equation. The numbers are at each scene's [numeric] values.

    python3 tests/sympy/classics.py > tests/fixtures/classics_sympy.json

(SymPy 1.14.0, as tests/sympy/compare.sh installs it in a venv.)"""

import json
import sympy as sp
from sympy.calculus.euler import euler_equations

t = sp.Symbol("t")


def equations(L, qs):
    """The Euler–Lagrange expressions d/dt ∂L/∂q' − ∂L/∂q, one per coordinate."""
    return [-eq.lhs for eq in euler_equations(L, qs, t)]


def modes(L, qs, rest, values):
    """√λ of M⁻¹K at rest: M = ∂²L/∂q'², K = −∂²L/∂q² there, at the values."""
    rates = [q.diff(t) for q in qs]
    at = {**{q: rest[k] for k, q in enumerate(qs)}, **{r: 0 for r in rates}}
    M = sp.Matrix([[sp.diff(L, a, b).subs(at) for b in rates] for a in rates])
    K = sp.Matrix([[-sp.diff(L, a, b).subs(at) for b in qs] for a in qs])
    exact = {s: sp.Rational(str(x)) for s, x in values.items()}
    A = sp.simplify((M.inv() * K).subs(exact))
    lam = sorted((sp.N(v, 30) for v in A.eigenvals(multiple=True)), key=lambda v: float(v))
    return [float(sp.sqrt(v)) for v in lam]


def acceleration(L, q, values):
    (eq,) = equations(L, [q])
    (a,) = sp.solve(eq, q.diff(t, 2))
    return float(a.subs(values))


def main():
    out = {}
    f = sp.Function

    m, D, a, x0 = sp.symbols("m D a x0", positive=True)
    x = f("x")(t)
    L = m * x.diff(t) ** 2 / 2 - D * (1 - sp.exp(-a * (x - x0))) ** 2
    v = {m: 0.5, D: 2, a: 1.5, x0: 1}
    out["classic-morse"] = {"Omega": modes(L, [x], [x0], v)[0]}

    m, k, l0, g = sp.symbols("m k l0 g", positive=True)
    r, phi = f("r")(t), f("phi")(t)
    L = (m * (r.diff(t) ** 2 + r**2 * phi.diff(t) ** 2) / 2 + m * g * r * sp.cos(phi)
         - k * (r - l0) ** 2 / 2)
    v = {m: 0.2, k: 40, l0: 0.5, g: 9.81}
    w = modes(L, [r, phi], [l0 + m * g / k, 0], v)
    out["classic-elastic-pendulum"] = {"Omega_1": w[0], "Omega_2": w[1]}

    m, l, a, k, g = sp.symbols("m l a k g", positive=True)
    p1, p2 = f("phi1")(t), f("phi2")(t)
    L = (m * l**2 * (p1.diff(t) ** 2 + p2.diff(t) ** 2) / 2
         + m * g * l * (sp.cos(p1) + sp.cos(p2))
         - k * a**2 * (sp.sin(p1) - sp.sin(p2)) ** 2 / 2)
    v = {m: 0.3, l: 1.0, a: 0.4, k: 5, g: 9.81}
    w = modes(L, [p1, p2], [0, 0], v)
    out["classic-spring-coupled"] = {"Omega_1": w[0], "Omega_2": w[1]}

    M, R, g, alpha = sp.symbols("M R g alpha", positive=True)
    x = f("x")(t)
    L = M * x.diff(t) ** 2 / 2 + (M * R**2 / 2) * (x.diff(t) / R) ** 2 / 2 + M * g * x * sp.sin(alpha)
    out["classic-rolling-cylinder"] = {
        "acc": acceleration(L, x, {M: 2, R: 0.1, g: 9.81, alpha: 0.4})
    }

    m1, m2, I, R, g = sp.symbols("m1 m2 I R g", positive=True)
    L = (m1 + m2) * x.diff(t) ** 2 / 2 + I * (x.diff(t) / R) ** 2 / 2 + (m1 - m2) * g * x
    out["classic-atwood-pulley"] = {
        "acc": acceleration(L, x, {m1: 3, m2: 2, I: 0.02, R: 0.1, g: 9.81})
    }

    m, k, l0, w = sp.symbols("m k l0 w", positive=True)
    r = f("r")(t)
    L = m * (r.diff(t) ** 2 + w**2 * r**2) / 2 - k * (r - l0) ** 2 / 2
    v = {m: 0.1, k: 10, l0: 0.2, w: 5}
    (eq,) = equations(L, [r])
    rs = sp.Symbol("rs")
    static = eq.subs({r.diff(t, 2): 0, r.diff(t): 0}).subs(r, rs)
    (rest,) = sp.solve(static, rs)
    out["classic-spring-bead"] = {
        "rest_1": float(rest.subs(v)),
        "stable_1": modes(L, [r], [rest], v)[0] ** 2,
    }

    m1, m2, l, g = sp.symbols("m1 m2 l g", positive=True)
    L = ((m1 + m2) * l**2 * p1.diff(t) ** 2 / 2 + m2 * l**2 * p2.diff(t) ** 2 / 2
         + m2 * l**2 * p1.diff(t) * p2.diff(t) * sp.cos(p1 - p2)
         + (m1 + m2) * g * l * sp.cos(p1) + m2 * g * l * sp.cos(p2))
    w = modes(L, [p1, p2], [0, 0], {m1: 2, m2: 1, l: 0.5, g: 9.81})
    out["classic-unequal-double-pendulum"] = {"Omega_1": w[0], "Omega_2": w[1]}

    # The rod's moment about its end from the integral over its length, not from a table.
    m, Lr, g, s = sp.symbols("m L g s", positive=True)
    I = sp.integrate(m / Lr * s**2, (s, 0, Lr))
    th = f("theta")(t)
    L = I * th.diff(t) ** 2 / 2 + m * g * Lr / 2 * sp.cos(th)
    v = {m: 0.4, Lr: 1.2, g: 9.81}
    out["classic-physical-pendulum"] = {
        "I": float(I.subs(v)),
        "Omega": modes(L, [th], [0], v)[0],
    }

    m, k = sp.symbols("m k", positive=True)
    x1, x2 = f("x1")(t), f("x2")(t)
    L = m * (x1.diff(t) ** 2 + x2.diff(t) ** 2) / 2 - k * (x1**2 + (x2 - x1) ** 2 + x2**2) / 2
    w = modes(L, [x1, x2], [0, 0], {m: 0.5, k: 8})
    out["classic-three-springs"] = {"Omega_1": w[0], "Omega_2": w[1]}

    m, r, R, g = sp.symbols("m r R g", positive=True)
    ph = f("phi")(t)
    L = (m * (R - r) ** 2 * ph.diff(t) ** 2 / 2 + (m * r**2 / 2) * ((R - r) * ph.diff(t) / r) ** 2 / 2
         + m * g * (R - r) * sp.cos(ph))
    w = modes(L, [ph], [0], {m: 1, r: 0.05, R: 0.6, g: 9.81})[0]
    out["classic-cylinder-in-cylinder"] = {"Omega": w, "T": 2 * float(sp.pi) / w}

    # A spherical pendulum on its steady cone at theta0: phi' from the conserved p_phi put into
    # the tilt's equation, theta'' = F(theta), and the wobble's omega^2 = -F'(theta0).
    m, l, g, p, th0 = sp.symbols("m l g p theta0", positive=True)
    th, ph = f("theta")(t), f("phi")(t)
    L = m * l**2 / 2 * (th.diff(t) ** 2 + sp.sin(th) ** 2 * ph.diff(t) ** 2) + m * g * l * sp.cos(th)
    tilt, _ = equations(L, [th, ph])
    u, pp = sp.symbols("u pp")
    rate = pp / (m * l**2 * sp.sin(u) ** 2)
    flat = tilt.subs(ph.diff(t), rate).subs(th.diff(t, 2), sp.Symbol("acc")).subs(th, u)
    (acc,) = sp.solve(flat, sp.Symbol("acc"))
    cone = m * l**2 * sp.sin(th0) ** 2 * sp.sqrt(g / (l * sp.cos(th0)))
    v = {m: 1, l: sp.Rational(3, 2), g: sp.Rational(981, 100), th0: sp.Rational(3, 5)}
    w2 = -sp.diff(acc, u).subs(pp, cone).subs(u, th0)
    out["classic-spherical-pendulum-cone"] = {"w": float(sp.sqrt(w2.subs(v)))}

    # A heavy symmetric top precessing steadily: Lagrange's tilt equation with theta' = theta''
    # = 0 and the spin w3 = psi' + phi' cos(theta), a quadratic in phi'.
    M, g, l, I1, I3, w3, th0 = sp.symbols("M g l I1 I3 w3 theta", positive=True)
    th, ph, ps = f("theta")(t), f("phi")(t), f("psi")(t)
    L = (I1 / 2 * (th.diff(t) ** 2 + ph.diff(t) ** 2 * sp.sin(th) ** 2)
         + I3 / 2 * (ps.diff(t) + ph.diff(t) * sp.cos(th)) ** 2 - M * g * l * sp.cos(th))
    tilt = equations(L, [th, ph, ps])[0]
    rate = sp.Symbol("rate")
    steady = (tilt.subs(th.diff(t, 2), 0).subs(th.diff(t), 0)
              .subs(ps.diff(t), w3 - ph.diff(t) * sp.cos(th)).subs(ph.diff(t), rate).subs(th, th0))
    v = {M: 1, g: sp.Rational(981, 100), l: sp.Rational(1, 10), I1: sp.Rational(1, 50),
         I3: sp.Rational(1, 100), w3: 60, th0: sp.Rational(1, 2)}
    slow, fast = sorted(float(r) for r in sp.solve(steady.subs(v), rate))
    out["classic-heavy-top-precession"] = {"slow": slow, "fast": fast}

    print(json.dumps(out, indent=2, sort_keys=True))


main()
