#!/usr/bin/python3
"""Exact reference solutions for the JWL detonation scenes (verification.md T8a, T8b).

usage: /usr/bin/python3 scripts/verification/detonation_reference.py [HE ...]
       (HE among TNT, PETN, CompB; default all three)

Computed from the JWL model itself (no handbook numbers enter except the constants):
* CJ state: tangency of the Rayleigh line D^2 = p / (rho0 (1 - V)) to the products Hugoniot
  through (V = 1, E = E0, p = 0), i.e. the minimum of D over V;
* isentrope through CJ: p_s(V) = A e^{-R1 V} + B e^{-R2 V} + C V^{-(1 + w)},
  sound speed c^2 = -(V^2 / rho0) p_s'(V);
* planar Taylor wave behind a detonation lit at a rigid wall (T8a): simple wave u + c = x/t with
  u = u_CJ - int_{V_CJ}^{V} sqrt(-p_s'/rho0) dV, stagnant wall region where u = 0;
* Taylor (1950) similarity solution of the cylindrical (j = 1) and spherical (j = 2) detonation
  (T8b): with U = u/D, Cs = c/D, xi = r/(Dt) and a parameter tau,
      dxi/dtau = xi [Cs^2 - (U - xi)^2],  dU/dtau = -j U Cs^2,  dV/dtau = j V U (xi - U),
  integrated (scipy DOP853, checked against fixed-step RK4) from the CJ point until U -> 0: the quiescent core r < xi0 D t.

Also importable: `model(name)` returns the functions the plot scripts use.
"""
import math
import sys

import numpy as np
from scipy.integrate import solve_ivp

# Dobratz & Crawford, LLNL Explosives Handbook UCRL-52997 Change 2 (1985), as in verification.md T8
CONSTANTS = {
    "TNT": dict(rho0=1630.0, A=371.2e9, B=3.231e9, R1=4.15, R2=0.95, w=0.30, E0=7.0e9),
    "PETN": dict(rho0=1770.0, A=617.0e9, B=16.926e9, R1=4.40, R2=1.20, w=0.25, E0=10.1e9),
    "CompB": dict(rho0=1717.0, A=524.2e9, B=7.678e9, R1=4.20, R2=1.10, w=0.34, E0=8.5e9),
}


