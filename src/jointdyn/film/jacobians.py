"""Exact Jacobians of the film kernels (compiled), hand-derived [T90–T95].

Every function here has the film-kernel arguments ``(xi, xi_dot, xi_Omega, mu, R, L, c, p, table)``
(see :mod:`jointdyn.film.models`: ξ [-], ξ̇ [1/s], X = ξΩ [rad/s], μ [Pa·s], R, L, c [m])
and returns the 8-tuple

    (F_r, F_t, ∂F_r/∂ξ, ∂F_r/∂ξ̇, ∂F_r/∂X, ∂F_t/∂ξ, ∂F_t/∂ξ̇, ∂F_t/∂X)   [N, N, N, N·s, N·s/rad, …]

with the partial derivatives taken at fixed values of the other two of (ξ, ξ̇, X). The forces are
the same numbers as the kernel's (same branches, same guards). At A = B = 0 (no squeeze, no
wedge) the forces are positively homogeneous of degree 1 and not differentiable; the Jacobian
returned there is zero [T90].
"""

from __future__ import annotations

import math

from numba import njit

from jointdyn.film.finite import _catmull_rom
from jointdyn.film.kernels import _atan_y_over_y_minus_1


@njit(cache=True)
def _datan_y_over_y(y):
    """d/dy [atan(y)/y] for y ≥ 0, series below y = 0.1 (no cancellation) [T91]."""
    if y < 0.1:
        # y·Σ_{n=1..9} (−1)^n 2n/(2n+1) y^{2n−2}; first omitted term (n = 10) < 1e-18 of the sum
        z = y * y
        s = -18.0 / 19.0
        for n in range(8, 0, -1):
            s = (-1.0) ** n * 2.0 * n / (2.0 * n + 1.0) + z * s
        return y * s
    return (1.0 / (1.0 + y * y) - math.atan(y) / y) / y


