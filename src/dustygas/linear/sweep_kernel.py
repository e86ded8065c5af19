"""Compiled integration of shearing waves for parameter sweeps (thesis §4.6.2, eq. 4.35).

One shearing wave obeys dX/dt = L(k(t)) X with k_x(t) = k_x0 + (3/2) k_y t
(:mod:`dustygas.linear.shearing_wave`, which integrates it with :func:`scipy.integrate.solve_ivp`
and serves as the independent reference of the tests). A sweep integrates 10⁴–10⁶ of them, so
here the whole integration of a chunk of waves is one compiled loop:

* the explicit embedded Runge–Kutta pair of Dormand & Prince (1980), 5th order with a 4th-order
  error estimate, and the step-size controller of Hairer, Nørsett & Wanner (1993, §II.4, the
  PI controller of their code DOPRI5: exponents 0.2 − 0.75 β and β = 0.04, safety 0.9, step
  ratio in [0.2, 10]); the error norm is the largest component of |err|/(atol + rtol·|y|);
* every accepted step is checked for a maximum of the energy E(t) inside it (dE/dt changes
  sign between its ends); there the cubic Hermite interpolant of the state (values and
  derivatives at both ends, error O(h⁴)) is maximised by golden-section search, so the peak
  amplification is not limited to the step grid;
* the step lands exactly on the start and end of the averaging window;
* with k_z = 0 (and no vertical drift) the vertical velocities decouple and the planar system of
  thesis eq. 4.35 (3 + 3N unknowns) is integrated; its fastest eigenmode starts the wave;
* the compressible operator is affine in t (every k_x-dependent entry is linear in k_x(t)), so
  it is stored once per wave as two sparse lists, L(t) y = A y + t (B y), instead of being rebuilt at every stage.

The drag terms make the system stiff for τ_s ≪ 1 (rate 1/τ_s) and sound waves make it
oscillatory (frequency c_s|k|): an explicit method needs h ≲ 3/max(c_s|k|, (1 + μ)/τ_s), which
the controller finds by itself. The work per wave therefore grows with c_s|k| t_end and
(1 + μ) t_end/τ_s; the sweep records the accepted steps of every wave.

Energy (module :mod:`dustygas.linear.shearing_wave`): E = ½(|u|² + c_s²|δρ_g|² + Σ_j μ_j|w_j|²);
in the internal variables (h = c_s δρ_g, or the two in-plane gas amplitudes a_1, a_2 in the
incompressible limit) it is ½ Σ_i e_i |x_i|² with weights e_i ∈ {0, 1, μ_j}.
"""

from __future__ import annotations

import math

import numba
import numpy as np

from .shearing_wave import SHEAR_RATE, _build

__all__ = ["INITIAL_STATES", "integrate_chunk", "RESULT_FIELDS"]

#: name -> code of the initial states of a sweep
INITIAL_STATES = {"fastest": 0, "vortical": 1, "dust": 2}

#: per-wave outputs of :func:`integrate_chunk`, in the order of its ``out`` rows
RESULT_FIELDS = ("energy_peak", "t_peak", "energy_final", "dust_final", "mean_growth", "steps", "failed")

# Dormand & Prince (1980) coefficients
_C2, _C3, _C4, _C5 = 0.2, 0.3, 0.8, 8.0 / 9.0
_A21 = 0.2
_A31, _A32 = 3.0 / 40.0, 9.0 / 40.0
_A41, _A42, _A43 = 44.0 / 45.0, -56.0 / 15.0, 32.0 / 9.0
_A51, _A52, _A53, _A54 = 19372.0 / 6561.0, -25360.0 / 2187.0, 64448.0 / 6561.0, -212.0 / 729.0
_A61, _A62, _A63, _A64, _A65 = 9017.0 / 3168.0, -355.0 / 33.0, 46732.0 / 5247.0, 49.0 / 176.0, -5103.0 / 18656.0
_B1, _B3, _B4, _B5, _B6 = 35.0 / 384.0, 500.0 / 1113.0, 125.0 / 192.0, -2187.0 / 6784.0, 11.0 / 84.0
_E1, _E3, _E4, _E5, _E6, _E7 = (71.0 / 57600.0, -71.0 / 16695.0, 71.0 / 1920.0, -17253.0 / 339200.0, 22.0 / 525.0,
                                -1.0 / 40.0)