class Jwl:
    """JWL products of one explosive: CJ state, CJ isentrope, simple-wave and similarity flows."""

    def __init__(self, rho0, A, B, R1, R2, w, E0):
        self.rho0, self.A, self.B, self.R1, self.R2, self.w, self.E0 = rho0, A, B, R1, R2, w, E0
        self._cj()
        self._sim = {}
        self._planar = {}
        e1, e2 = math.exp(-R1 * self.Vcj), math.exp(-R2 * self.Vcj)
        self.C = (self.pcj - A * e1 - B * e2) * self.Vcj ** (1 + w)

    def hugoniot(self, V):
        A, B, R1, R2, w = self.A, self.B, self.R1, self.R2, self.w
        cold = A * (1 - w / (R1 * V)) * math.exp(-R1 * V) + B * (1 - w / (R2 * V)) * math.exp(-R2 * V)
        return (cold + w * self.E0 / V) / (1 - w * (1 - V) / (2 * V))

    def _cj(self):
        vmin = self.w / (2 + self.w)
        d2 = lambda V: self.hugoniot(V) / (self.rho0 * (1 - V))
        grid = np.linspace(vmin, 1, 4001)[1:-1]
        vals = [d2(V) if self.hugoniot(V) > 0 else np.inf for V in grid]
        k = int(np.argmin(vals))
        a, b = grid[k - 1], grid[k + 1]
        g = 0.5 * (math.sqrt(5) - 1)
        for _ in range(200):  # golden section
            x1, x2 = b - g * (b - a), a + g * (b - a)
            if d2(x1) < d2(x2):
                b = x2
            else:
                a = x1
        self.Vcj = 0.5 * (a + b)
        self.pcj = self.hugoniot(self.Vcj)
        self.D = math.sqrt(d2(self.Vcj))
        self.ucj = self.D * (1 - self.Vcj)
        self.ccj = self.D - self.ucj
        self.rhocj = self.rho0 / self.Vcj

    # CJ isentrope
    def ps(self, V):
        return self.A * np.exp(-self.R1 * V) + self.B * np.exp(-self.R2 * V) + self.C * V ** (-(1 + self.w))

    def dps(self, V):
        return (-self.R1 * self.A * np.exp(-self.R1 * V) - self.R2 * self.B * np.exp(-self.R2 * V)
                - (1 + self.w) * self.C * V ** (-(2 + self.w)))

    def c(self, V):
        return np.sqrt(-(V * V / self.rho0) * self.dps(V))

    def gamma_cj(self):
        return self.rhocj * self.ccj ** 2 / self.pcj

    # planar Taylor wave (T8a)
    def planar(self, n=20001, vmax=3.0):
        """Returns V grid, u(V), c(V) along the CJ isentrope and the wall state (V_w, p_w, c_w)."""
        if (n, vmax) in self._planar:
            return self._planar[(n, vmax)]
        V = np.linspace(self.Vcj, vmax, n)
        f = np.sqrt(-self.dps(V) / self.rho0)
        integral = np.concatenate([[0], np.cumsum(0.5 * (f[1:] + f[:-1]) * np.diff(V))])
        u = self.ucj - integral
        k = int(np.argmax(u <= 0))
        # linear interpolation of the wall state u = 0
        t = u[k - 1] / (u[k - 1] - u[k])
        Vw = V[k - 1] + t * (V[k] - V[k - 1])
        self._planar[(n, vmax)] = (V[:k], u[:k], self.c(V[:k]), (Vw, float(self.ps(Vw)), float(self.c(Vw))))
        return self._planar[(n, vmax)]

    def planar_profile(self, s):
        """p / P_CJ at x/(D t) = s (array) for the planar wave lit at a rigid wall."""
        V, u, c, (Vw, pw, cw) = self.planar()
        xi = (u + c) / self.D  # decreasing from 1 at CJ to the wall value
        s = np.asarray(s, dtype=float)
        p = np.interp(s, xi[::-1], self.ps(V)[::-1], left=pw, right=self.pcj)
        p = np.where(s <= cw / self.D, pw, p)
        return p / self.pcj

    # Taylor (1950) similarity solution (T8b)
    def similarity(self, j):
        """Integrates the similarity ODEs from CJ (DOP853, rtol 1e-11) until U = 1e-12 U_CJ;
        returns arrays xi, U, V from the front to the core, densely sampled (cached per j)."""
        if j in self._sim:
            return self._sim[j]

        def rhs(_, y):
            xi, U, V = y
            cs = self.c(V) / self.D
            return [xi * (cs * cs - (U - xi) ** 2), -j * U * cs * cs, j * V * U * (xi - U)]

        u0 = self.ucj / self.D
        stop = lambda _, y: y[1] - 1e-12 * u0
        stop.terminal = True
        sol = solve_ivp(rhs, [0, 1e5], [1.0, u0, self.Vcj], method="DOP853", rtol=1e-11,
                        atol=1e-14, events=stop, dense_output=True)
        # the solution leaves the CJ point with an infinite slope dU/dxi: sample densely there
        tau = np.concatenate([np.linspace(0, 1, 20001), np.linspace(1, sol.t[-1], 20001)[1:]])
        self._sim[j] = tuple(sol.sol(tau))
        return self._sim[j]

    def similarity_core(self, j):
        xi, U, V = self.similarity(j)
        return float(self.ps(V[-1])), float(xi[-1])

    def similarity_profile(self, j, s):
        """p / P_CJ at xi = s (array) of the similarity solution (core pressure inside xi0)."""
        xi, U, V = self.similarity(j)
        p = self.ps(V)
        s = np.asarray(s, dtype=float)
        # xi decreases monotonically from 1 to xi0 along the solution
        return np.interp(s, xi[::-1], p[::-1], left=p[-1], right=self.pcj) / self.pcj


    def planar_velocity(self, s):
        """u / D at x/(D t) = s of the planar wave (0 in the stagnant region and ahead)."""
        V, u, c, (Vw, pw, cw) = self.planar()
        xi = (u + c) / self.D
        s = np.asarray(s, dtype=float)
        U = np.interp(s, xi[::-1], (u / self.D)[::-1], left=0.0, right=0.0)
        return np.where((s <= cw / self.D) | (s > 1), 0.0, U)

    def similarity_velocity(self, j, s):
        """u / D at xi = s of the similarity solution (0 in the core and ahead)."""
        xi, U, V = self.similarity(j)
        s = np.asarray(s, dtype=float)
        return np.where(s > 1, 0.0, np.interp(s, xi[::-1], U[::-1], left=0.0, right=0.0))

    def particle_history(self, r0, times, velocity, profile):
        """p / P_CJ at a material particle that starts at r0 (> 0), for increasing `times`:
        the particle is at rest until the front arrives at t = r0/D, then moves with
        dr/dt = D U(r/(Dt)) (midpoint rule, steps of 0.1 % of t: the flow is self-similar)."""
        out = np.zeros(len(times))
        r, t = r0, r0 / self.D
        for k, tk in enumerate(times):
            while t < tk:
                dt = min(tk - t, 1e-3 * t)
                rm = r + 0.5 * dt * self.D * float(velocity(r / (self.D * t)))
                r += dt * self.D * float(velocity(rm / (self.D * (t + 0.5 * dt))))
                t += dt
            out[k] = float(profile(r / (self.D * tk))) if tk >= r0 / self.D else 0.0
        return out