@njit(cache=True)
def pi_film_jac(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """π-film [T21–T23] and its exact Jacobian [T91]."""
    A = xi_dot
    s = 2.0 + xi * xi
    B = xi_Omega / s
    rho = math.hypot(A, B)
    if rho == 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    k = mu * L * R * R * R / (c * c)
    # derivatives of the intermediates w.r.t. (ξ, ξ̇, X): suffixes _x, _a, _o
    B_x = -2.0 * xi * B / s
    B_o = 1.0 / s
    rho_a = A / rho
    rho_x = B * B_x / rho
    rho_o = B * B_o / rho
    w = (1.0 - xi) * (1.0 + xi)
    sw = math.sqrt(w)
    sw_x = -xi / sw
    Pp = rho * sw
    Qv = -xi * A
    dd = 2.0 * math.atan2(Pp, Qv)
    n2 = A * A + B * B * w  # = Pp² + Qv²
    Pp_x = rho_x * sw + rho * sw_x
    Pp_a = rho_a * sw
    Pp_o = rho_o * sw
    dd_x = 2.0 * (Qv * Pp_x + Pp * A) / n2
    dd_a = 2.0 * (Qv * Pp_a + Pp * xi) / n2
    dd_o = 2.0 * (Qv * Pp_o) / n2
    # F_t = 6k·B·Δδ/√w
    ft = 6.0 * k * B * dd / sw
    ft_x = 6.0 * k * (B_x * dd / sw + B * dd_x / sw - B * dd * sw_x / w)
    ft_a = 6.0 * k * B * dd_a / sw
    ft_o = 6.0 * k * (B_o * dd + B * dd_o) / sw
    if A < 0.0 and Pp < Qv:
        # near-wall form F_r = 12k(ρ/ξ)[1 + g(y)/w], y = Pp/Qv [T23]
        y = Pp / Qv
        g = _atan_y_over_y_minus_1(y)
        gp = _datan_y_over_y(y)
        y_x = (Pp_x * Qv + Pp * A) / (Qv * Qv)
        y_a = (Pp_a * Qv + Pp * xi) / (Qv * Qv)
        y_o = Pp_o / Qv
        bracket = 1.0 + g / w
        fr = 12.0 * k * (rho / xi) * bracket
        fr_x = (
            12.0
            * k
            * (
                (rho_x / xi - rho / (xi * xi)) * bracket
                + (rho / xi) * (gp * y_x / w + g * 2.0 * xi / (w * w))
            )
        )
        fr_a = 12.0 * k * (rho_a / xi * bracket + (rho / xi) * gp * y_a / w)
        fr_o = 12.0 * k * (rho_o / xi * bracket + (rho / xi) * gp * y_o / w)
    else:
        w32 = w * sw
        fr = -6.0 * k * (A * dd / w32 + 2.0 * xi * rho / w)
        fr_x = (
            -6.0
            * k
            * (
                A * dd_x / w32
                + 3.0 * xi * A * dd / (w32 * w)
                + 2.0 * rho / w
                + 2.0 * xi * rho_x / w
                + 4.0 * xi * xi * rho / (w * w)
            )
        )
        fr_a = -6.0 * k * (dd / w32 + A * dd_a / w32 + 2.0 * xi * rho_a / w)
        fr_o = -6.0 * k * (A * dd_o / w32 + 2.0 * xi * rho_o / w)
    return fr, ft, fr_x, fr_a, fr_o, ft_x, ft_a, ft_o


@njit(cache=True)
def ott_jac(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Ott's model [T25, T26] and its exact Jacobian [T92] (|ξ̇| enters only multiplied by
    ξξ̇, so the first derivatives are continuous at ξ̇ = 0)."""
    A = xi_dot
    X = xi_Omega
    h = math.hypot(X, 2.0 * A)
    if h == 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    h_a = 4.0 * A / h
    h_o = X / h
    k = mu * L * R * R * R / (c * c)
    w = (1.0 - xi) * (1.0 + xi)
    sw = math.sqrt(w)
    sw_x = -xi / sw
    s = 2.0 + xi * xi
    sa = 1.0 if A > 0.0 else (-1.0 if A < 0.0 else 0.0)
    D = sw * h + 3.0 * xi * abs(A)
    D_x = sw_x * h + 3.0 * abs(A)
    D_a = sw * h_a + 3.0 * xi * sa
    D_o = sw * h_o
    num = 3.0 * xi * A
    phi = 1.0 + num / D
    phi_x = 3.0 * A / D - num * D_x / (D * D)
    phi_a = 3.0 * xi / D - num * D_a / (D * D)
    phi_o = -num * D_o / (D * D)
    # F_t = 6πk·X·Φ/(s√w)
    ct = 6.0 * math.pi * k / (s * sw)
    ft = 6.0 * math.pi * k * X * phi / (s * sw)  # the kernel's expression, bit for bit
    ft_x = ct * X * (phi_x - phi * (2.0 * xi / s + sw_x / sw))
    ft_a = ct * X * phi_a
    ft_o = ct * (phi + X * phi_o)
    # F_r = −3k·N/(s w^{3/2}), N = 4ξ√w·h + 2π s ξ̇ Φ
    N = 4.0 * xi * sw * h + 2.0 * math.pi * s * A * phi
    N_x = 4.0 * (sw + xi * sw_x) * h + 2.0 * math.pi * (2.0 * xi * A * phi + s * A * phi_x)
    N_a = 4.0 * xi * sw * h_a + 2.0 * math.pi * s * (phi + A * phi_a)
    N_o = 4.0 * xi * sw * h_o + 2.0 * math.pi * s * A * phi_o
    cr = -3.0 * k / (s * w * sw)
    fr = -3.0 * k * (4.0 * (xi * sw * h) + 2.0 * math.pi * s * A * phi) / (s * w * sw)
    fr_x = cr * (N_x - N * (2.0 * xi / s - 3.0 * xi / w))
    fr_a = cr * N_a
    fr_o = cr * N_o
    return fr, ft, fr_x, fr_a, fr_o, ft_x, ft_a, ft_o


@njit(cache=True)
def short_jac(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Short-bearing π-film [T35] and its exact Jacobian [T93]: the pressure vanishes at both
    ends of the film arc, so ∂/∂(ξ̇, X) act on the integrands only; ∂/∂ξ differentiates the
    closed forms at fixed arc ends with ∂δ/∂ξ|_θ = −sin θ/(√(1−ξ²)(1 + ξ cos θ))."""
    a = 2.0 * xi_dot
    b = xi_Omega
    if a == 0.0 and b == 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    ks = mu * R * L * L * L / (2.0 * c * c)
    beta = math.atan2(b, a)
    t0 = 0.5 * math.pi - beta
    t1 = t0 + math.pi
    w1 = (1.0 - xi) * (1.0 + xi)
    sw = math.sqrt(w1)
    d0 = math.atan2(sw * math.sin(t0), math.cos(t0) + xi)
    dd = (math.atan2(sw * math.sin(t1), math.cos(t1) + xi) - d0) % (2.0 * math.pi)
    d1 = d0 + dd
    c0 = math.cos(t0)
    c1 = math.cos(t1)
    h0 = 1.0 + xi * c0
    h1 = 1.0 + xi * c1
    isc = -c1 * c1 / (2.0 * h1 * h1) + c0 * c0 / (2.0 * h0 * h0)
    jss = (d1 - d0) / 2.0 - (math.sin(2.0 * d1) - math.sin(2.0 * d0)) / 4.0
    iss = jss / (w1 * sw)
    j3n = (
        (d1 - d0) * (1.0 + 0.5 * xi * xi)
        - 2.0 * xi * (math.sin(d1) - math.sin(d0))
        + 0.25 * xi * xi * (math.sin(2.0 * d1) - math.sin(2.0 * d0))
    )
    j3 = j3n / (w1 * w1 * sw)
    icc = j3 - iss
    fr = -ks * (a * icc - b * isc)
    ft = -ks * (a * isc - b * iss)
    # ∂/∂ξ at fixed arc ends θ₀, θ₁
    e0 = -math.sin(t0) / (sw * h0)  # ∂δ₀/∂ξ
    e1 = -math.sin(t1) / (sw * h1)
    isc_x = c1**3 / h1**3 - c0**3 / h0**3
    jss_x = math.sin(d1) ** 2 * e1 - math.sin(d0) ** 2 * e0
    iss_x = jss_x / (w1 * sw) + 3.0 * xi * jss / (w1 * w1 * sw)
    j3n_x = (
        xi * (d1 - d0)
        - 2.0 * (math.sin(d1) - math.sin(d0))
        + 0.5 * xi * (math.sin(2.0 * d1) - math.sin(2.0 * d0))
        + (1.0 - xi * math.cos(d1)) ** 2 * e1
        - (1.0 - xi * math.cos(d0)) ** 2 * e0
    )
    j3_x = j3n_x / (w1 * w1 * sw) + 5.0 * xi * j3n / (w1 * w1 * w1 * sw)
    icc_x = j3_x - iss_x
    fr_x = -ks * (a * icc_x - b * isc_x)
    ft_x = -ks * (a * isc_x - b * iss_x)
    # a = 2ξ̇, b = X
    return fr, ft, fr_x, -2.0 * ks * icc, ks * isc, ft_x, -2.0 * ks * isc, ks * iss


@njit(cache=True)
def _catmull_rom_d(p0, p1, p2, p3, w):
    """d/dw of :func:`jointdyn.film.finite._catmull_rom` [T94]."""
    return (
        0.5 * (p2 - p0)
        + w * (2.0 * p0 - 5.0 * p1 + 4.0 * p2 - p3)
        + 1.5 * w * w * (3.0 * (p1 - p2) + p3 - p0)
    )


@njit(cache=True)
def finite_jac(xi, xi_dot, xi_Omega, mu, R, L, c, p, table):
    """Tabulated finite-length film [T37] and the exact Jacobian of its interpolant [T94]."""
    A = xi_dot
    s2 = 2.0 + xi * xi
    B = xi_Omega / s2
    rho = math.sqrt(A * A + B * B)
    if rho == 0.0:
        return 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0
    B_x = -2.0 * xi * B / s2
    B_o = 1.0 / s2
    n_xi = int(table[0, 0])
    n_psi = int(table[0, 1])
    xmax = table[1, 0]
    umax = -math.log(1.0 - xmax)
    u = -math.log(1.0 - min(xi, xmax))
    su = u / umax * (n_xi - 1)
    su_x = (n_xi - 1) / (umax * (1.0 - xi)) if xi < xmax else 0.0
    a = min(int(su), n_xi - 2)
    wa = su - a
    psi = math.atan2(A, B)
    sp = (psi + math.pi) / (2.0 * math.pi) * (n_psi - 1)
    sp_psi = (n_psi - 1) / (2.0 * math.pi)
    b = min(int(sp), n_psi - 2)
    wb = sp - b
    fv = [0.0, 0.0]
    fu = [0.0, 0.0]  # ∂/∂su
    fp = [0.0, 0.0]  # ∂/∂sp
    for comp in range(2):
        col0 = 0.0
        col1 = 0.0
        col2 = 0.0
        col3 = 0.0
        dc0 = 0.0
        dc1 = 0.0
        dc2 = 0.0
        dc3 = 0.0
        for i in range(4):
            ai = min(max(a - 1 + i, 0), n_xi - 1)
            v0 = table[2 + ai * n_psi + (b - 1) % (n_psi - 1), comp]
            v1 = table[2 + ai * n_psi + b % (n_psi - 1), comp]
            v2 = table[2 + ai * n_psi + (b + 1) % (n_psi - 1), comp]
            v3 = table[2 + ai * n_psi + (b + 2) % (n_psi - 1), comp]
            cv = _catmull_rom(v0, v1, v2, v3, wb)
            dv = _catmull_rom_d(v0, v1, v2, v3, wb)
            if i == 0:
                col0, dc0 = cv, dv
            elif i == 1:
                col1, dc1 = cv, dv
            elif i == 2:
                col2, dc2 = cv, dv
            else:
                col3, dc3 = cv, dv
        if a == 0:
            col0 = 2.0 * col1 - col2
            dc0 = 2.0 * dc1 - dc2
        if a + 2 >= n_xi - 1:
            col3 = 2.0 * col2 - col1
            dc3 = 2.0 * dc2 - dc1
        fv[comp] = _catmull_rom(col0, col1, col2, col3, wa)
        fu[comp] = _catmull_rom_d(col0, col1, col2, col3, wa)
        fp[comp] = _catmull_rom(dc0, dc1, dc2, dc3, wa)
    rho_x = B * B_x / rho
    rho_a = A / rho
    rho_o = B * B_o / rho
    r2 = rho * rho
    psi_x = -A * B_x / r2
    psi_a = B / r2
    psi_o = -A * B_o / r2
    w = (1.0 - xi) * (1.0 + xi)
    C = 6.0 * mu * R * R * R * R / (c * c) / (w * math.sqrt(w))
    res = [0.0] * 8
    for comp in range(2):
        f = fv[comp]
        f_x = fu[comp] * su_x + fp[comp] * sp_psi * psi_x
        f_a = fp[comp] * sp_psi * psi_a
        f_o = fp[comp] * sp_psi * psi_o
        res[comp] = f * (6.0 * mu * R * R * R * R / (c * c) * rho / ((1.0 - xi) * (1.0 + xi)) ** 1.5)
        res[2 + 3 * comp] = C * (rho_x * f + rho * f_x + rho * f * 3.0 * xi / w)
        res[3 + 3 * comp] = C * (rho_a * f + rho * f_a)
        res[4 + 3 * comp] = C * (rho_o * f + rho * f_o)
    return res[0], res[1], res[2], res[3], res[4], res[5], res[6], res[7]


FD_JAC = """
fr, ft = KERNEL(xi, xi_dot, xi_Omega, mu, R, L, c, p, table)
h_ = 6.055454452393343e-06 * (1.0 - xi)
lo_ = max(xi - h_, 0.0)
hi_ = xi + h_
frp_, ftp_ = KERNEL(hi_, xi_dot, xi_Omega, mu, R, L, c, p, table)
frm_, ftm_ = KERNEL(lo_, xi_dot, xi_Omega, mu, R, L, c, p, table)
frx_ = (frp_ - frm_) / (hi_ - lo_)
ftx_ = (ftp_ - ftm_) / (hi_ - lo_)
s_ = 6.055454452393343e-06 * max(math.hypot(xi_dot, xi_Omega), 1e-300)
frp_, ftp_ = KERNEL(xi, xi_dot + s_, xi_Omega, mu, R, L, c, p, table)
frm_, ftm_ = KERNEL(xi, xi_dot - s_, xi_Omega, mu, R, L, c, p, table)
fra_ = (frp_ - frm_) / (2.0 * s_)
fta_ = (ftp_ - ftm_) / (2.0 * s_)
frp_, ftp_ = KERNEL(xi, xi_dot, xi_Omega + s_, mu, R, L, c, p, table)
frm_, ftm_ = KERNEL(xi, xi_dot, xi_Omega - s_, mu, R, L, c, p, table)
return fr, ft, frx_, fra_, (frp_ - frm_) / (2.0 * s_), ftx_, fta_, (ftp_ - ftm_) / (2.0 * s_)
"""
"""The 8-tuple of :func:`pi_film_jac` for a film ``KERNEL`` without an exact Jacobian, by central
differences [T229] (steps ε^{1/3}·(1 − ξ) for ξ, the distance to the wall setting the scale,
cut at ξ = 0, and ε^{1/3}·|(ξ̇, ξΩ)| for the rates): source lines for the generated dispatch."""