_GOLDEN = 0.3819660112501051


@numba.njit(cache=True)
def _affine_operator(keep, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, ia, ja, a, ib, jb, b):
    """L(t) = A + t B on the components ``keep`` (exact for the compressible operator, which is
    affine in k_x(t)) as two sparse lists; returns (nnz of A, nnz of B)."""
    n = _build(0.0, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G)
    A = L[:n, :n].copy()
    _build(1.0, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G)
    na = 0
    nb = 0
    for i in range(keep.shape[0]):
        for j in range(keep.shape[0]):
            aij = A[keep[i], keep[j]]
            if aij != 0.0:
                ia[na] = i
                ja[na] = j
                a[na] = aij
                na += 1
            bij = L[keep[i], keep[j]] - aij
            if bij != 0.0:
                ib[nb] = i
                jb[nb] = j
                b[nb] = bij
                nb += 1
    return na, nb


@numba.njit(cache=True, inline="always")
def _rhs_affine(t, y, n, na, ia, ja, a, nb, ib, jb, b, f):
    """f = A y + t (B y)."""
    for i in range(n):
        f[i] = 0.0
    for q in range(nb):
        f[ib[q]] += b[q] * y[jb[q]]
    for i in range(n):
        f[i] *= t
    for q in range(na):
        f[ia[q]] += a[q] * y[ja[q]]


@numba.njit(cache=True, inline="always")
def _rhs(t, y, n, op, f):
    """f = L(t) y on the kept components; ``op`` holds the affine lists or, for the incompressible
    operator, what rebuilds L."""
    affine, keep, na, ia, ja, a, nb, ib, jb, b, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G = op
    if affine:
        _rhs_affine(t, y, n, na, ia, ja, a, nb, ib, jb, b, f)
        return
    _build(t, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G)
    for i in range(n):
        acc = 0.0j
        for j in range(n):
            acc += L[keep[i], keep[j]] * y[j]
        f[i] = acc


@numba.njit(cache=True, inline="always")
def _energy(y, e, n):
    s = 0.0
    for i in range(n):
        s += e[i] * (y[i].real * y[i].real + y[i].imag * y[i].imag)
    return 0.5 * s


@numba.njit(cache=True, inline="always")
def _denergy(y, f, e, n):
    """dE/dt = Σ e_i Re(conj(y_i) f_i)."""
    s = 0.0
    for i in range(n):
        s += e[i] * (y[i].real * f[i].real + y[i].imag * f[i].imag)
    return s


@numba.njit(cache=True)
def _hermite_energy(s, h, y0, f0, y1, f1, e, n):
    """E at t0 + s h on the cubic Hermite interpolant of the step (0 <= s <= 1)."""
    h00 = (1.0 + 2.0 * s) * (1.0 - s) * (1.0 - s)
    h10 = s * (1.0 - s) * (1.0 - s)
    h01 = s * s * (3.0 - 2.0 * s)
    h11 = s * s * (s - 1.0)
    acc = 0.0
    for i in range(n):
        v = h00 * y0[i] + h10 * h * f0[i] + h01 * y1[i] + h11 * h * f1[i]
        acc += e[i] * (v.real * v.real + v.imag * v.imag)
    return 0.5 * acc


@numba.njit(cache=True)
def _step_peak(h, y0, f0, y1, f1, e, n):
    """(s, E) of the maximum of E inside a step whose ends bracket it (golden section in s)."""
    a, b = 0.0, 1.0
    x1 = a + _GOLDEN * (b - a)
    x2 = b - _GOLDEN * (b - a)
    g1 = _hermite_energy(x1, h, y0, f0, y1, f1, e, n)
    g2 = _hermite_energy(x2, h, y0, f0, y1, f1, e, n)
    for _ in range(48):  # bracket shrinks 0.618^48 ~ 1e-10
        if g1 > g2:
            b = x2
            x2, g2 = x1, g1
            x1 = a + _GOLDEN * (b - a)
            g1 = _hermite_energy(x1, h, y0, f0, y1, f1, e, n)
        else:
            a = x1
            x1, g1 = x2, g2
            x2 = b - _GOLDEN * (b - a)
            g2 = _hermite_energy(x2, h, y0, f0, y1, f1, e, n)
    return (x1, g1) if g1 > g2 else (x2, g2)


