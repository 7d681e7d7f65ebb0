#!/usr/bin/env python3
"""Minimax coefficients for warpcore's polynomial kernels (src/trig.rs).

Each kernel is f(t) = g(t) * P(t^2) with P a polynomial in s = t^2 (on [0, 1] for sin and cos); we run a
plain Remez exchange in s with mpmath at 60 digits, minimizing the *relative* error
|P(s) - F(s)| / F(s), where F(s) = f(sqrt s) / g(sqrt s):

  sin_q(t)  = sin(pi/4 t)          g = t, F(s) = sin(pi/4 sqrt s) / sqrt s
  cos_q(t)  = cos(pi/4 t)          g = 1, F(s) = cos(pi/4 sqrt s), constant term pinned to 1
  atan_q(z) = (4/pi) atan(z)       g = z, F(s) = (4/pi) atan(sqrt s) / sqrt s, on s <= 1/4

Then the coefficients are rounded to f32. The f32 evaluation error (Horner, no FMA) is what
matters and is measured exhaustively in the trig.rs unit tests, not here.

Usage: python3 tools/fit_kernels.py  (needs `pip install mpmath`)
"""
import mpmath as mp
import struct

mp.mp.dps = 60


def f32(x):
    return struct.unpack("<f", struct.pack("<f", float(x)))[0]


def remez(F, deg, pin_const=None, iters=60, smax=1):
    """Minimax P of degree `deg` in s on [0,1] for relative error (P - F)/F.
    If pin_const is given, P(0) is fixed to it and we fit the remaining terms."""
    n = deg + 1 if pin_const is None else deg  # unknown coefficients
    # initial reference: Chebyshev extrema, n + 1 points
    smax = mp.mpf(smax)
    pts = [smax / 2 - smax * mp.cos(mp.pi * k / n) / 2 for k in range(n + 1)]
    # avoid s = 0 exactly for the sqrt in F (use the limit via a tiny s)
    def FF(s):
        return F(s if s > 0 else mp.mpf(10) ** -40)

    def P(c, s):
        acc = mp.mpf(0)
        for a in reversed(c):
            acc = acc * s + a
        if pin_const is not None:
            acc = acc * s + pin_const
        return acc

    E = mp.mpf(0)
    for _ in range(iters):
        # solve P(x_i) - F(x_i) = (-1)^i E F(x_i) for coefficients and E
        A = mp.matrix(n + 1, n + 1)
        b = mp.matrix(n + 1, 1)
        for i, s in enumerate(pts):
            fs = FF(s)
            for j in range(n):
                A[i, j] = s ** (j + (0 if pin_const is None else 1))
            A[i, n] = -((-1) ** i) * fs
            b[i] = fs - (0 if pin_const is None else pin_const)
        sol = mp.lu_solve(A, b)
        c = [sol[j] for j in range(n)]
        E = sol[n]
        # new reference: extrema of the error on a fine grid, refined by golden search
        err = lambda s: (P(c, s) - FF(s)) / FF(s)
        grid = [smax * k / 4000 for k in range(4001)]
        vals = [err(s) for s in grid]
        ext = [0]
        for k in range(1, 4000):
            if (vals[k] - vals[k - 1]) * (vals[k + 1] - vals[k]) <= 0:
                ext.append(k)
        ext.append(4000)
        # keep alternating extrema with largest magnitude
        cand = [(grid[k], vals[k]) for k in ext]
        alt = []
        for s, v in cand:
            if alt and mp.sign(v) == mp.sign(alt[-1][1]):
                if abs(v) > abs(alt[-1][1]):
                    alt[-1] = (s, v)
            else:
                alt.append((s, v))
        while len(alt) > n + 1:
            if abs(alt[0][1]) < abs(alt[-1][1]):
                alt.pop(0)
            else:
                alt.pop()
        if len(alt) == n + 1:
            pts = [s for s, _ in alt]
    maxerr = max(abs((P(c, s) - FF(s)) / FF(s)) for s in [smax * k / 20000 for k in range(20001)])
    return c, maxerr


def show(name, c, maxerr, pin=None):
    print(f"{name}: max relative error of the real-coefficient polynomial {mp.nstr(maxerr, 4)}")
    if pin is not None:
        print(f"    c0 = {pin} (pinned)")
    for j, a in enumerate(c):
        print(f"    c{j + (0 if pin is None else 1)} = {f32(a)!r:>24}  # {mp.nstr(a, 20)}")


q = mp.pi / 4
sin_F = lambda s: mp.sin(q * mp.sqrt(s)) / mp.sqrt(s)
cos_F = lambda s: mp.cos(q * mp.sqrt(s))
atan_F = lambda s: mp.atan(mp.sqrt(s)) / mp.sqrt(s) / q

for deg in (3,):
    c, e = remez(sin_F, deg)
    show(f"sin(pi/4 t) = t * P(t^2), deg {deg}", c, e)
for deg in (4,):
    c, e = remez(cos_F, deg, pin_const=mp.mpf(1))
    show(f"cos(pi/4 t) = P(t^2), deg {deg}", c, e, pin=1)
# atan is evaluated after the reduction z -> (z - 1) / (z + 1) for z >= 1/2 (where z - 1 is
# exact), so the polynomial covers |z| <= 1/2 (the reduced branch gives |z| <= 1/3).

t8 = mp.mpf(1) / 4
for deg in (5, 6):
    c, e = remez(atan_F, deg, smax=t8)
    show(f"(4/pi) atan(z) = z * P(z^2) on |z| <= 1/2, deg {deg}", c, e)
