#!/usr/bin/env python3
"""The factor of safety of benchmarks/slope/slope.prm by limit equilibrium:
Bishop's simplified method of slices over circular slip surfaces, searched
over a grid of centres and radii (the surfaces may not pass below the rigid
base, y = 0). An independent check of the reference value the strength
reduction is compared with (Griffiths and Lane 1999 quote 1.38 from Bishop
and Morgenstern's charts for this slope).

  python3 benchmarks/slope/limit_equilibrium.py   # prints F and the circle
"""
import math

H, WIDTH, CREST = 10.0, 20.0, 30.0      # height, slope run (2:1), back
GAMMA, C, PHI = 2000 * 10.0, 1e4, math.radians(20)


def surface(x):
    """Ground level: the toe at x = 0, the crest at x = 20."""
    return 0.0 if x <= 0 else (x / 2 if x <= WIDTH else H)


def bishop(xc, yc, r, slices=200):
    """F of the circle (centre, radius), or None if it leaves the soil."""
    if yc - r < -1e-9:
        return None                     # below the base
    # Where the circle's lower arc meets the ground: scan.
    left = xc - r
    right = min(xc + r, CREST)
    xs = [left + (right - left) * (i + 0.5) / slices for i in range(slices)]
    b = (right - left) / slices
    rows = []
    for x in xs:
        depth = surface(x) - (yc - math.sqrt(max(r * r - (x - xc) ** 2, 0)))
        if depth > 0:
            alpha = math.asin((x - xc) / r)
            rows.append((GAMMA * depth * b, alpha))
    if len(rows) < 10 or xc + r > CREST:
        return None                     # too small, or through the back
    driving = sum(w * math.sin(a) for w, a in rows)
    if driving <= 0:
        return None
    f = 1.5
    for _ in range(100):
        resisting = sum((C * b + w * math.tan(PHI)) /
                        (math.cos(a) + math.sin(a) * math.tan(PHI) / f)
                        for w, a in rows)
        f_new = resisting / driving
        if abs(f_new - f) < 1e-10:
            break
        f = f_new
    return f


def main():
    best = (float("inf"), None)
    for i in range(0, 61):
        xc = -5 + 0.5 * i
        for j in range(0, 61):
            yc = 5 + 0.5 * j
            for k in range(1, 81):
                r = 0.5 * k
                f = bishop(xc, yc, r)
                if f is not None and f < best[0]:
                    best = (f, (xc, yc, r))
    # Refine around the best circle.
    f, (xc, yc, r) = best
    step = 0.25
    while step > 1e-3:
        improved = False
        for dx in (-step, 0, step):
            for dy in (-step, 0, step):
                for dr in (-step, 0, step):
                    g = bishop(xc + dx, yc + dy, r + dr)
                    if g is not None and g < f - 1e-12:
                        f, xc, yc, r, improved = g, xc + dx, yc + dy, r + dr, True
        if not improved:
            step /= 2
    print("factor_of_safety,%.4f" % f)
    print("circle_centre_x,%.3f\ncircle_centre_y,%.3f\nradius,%.3f"
          % (xc, yc, r))


if __name__ == "__main__":
    main()