@numba.njit(cache=True)
def _initial_state(code, t0, n, keep, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, y):
    """Initial state on the components ``keep`` of the internal variables (False: none)."""
    nsp = T.shape[0]
    g0 = n - 4 * nsp
    m = keep.shape[0]
    full = np.zeros(n, dtype=np.complex128)
    if code == 0:  # fastest eigenmode of L(k(t0)) restricted to the kept components
        _build(t0, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G)
        A = np.empty((m, m), dtype=np.complex128)
        for i in range(m):
            for j in range(m):
                A[i, j] = L[keep[i], keep[j]]
                if not math.isfinite(A[i, j].real) or not math.isfinite(A[i, j].imag):
                    return False
        w, v = np.linalg.eig(A)
        best = 0
        for i in range(1, m):
            if w[i].real > w[best].real:
                best = i
        for i in range(m):
            y[i] = v[i, best]
        return True
    if code == 1:  # vortical gas wave: u along z_hat x k_hat (in plane), no density, dust at rest
        kx = kx0 + SHEAR_RATE * ky * t0
        kh = math.sqrt(kx * kx + ky * ky)
        if kh == 0.0:
            return False
        if g0 == 2:  # incompressible: a_1 along e_1 = z_hat x k / |z_hat x k|
            full[0] = 1.0
        else:
            full[1] = -ky / kh
            full[2] = kx / kh
    else:
        for j in range(nsp):  # code 2: dust density only
            full[g0 + 4 * j] = 1.0
    for i in range(m):
        y[i] = full[keep[i]]
    return True


@numba.njit(cache=True)
def _dust_density(y, M, idx):
    """Total dust-density perturbation Σ_j μ_j δρ_j / Σ_j μ_j (complex); ``idx[j]``: δρ_j in y."""
    num = 0.0j
    den = 0.0
    for j in range(idx.shape[0]):
        num += M[j] * y[idx[j]]
        den += M[j]
    return num / den if den > 0.0 else 0.0j


