"""Shared setup of the small-problem experiments (bench/README, "LOBPCG and Chebyshev-filtered
subspace iteration at 10K x 100"): noisy torus mesh, cotangent stiffness L, lumped mass M,
shift-invert factorization with a column-solve counter, reference loader. The reference
(ref_eigsh.py) is written to and read from $WORKDIR (default /tmp)."""
import os
import time
import numpy as np
import scipy.sparse as sp
import scipy.sparse.linalg as sla

WORKDIR = os.environ.get("WORKDIR", "/tmp")
NEV = 100


def torus_mesh(nu=100, nv=100, R=1.0, r=0.4, noise=0.02, seed=12345):
    rng = np.random.default_rng(seed)
    u = 2 * np.pi * np.arange(nu) / nu
    v = 2 * np.pi * np.arange(nv) / nv
    U, V = np.meshgrid(u, v, indexing="ij")          # vertex id = i*nv + j
    rr = r * (1.0 + noise * rng.uniform(-1.0, 1.0, size=U.shape))  # radial move, 2% of r
    x = (R + rr * np.cos(V)) * np.cos(U)
    y = (R + rr * np.cos(V)) * np.sin(U)
    z = rr * np.sin(V)
    P = np.stack([x.ravel(), y.ravel(), z.ravel()], axis=1)
    I, J = np.meshgrid(np.arange(nu), np.arange(nv), indexing="ij")
    a = (I * nv + J).ravel()
    b = (((I + 1) % nu) * nv + J).ravel()
    c = (((I + 1) % nu) * nv + (J + 1) % nv).ravel()
    d = (I * nv + (J + 1) % nv).ravel()
    T = np.concatenate([np.stack([a, b, c], 1), np.stack([a, c, d], 1)], axis=0)
    return P, T


def assemble(P, T):
    n = P.shape[0]
    rows, cols, vals = [], [], []
    area = 0.5 * np.linalg.norm(np.cross(P[T[:, 1]] - P[T[:, 0]], P[T[:, 2]] - P[T[:, 0]]), axis=1)
    for k in range(3):                      # angle at corner k, opposite edge (i, j)
        i, j, o = T[:, (k + 1) % 3], T[:, (k + 2) % 3], T[:, k]
        e1, e2 = P[i] - P[o], P[j] - P[o]
        cot = np.einsum("ij,ij->i", e1, e2) / np.linalg.norm(np.cross(e1, e2), axis=1)
        w = 0.5 * cot
        rows += [i, j]; cols += [j, i]; vals += [-w, -w]
    rows = np.concatenate(rows); cols = np.concatenate(cols); vals = np.concatenate(vals)
    Loff = sp.coo_matrix((vals, (rows, cols)), shape=(n, n)).tocsr()
    L = (Loff - sp.diags(np.asarray(Loff.sum(axis=1)).ravel())).tocsr()
    L.sum_duplicates()
    mass = np.zeros(n)
    for k in range(3):
        np.add.at(mass, T[:, k], area / 3.0)
    return L, mass


class CountingSolver:
    """A^{-1} with A = L - sigma*M, counting every column solved."""
    def __init__(self, L, mass, sigma):
        t = time.perf_counter()
        self.lu = sla.splu((L - sigma * sp.diags(mass)).tocsc())
        self.t_factor = time.perf_counter() - t
        self.ncols = 0
        self.t_solve = 0.0

    def solve(self, B):
        t = time.perf_counter()
        B = np.asarray(B)
        self.ncols += 1 if B.ndim == 1 else B.shape[1]
        X = self.lu.solve(np.ascontiguousarray(B))
        self.t_solve += time.perf_counter() - t
        return X


def problem():
    P, T = torus_mesh()
    L, mass = assemble(P, T)
    return L, mass


def shifted_problem():
    """The problem, the reference eigenvalues and vectors, and the counting solver of
    L - sigma M at sigma = -1 / area: (L, mass, area, sigma, lam_ref, X_ref, solver)."""
    L, mass = problem()
    lam_ref, X_ref = reference()
    area = mass.sum()
    sigma = -1.0 / area
    return L, mass, area, sigma, lam_ref, X_ref, CountingSolver(L, mass, sigma)


def reference():
    f = os.path.join(WORKDIR, "ref_eigsh.npz")
    z = np.load(f)
    return z["lam"], z["X"]


def compare(lam, lam_ref, nev=NEV):
    """number of the nev smallest eigenvalues that agree to 1e-9 relative
    (the zero eigenvalue: |lam| <= 1e-9 * lam_ref[1])."""
    lam = np.sort(np.asarray(lam))[:nev]
    if len(lam) < nev:
        return 0, np.inf
    ok = np.empty(nev, bool)
    err = np.abs(lam - lam_ref[:nev])
    ok[0] = err[0] <= 1e-9 * lam_ref[1]
    rel = err[1:] / lam_ref[1:nev]
    ok[1:] = rel <= 1e-9
    return int(ok.sum()), float(rel.max())


def relres(L, mass, X, lam):
    R = L @ X - (mass[:, None] * X) * lam[None, :]
    MX = mass[:, None] * X
    den = np.abs(lam) * np.linalg.norm(MX, axis=0)
    return np.linalg.norm(R, axis=0) / np.maximum(den, 1e-300)