def model(name):
    return Jwl(**CONSTANTS[name])


def main(names):
    xs = [0.6, 0.7, 0.8, 0.9, 0.95]
    print("| HE | D [m/s] | P_CJ [GPa] | V_CJ | rho_CJ | u_CJ | c_CJ | Gamma_CJ | wall p_w [GPa] (p_w/P_CJ) | c_w/D |")
    print("|---|---|---|---|---|---|---|---|---|---|")
    for n in names:
        m = model(n)
        _, _, _, (Vw, pw, cw) = m.planar()
        print(f"| {n} | {m.D:.1f} | {m.pcj / 1e9:.3f} | {m.Vcj:.5f} | {m.rhocj:.1f} | {m.ucj:.1f} | "
              f"{m.ccj:.1f} | {m.gamma_cj():.3f} | {pw / 1e9:.3f} ({pw / m.pcj:.4f}) | {cw / m.D:.4f} |")
    print()
    print("planar Taylor wave p/P_CJ at x/(Dt) = " + " / ".join(str(x) for x in xs))
    for n in names:
        m = model(n)
        print(f"  {n}: " + " / ".join(f"{v:.3f}" for v in m.planar_profile(xs)))
    print()
    print("| HE | geometry | core pressure [GPa] (p/P_CJ) | core radius xi0 | p/P_CJ at xi = "
          + "/".join(str(x) for x in xs) + " |")
    print("|---|---|---|---|---|")
    for n in names:
        m = model(n)
        for j, geom in ((1, "cylinder"), (2, "sphere")):
            pc, xi0 = m.similarity_core(j)
            prof = m.similarity_profile(j, xs)
            print(f"| {n} | {geom} | {pc / 1e9:.3f} ({pc / m.pcj:.4f}) | {xi0:.4f} | "
                  + "/".join(f"{v:.3f}" for v in prof) + " |")
    # check of the method on the gamma-law (gamma = 3) case: p_w/p_CJ = 8/27, c_w = D/2
    g = Jwl(rho0=1000.0, A=0.0, B=0.0, R1=1.0, R2=1.0, w=2.0, E0=1e9)
    _, _, _, (Vw, pw, cw) = g.planar()
    print(f"\ngamma = 3 check (JWL with A = B = 0, w = 2): p_w/P_CJ = {pw / g.pcj:.4f} (exact 8/27 = "
          f"{8 / 27:.4f}), c_w/D = {cw / g.D:.4f} (exact 0.5)")


if __name__ == "__main__":
    main(sys.argv[1:] or ["TNT", "PETN", "CompB"])
