#!/usr/bin/env python3
"""Why the explicit step uses Newmark's beta = 0 member (issue 11).

The amplification matrix of one step on the oscillator x'' = -omega^2 x,
for two readings of Newmark in explicit MPM:

  lagged   the equations as UCAM-MPM3D's documentation writes them (its steps
           14.2, 17.3, 18.2): the acceleration of the previous step a^(n-1)
           and the one from this step's forces a^n,
             v^(n+1) = v^n + dt ((1 - gamma) a^(n-1) + gamma a^n)
             x^(n+1) = x^n + dt v^n + dt^2 ((1/2 - beta) a^(n-1) + beta a^n)
  explicit Newmark's beta = 0 member in predictor form, what dealii-mpm
           does: the points carry v~ = v^n + (1 - gamma) dt a^n, the grid
           moves them with v~ + (gamma + 1/2) dt a^n,
             x^(n+1) = x^n + dt (v~^n + (gamma + 1/2) dt a^n)
             v~^(n+1) = v~^n + dt a^n
           (gamma = 1/2: central difference, the plain step exactly).

Prints the spectral radius per step (> 1: the energy grows) at omega dt
from 0.01 to 1.9 (the CFL number 0.5 puts the grid's highest mode near
omega dt = 1), as CSV.

  newmark_amplification.py
"""
import numpy as np

OMEGA_DT = (0.01, 0.1, 0.5, 1.0, 1.5, 1.9)


def lagged(gamma, beta, w):
    # State (x^n, v^n, a^(n-1)), dt = 1, a^n = -w^2 x^n.
    w2 = w * w
    return np.array([[1 - beta * w2, 1, 0.5 - beta],
                     [-gamma * w2, 1, 1 - gamma],
                     [-w2, 0, 0]])


def explicit(gamma, w):
    # State (x^n, v~^n).
    w2 = w * w
    return np.array([[1 - (gamma + 0.5) * w2, 1],
                     [-w2, 1]])


def radius(m):
    return max(abs(np.linalg.eigvals(m)))


def main():
    print("form,gamma,beta," + ",".join("omega_dt=%g" % w for w in OMEGA_DT))
    for gamma, beta in [(0.5, 0.25), (0.5, 0.5), (0.5, 0.0), (0.6, 0.3025),
                        (1.0, 0.5), (1.5, 2.0 / 3.0)]:
        print("lagged,%g,%.4g," % (gamma, beta) +
              ",".join("%.6f" % radius(lagged(gamma, beta, w)) for w in OMEGA_DT))
    for gamma in (0.5, 0.6, 0.75, 1.0):
        print("explicit,%g,0," % gamma +
              ",".join("%.6f" % radius(explicit(gamma, w)) for w in OMEGA_DT))


if __name__ == "__main__":
    main()
