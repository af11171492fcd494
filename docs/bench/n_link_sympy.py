"""The n-link pendulum by SymPy's physics.mechanics, as `mechbook bench --links` compares it.

n equal point masses m on light links of length l, each angle q_k from the downward vertical:
the Lagrangian from the particles (Lagrangian), the equations (LagrangesMethod), the
linearisation about hanging at rest (linearize, A_and_B=True), and the normal-mode
frequencies at m = 1, l = 1, g = 9.81 as the imaginary parts of the eigenvalues of A.

    python n_link_sympy.py N

prints one JSON line: n, the seconds from the first import to the modes (the whole script,
start-up included), the seconds of the mechanics alone, the frequencies, slowest first, and
the process's peak memory in MiB.
"""

import json
import resource
import sys
import time

start = time.perf_counter()

import mpmath  # noqa: E402
import sympy as sp  # noqa: E402
from sympy.physics.mechanics import (  # noqa: E402
    LagrangesMethod,
    Lagrangian,
    Particle,
    Point,
    ReferenceFrame,
    dynamicsymbols,
)


def modes(n):
    mechanics = time.perf_counter()
    q = dynamicsymbols(f"q1:{n + 1}")
    qd = [qk.diff() for qk in q]
    m, l, g = sp.symbols("m l g", positive=True)
    frame = ReferenceFrame("N")
    pivot = Point("O")
    pivot.set_vel(frame, 0)
    particles = []
    previous = pivot
    for k in range(n):
        link = frame.orientnew(f"A{k}", "Axis", [q[k], frame.z])
        bob = previous.locatenew(f"P{k}", l * link.x)
        bob.v2pt_theory(previous, frame, link)
        particle = Particle(f"m{k}", bob, m)
        # frame.x points down: the height is −x.
        particle.potential_energy = -m * g * bob.pos_from(pivot).dot(frame.x)
        particles.append(particle)
        previous = bob
    method = LagrangesMethod(Lagrangian(frame, *particles), q)
    method.form_lagranges_equations()
    rest = {qk: 0 for qk in q} | {v: 0 for v in qd}
    a, _, _ = method.linearize(q_ind=q, qd_ind=qd, A_and_B=True, op_point=rest)
    numbers = a.subs({m: 1, l: 1, g: sp.Rational(981, 100)}).evalf()
    eigenvalues, _ = mpmath.eig(mpmath.matrix(numbers.tolist()))
    frequencies = sorted(float(abs(mpmath.im(z))) for z in eigenvalues if mpmath.im(z) > 0)
    return frequencies, time.perf_counter() - mechanics


n = int(sys.argv[1])
frequencies, mechanics = modes(n)
print(
    json.dumps(
        {
            "n": n,
            "seconds": time.perf_counter() - start,
            "mechanics_seconds": mechanics,
            "frequencies": frequencies,
            # Linux gives the peak resident set in KiB.
            "peak_mib": resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024,
        }
    )
)