@numba.njit(cache=True)
def _integrate(code, t0, t1, ta, tb, tout, rtol, atol, hmax, max_steps, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy,
               Vz, gamma, beta, res, series):
    """One wave from t0 to t1; fills ``res`` in the order of :data:`RESULT_FIELDS` and
    ``series[0, i], series[1, i]`` with the dust and energy amplifications at the sorted times
    ``tout[i]`` (t0 < tout <= t1)."""
    nsp = T.shape[0]
    nmax = 4 + 4 * nsp
    L = np.zeros((nmax, nmax), dtype=np.complex128)
    G = np.zeros((3, 3 + 4 * nsp), dtype=np.complex128)
    nfull = _build(t0, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G)
    g0 = nfull - 4 * nsp
    # k_z = 0 without vertical drift: the vertical velocities decouple; integrate the planar
    # system (thesis eq. 4.35) without u_z (a_2 = u_z in the incompressible limit) and w_z
    planar = kz == 0.0
    for j in range(nsp):
        planar = planar and Vz[j] == 0.0
    keep = np.empty(nfull, dtype=np.int64)
    n = 0
    for i in range(nfull):
        vertical = i == g0 - 1 or (i >= g0 and (i - g0) % 4 == 3)
        if not (planar and vertical):
            keep[n] = i
            n += 1
    keep = keep[:n].copy()
    e = np.zeros(n)
    dens = np.empty(nsp, dtype=np.int64)
    for q in range(n):
        i = keep[q]
        if i < g0:
            e[q] = 1.0
        elif (i - g0) % 4 == 0:
            dens[(i - g0) // 4] = q
        else:
            e[q] = M[(i - g0) // 4]
    for i in range(len(res)):
        res[i] = math.nan
    res[6] = 1.0
    for i in range(series.shape[1]):
        series[0, i] = math.nan
        series[1, i] = math.nan
    y = np.empty(n, dtype=np.complex128)
    if not _initial_state(code, t0, nfull, keep, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, y):
        return
    E0 = _energy(y, e, n)
    if not E0 > 0.0:
        return
    rho0 = abs(_dust_density(y, M, dens))
    k1 = np.empty(n, dtype=np.complex128)
    k2 = np.empty_like(k1)
    k3 = np.empty_like(k1)
    k4 = np.empty_like(k1)
    k5 = np.empty_like(k1)
    k6 = np.empty_like(k1)
    k7 = np.empty_like(k1)
    ys = np.empty_like(k1)
    yn = np.empty_like(k1)
    affine = math.isfinite(cs)  # the incompressible operator is not affine in t (rotating basis)
    ia = np.zeros(n * n, dtype=np.int64)
    ja = np.zeros(n * n, dtype=np.int64)
    a = np.zeros(n * n, dtype=np.complex128)
    ib = np.zeros(n * n, dtype=np.int64)
    jb = np.zeros(n * n, dtype=np.int64)
    b = np.zeros(n * n, dtype=np.complex128)
    na = nb = 0
    if affine:
        na, nb = _affine_operator(keep, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G, ia, ja, a, ib, jb,
                                  b)
    op = (affine, keep, na, ia, ja, a, nb, ib, jb, b, kx0, ky, kz, cs, Ux, Uy, T, M, Vx, Vy, Vz, gamma, beta, L, G)
    _rhs(t0, y, n, op, k1)
    # initial step (Hairer, Norsett & Wanner 1993, II.4, simplified): 1 % of |y|/|f|
    ynorm = 0.0
    fnorm = 0.0
    for i in range(n):
        ynorm = max(ynorm, abs(y[i]))
        fnorm = max(fnorm, abs(k1[i]))
    h = 0.01 * ynorm / fnorm if fnorm > 0.0 else hmax
    h = min(h, hmax, t1 - t0)
    t = t0
    Epeak = E0
    tpeak = t0
    Ea = E0 if ta <= t0 else math.nan
    Eb = math.nan
    facold = 1e-4
    expo1 = 0.2 - 0.75 * 0.04
    steps = 0
    total = 0
    nout = tout.shape[0]
    iout = 0
    while t < t1:
        total += 1
        if total > max_steps:
            return
        # land exactly on the window edges and the end
        stop = t1
        if ta > t and ta < stop:
            stop = ta
        if tb > t and tb < stop:
            stop = tb
        if iout < nout and tout[iout] < stop:
            stop = tout[iout]
        landing = False
        if t + h >= stop - 1e-14 * max(1.0, abs(stop)):
            h = stop - t
            landing = True
        for i in range(n):
            ys[i] = y[i] + h * _A21 * k1[i]
        _rhs(t + _C2 * h, ys, n, op, k2)
        for i in range(n):
            ys[i] = y[i] + h * (_A31 * k1[i] + _A32 * k2[i])
        _rhs(t + _C3 * h, ys, n, op, k3)
        for i in range(n):
            ys[i] = y[i] + h * (_A41 * k1[i] + _A42 * k2[i] + _A43 * k3[i])
        _rhs(t + _C4 * h, ys, n, op, k4)
        for i in range(n):
            ys[i] = y[i] + h * (_A51 * k1[i] + _A52 * k2[i] + _A53 * k3[i] + _A54 * k4[i])
        _rhs(t + _C5 * h, ys, n, op, k5)
        for i in range(n):
            ys[i] = y[i] + h * (_A61 * k1[i] + _A62 * k2[i] + _A63 * k3[i] + _A64 * k4[i] + _A65 * k5[i])
        _rhs(t + h, ys, n, op, k6)
        for i in range(n):
            yn[i] = y[i] + h * (_B1 * k1[i] + _B3 * k3[i] + _B4 * k4[i] + _B5 * k5[i] + _B6 * k6[i])
        _rhs(t + h, yn, n, op, k7)
        err2 = 0.0
        for i in range(n):
            d = h * (_E1 * k1[i] + _E3 * k3[i] + _E4 * k4[i] + _E5 * k5[i] + _E6 * k6[i] + _E7 * k7[i])
            m2 = max(y[i].real * y[i].real + y[i].imag * y[i].imag, yn[i].real * yn[i].real + yn[i].imag * yn[i].imag)
            sc = atol + rtol * math.sqrt(m2)
            r2 = (d.real * d.real + d.imag * d.imag) / (sc * sc)
            if r2 > err2:
                err2 = r2
        err = math.sqrt(err2)
        if not math.isfinite(err):
            return
        fac11 = err ** expo1 if err > 0.0 else 0.0
        if err <= 1.0:
            # accepted: peak inside the step?
            E1 = _energy(yn, e, n)
            d0 = _denergy(y, k1, e, n)
            d1 = _denergy(yn, k7, e, n)
            if d0 > 0.0 and d1 < 0.0:
                s, Em = _step_peak(h, y, k1, yn, k7, e, n)
                if Em > Epeak:
                    Epeak = Em
                    tpeak = t + s * h
            if E1 > Epeak:
                Epeak = E1
                tpeak = t + h
            t = stop if landing else t + h
            for i in range(n):
                y[i] = yn[i]
                k1[i] = k7[i]
            steps += 1
            if t == ta:
                Ea = E1
            if t == tb:
                Eb = E1
            while iout < nout and t == tout[iout]:
                series[0, iout] = abs(_dust_density(y, M, dens)) / rho0 if rho0 > 0.0 else math.nan
                series[1, iout] = math.sqrt(E1 / E0)
                iout += 1
            facold = max(err, 1e-4)
            fac = fac11 / facold ** 0.04
            fac = max(0.1, min(5.0, fac / 0.9))
            h = min(h / fac, hmax)
        else:
            h = h / min(5.0, fac11 / 0.9)
    E1 = _energy(y, e, n)
    res[0] = math.sqrt(Epeak / E0)
    res[1] = tpeak
    res[2] = math.sqrt(E1 / E0)
    res[3] = abs(_dust_density(y, M, dens)) / rho0 if rho0 > 0.0 else math.nan
    if tb > ta and Ea > 0.0 and Eb > 0.0:
        res[4] = 0.5 * math.log(Eb / Ea) / (tb - ta)
    res[5] = steps
    res[6] = 0.0


@numba.njit(cache=True)
def integrate_chunk(code, T, M, Ux, Uy, Vx, Vy, Vz, kx0, ky, kz, cs, gamma, beta, t1, ta, tb, tfrac, rtol, atol,
                    hfrac, max_steps, out, series):
    """Integrate waves ``p`` of a chunk (arrays over points; species along the last axis).

    ``t1[p]`` is each wave's end time (NaN: skip the point), ``ta[p], tb[p]`` its averaging
    window, ``tfrac`` the sorted sample times as fractions of t1 (0 < tfrac <= 1), ``hfrac`` the
    largest step as a fraction of t1. ``out`` has shape (len(RESULT_FIELDS), npts), ``series``
    (2, npts, len(tfrac)): dust and energy amplification at the sample times.
    """
    npts = T.shape[0]
    res = np.empty(out.shape[0])
    ser = np.empty((2, tfrac.shape[0]))
    tout = np.empty(tfrac.shape[0])
    for p in range(npts):
        if not math.isfinite(t1[p]):
            for i in range(out.shape[0]):
                out[i, p] = math.nan
            out[6, p] = 0.0
            series[:, p, :] = math.nan
            continue
        for i in range(tfrac.shape[0]):
            tout[i] = t1[p] if tfrac[i] == 1.0 else tfrac[i] * t1[p]
        _integrate(code, 0.0, t1[p], ta[p], tb[p], tout, rtol, atol, hfrac * t1[p], max_steps, kx0[p], ky[p], kz, cs,
                   Ux[p], Uy[p], T[p], M[p], Vx[p], Vy[p], Vz[p], gamma, beta, res, ser)
        for i in range(out.shape[0]):
            out[i, p] = res[i]
        series[:, p, :] = ser
