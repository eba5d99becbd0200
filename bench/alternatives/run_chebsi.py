#!/usr/bin/python3
"""Method B: Chebyshev-filtered subspace iteration on Op = A^{-1} M,
A = L - sigma*M, sigma = -1/area.  theta = 1/(lambda - sigma); want the 100
largest theta (= 100 smallest lambda).

usage: run_chebsi.py p d [defl_every] [maxdeg_growth]
  p          total block: 1 (constant, pre-locked) + locked + active
  d          Chebyshev degree (applications of Op per active column per outer it)
  defl_every project locked vectors out of the filter iterate every s Op
             applications (1 = every application; 0 = only after the filter)
  maxgrowth  optional: cap the degree so that the filter's amplification ratio
             between the largest active Ritz theta and the p-th is <= this
             (e.g. 1e8); 0 = fixed degree d.

Filter damps [0, theta_cut], theta_cut = smallest active Ritz theta (p-th Ritz
value), normalised at the largest active Ritz theta.  M-orthonormalisation by
Cholesky QR twice (Householder-QR fallback if Cholesky fails), Rayleigh-Ritz
with L (M-orthonormal basis), locking at relative residual <= 1e-10.
"""
import sys
import time
import numpy as np
import scipy.linalg as la
from common import shifted_problem, compare, relres, NEV

p = int(sys.argv[1]); d = int(sys.argv[2])
s_defl = int(sys.argv[3]) if len(sys.argv) > 3 else 1
maxgrowth = float(sys.argv[4]) if len(sys.argv) > 4 else 0.0
TOL = 1e-10
L, mass, area, sigma, lam_ref, X_ref, S = shifted_problem()
n = L.shape[0]
sqm = np.sqrt(mass)
c1 = np.ones((n, 1)) / np.sqrt(area)           # M-normalised null vector, lambda = 0
flops = {"defl": 0.0, "orth": 0.0, "rr_gemm": 0.0, "eig": 0.0}
nfallback = 0


def Op(W):
    return S.solve(mass[:, None] * W)


def proj(W, X):
    """W <- W - X (X^T M W)  (one pass)"""
    if X.shape[1]:
        W -= X @ (X.T @ (mass[:, None] * W))
    return W


def chol_qr(W):
    G = W.T @ (mass[:, None] * W)
    G = 0.5 * (G + G.T)
    R = la.cholesky(G, lower=False)
    return la.solve_triangular(R, W.T, trans="T", lower=False).T


def m_orthonormalize(W):
    global nfallback
    m = W.shape[1]
    try:
        W = chol_qr(chol_qr(W))
    except la.LinAlgError:
        nfallback += 1
        Q, _ = np.linalg.qr(sqm[:, None] * W)
        W = chol_qr(Q / sqm[:, None])
    flops["orth"] += 4.0 * n * m * m
    return W


def rayleigh_ritz(W):
    m = W.shape[1]
    LW = L @ W
    H = W.T @ LW
    lam, V = la.eigh(0.5 * (H + H.T))
    flops["rr_gemm"] += 4.0 * n * m * m       # H (2nm^2) + rotation W V (2nm^2)
    flops["eig"] += 9.0 * m ** 3
    return lam, W @ V


def cheb_filter(W, deg, th_cut, th0, X):
    """p(Op) W with p = T_deg((2 th - th_cut)/th_cut) / T_deg(x(th0))."""
    c = e = 0.5 * th_cut
    x0 = (th0 - c) / e
    k, m = X.shape[1], W.shape[1]
    Z = Op(W); Z -= c1 @ (c1.T @ (mass[:, None] * Z))
    if s_defl == 1 or (s_defl > 1 and deg >= 1 and 1 % s_defl == 0):
        proj(Z, X); flops["defl"] += 4.0 * n * k * m
    rp, r = 1.0, x0
    Yp, Y = W, (Z - c * W) / (e * x0)
    for j in range(2, deg + 1):
        rn = 2 * x0 * r - rp
        Z = Op(Y); Z -= c1 @ (c1.T @ (mass[:, None] * Z))
        if s_defl >= 1 and j % s_defl == 0:
            proj(Z, X); flops["defl"] += 4.0 * n * k * m
        Yn = (2 * r / rn) * (Z - c * Y) / e - (rp / rn) * Yp
        Yp, Y, rp, r = Y, Yn, r, rn
    return Y


def cheb_T(deg, x):
    return np.cosh(deg * np.arccosh(x)) if x >= 1 else np.cos(deg * np.arccos(x))


rng = np.random.default_rng(7)
t0 = time.perf_counter()
W = rng.standard_normal((n, p - 1))
W -= c1 @ (c1.T @ (mass[:, None] * W))
W = Op(W)                                   # one plain shift-invert step to start
W -= c1 @ (c1.T @ (mass[:, None] * W))
W = m_orthonormalize(W)
lamW, W = rayleigh_ritz(W)
X = np.zeros((n, 0)); lamX = np.zeros(0)
hist = []
it = 0
while X.shape[1] + 1 < NEV and it < 40:
    it += 1
    k, m = X.shape[1], W.shape[1]
    th = 1.0 / (lamW - sigma)
    th_cut, th0 = th[-1], th[0]
    deg = d
    if maxgrowth > 0:                     # cap amplification spread inside the active block
        while deg > 1 and cheb_T(deg, 2 * th0 / th_cut - 1) > maxgrowth * cheb_T(deg, 1.0):
            deg -= 1
    a0 = S.ncols
    W = cheb_filter(W, deg, th_cut, th0, X)
    proj(W, X); proj(W, X); flops["defl"] += 8.0 * n * k * m
    W -= c1 @ (c1.T @ (mass[:, None] * W))
    W = m_orthonormalize(W)
    lamW, W = rayleigh_ritz(W)
    rr = relres(L, mass, W, lamW)
    nrem = NEV - 1 - k
    lock = np.zeros(m, bool)
    lock[:nrem] = rr[:nrem] <= TOL
    X = np.hstack([X, W[:, lock]]); lamX = np.concatenate([lamX, lamW[lock]])
    W = W[:, ~lock]; lamW = lamW[~lock]; rr = rr[~lock]
    hist.append((it, deg, m, S.ncols - a0, int(lock.sum()), X.shape[1] + 1,
                 float(np.max(rr[:max(1, nrem - lock.sum())])) if W.shape[1] else 0.0,
                 time.perf_counter() - t0))
t_total = time.perf_counter() - t0
lam_all = np.concatenate([[0.0], lamX])
nok, maxrel = compare(lam_all, lam_ref)
print(f"p={p} d={d} defl_every={s_defl} maxgrowth={maxgrowth:g}: outer_its={it} "
      f"applications={S.ncols} converged={X.shape[1]+1} agree={nok}/100 maxrel={maxrel:.1e} "
      f"time={t_total:.2f}s (solves {S.t_solve:.2f}s) qr_fallbacks={nfallback}")
for h in hist:
    print("  it %d deg %d active %d solves %d locked+%d total %d worst_unlocked_res %.1e t=%.2f" % h)
tot = sum(flops.values())
print("  dense GF: " + " ".join(f"{k}={v/1e9:.2f}" for k, v in flops.items()) + f" total={tot/1e9:.2f}")
