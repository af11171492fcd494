"""SymPy's rolling disc (sympy.physics.mechanics examples, 3-1-2 rotations: yaw q1, lean q2,
spin q3) at seeded random states: the accelerations q1'', q2'', q3'' from Kane's method with
the contact point at rest, and from the Lagrange's-method example, whose Lagrangian has the
rolling constraint substituted in. Prints JSON, the fixture tests/fixtures/rolling_disc_sympy.json:

    python3 tests/sympy/rolling_disc.py > tests/fixtures/rolling_disc_sympy.json

(SymPy 1.14.0, as tests/sympy/compare.sh installs it in a venv.)"""
import json
import random

import sympy
from sympy import Matrix, cos, lambdify, sin, symbols
from sympy.physics.mechanics import (KanesMethod, LagrangesMethod, Lagrangian, Point,
                                     ReferenceFrame, RigidBody, dynamicsymbols, inertia)

q1, q2, q3, u1, u2, u3 = dynamicsymbols('q1 q2 q3 u1 u2 u3')
q1d, q2d, q3d = dynamicsymbols('q1 q2 q3', 1)
r, m, g = symbols('r m g')
VALUES = {m: 2.0, r: 0.5, g: 9.81}


def frames():
    N = ReferenceFrame('N')
    Y = N.orientnew('Y', 'Axis', [q1, N.z])
    L = Y.orientnew('L', 'Axis', [q2, Y.x])
    R = L.orientnew('R', 'Axis', [q3, L.y])
    return N, Y, L, R


def kane():
    """Kane's method, generalised speeds the disc's angular velocity in the lean frame."""
    N, Y, L, R = frames()
    w_qd = R.ang_vel_in(N)
    R.set_ang_vel(N, u1 * L.x + u2 * L.y + u3 * L.z)
    contact = Point('C')
    contact.set_vel(N, 0)
    centre = contact.locatenew('Dmc', r * L.z)
    centre.v2pt_theory(contact, N, R)
    disc = RigidBody('disc', centre, R, m,
                     (inertia(L, m * r**2 / 4, m * r**2 / 2, m * r**2 / 4), centre))
    kd = [(R.ang_vel_in(N) - w_qd).dot(v) for v in L]
    km = KanesMethod(N, q_ind=[q1, q2, q3], u_ind=[u1, u2, u3], kd_eqs=kd)
    km.kanes_equations([disc], [(centre, -m * g * Y.z)])
    udot = km.mass_matrix.LUsolve(km.forcing)
    qd_of_u = Matrix([km.kindiffdict()[v] for v in (q1d, q2d, q3d)])
    u_of_qd = sympy.solve(kd, [u1, u2, u3])
    # q'' = ∂q'/∂q · q' + ∂q'/∂u · u'.
    qdd = qd_of_u.jacobian([q1, q2, q3]) * qd_of_u + qd_of_u.jacobian([u1, u2, u3]) * udot
    state = [q1, q2, q3, q1d, q2d, q3d]
    qdd = qdd.subs(u_of_qd).subs(VALUES)
    plain = symbols('a1 a2 a3 b1 b2 b3')
    return lambdify(plain, qdd.subs(dict(zip(state[3:], plain[3:]))).subs(dict(zip(state[:3], plain[:3]))))


def lagrange_substituted():
    """The Lagrange's-method example: the centre's velocity from the contact point at rest."""
    N, Y, L, R = frames()
    contact = Point('C')
    contact.set_vel(N, 0)
    centre = contact.locatenew('Dmc', r * L.z)
    centre.v2pt_theory(contact, N, R)
    disc = RigidBody('disc', centre, R, m,
                     (inertia(L, m * r**2 / 4, m * r**2 / 2, m * r**2 / 4), centre))
    disc.potential_energy = m * g * r * cos(q2)
    lm = LagrangesMethod(Lagrangian(N, disc), [q1, q2, q3])
    lm.form_lagranges_equations()
    qdd = lm.mass_matrix.LUsolve(lm.forcing).subs(VALUES)
    plain = symbols('a1 a2 a3 b1 b2 b3')
    state = [q1, q2, q3, q1d, q2d, q3d]
    return lambdify(plain, qdd.subs(dict(zip(state[3:], plain[3:]))).subs(dict(zip(state[:3], plain[:3]))))


def main():
    rng = random.Random(20261127)
    kane_qdd, lagrange_qdd = kane(), lagrange_substituted()
    states = []
    for _ in range(8):
        s = [rng.uniform(-3, 3), rng.uniform(-1.2, 1.2), rng.uniform(-3, 3),
             rng.uniform(-2, 2), rng.uniform(-2, 2), rng.uniform(-4, 4)]
        states.append({
            "q": s,
            "kane": [float(v) for v in kane_qdd(*s)],
            "lagrange_substituted": [float(v) for v in lagrange_qdd(*s)],
        })
    print(json.dumps({
        "sympy": sympy.__version__,
        "values": {"m": 2.0, "r": 0.5, "g": 9.81},
        "order": ["q1", "q2", "q3", "q1'", "q2'", "q3'"],
        "states": states,
    }, indent=1))


main()
