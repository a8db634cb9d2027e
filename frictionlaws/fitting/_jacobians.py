"""Analytic Jacobians of the built-in laws: GENERATED, do not edit.

Written by ``python -m frictionlaws.caches`` from each law's symbolic form
(sympy, common subexpressions shared); see :mod:`frictionlaws.fitting.derivatives`.
"""

# ruff: noqa
# mypy: ignore-errors

import numpy

__all__ = ["JACOBIANS"]

def _d_coulomb(m, names, mu0):
    _cols = {
        'mu0': lambda: 1,
    }
    return [_cols[k]() for k in names]


def _d_thirion(m, names, p, a, b):
    x0 = 1.0/(a + b*p)**2
    _cols = {
        'a': lambda: -x0,
        'b': lambda: -p*x0,
    }
    return [_cols[k]() for k in names]


def _d_schallamach(m, names, F_N, mu_ref, n, F_ref):
    x0 = F_ref**(-1.0)
    x1 = F_N*x0
    x2 = x1**(-n)
    x3 = mu_ref*x2
    _cols = {
        'mu_ref': lambda: x2,
        'n': lambda: -x3*numpy.log(x1),
        'F_ref': lambda: n*x0*x3,
    }
    return [_cols[k]() for k in names]


def _d_denny(m, names, p, a, b, E_v):
    x0 = p/E_v
    x1 = b*x0 + 1.0
    x2 = 1.0/(a*x1**2)
    _cols = {
        'a': lambda: -1.0/(a**2*x1),
        'b': lambda: -x0*x2,
        'E_v': lambda: b*p*x2/E_v**2,
    }
    return [_cols[k]() for k in names]


def _d_exponential_decay(m, names, v, mu_s, mu_d, v_c, delta):
    x0 = v_c**(-1.0)
    x1 = v*x0
    x2 = x1**delta
    x3 = numpy.exp(-x2)
    x4 = x2*x3*(mu_d - mu_s)
    _cols = {
        'mu_s': lambda: x3,
        'mu_d': lambda: 1 - x3,
        'v_c': lambda: -delta*x0*x4,
        'delta': lambda: x4*numpy.log(x1),
    }
    return [_cols[k]() for k in names]


def _d_quadratic_pv(m, names, p, v, c0, c1, c2, c3, c4, c5):
    _cols = {
        'c0': lambda: 1,
        'c1': lambda: p,
        'c2': lambda: v,
        'c3': lambda: p*v,
        'c4': lambda: p**2,
        'c5': lambda: v**2,
    }
    return [_cols[k]() for k in names]


def _d_thesis_poly2(m, names, p, v, a0, a1, a2, a3, a4):
    _cols = {
        'a0': lambda: 1,
        'a1': lambda: 1.0e-6*p,
        'a2': lambda: 1.0e-12*p**2,
        'a3': lambda: v,
        'a4': lambda: v**2,
    }
    return [_cols[k]() for k in names]


def _d_thesis_poly3(m, names, p, v, a0, a1, a2, a3, a4, a5, a6):
    _cols = {
        'a0': lambda: 1,
        'a1': lambda: 1.0e-6*p,
        'a2': lambda: 1.0e-12*p**2,
        'a3': lambda: 1.0e-18*p**3,
        'a4': lambda: v,
        'a5': lambda: v**2,
        'a6': lambda: v**3,
    }
    return [_cols[k]() for k in names]


def _d_savkoor(m, names, p, v, mu_s, mu_m, h10, v_m, n, p_ref):
    x0 = p_ref**(-1.0)
    x1 = p*x0
    x2 = x1**n
    x3 = h10**2
    x4 = numpy.log(10)**(-2.0)
    x5 = v_m**(-1.0)
    x6 = numpy.log(v*x5)
    x7 = x4*x6**2
    x8 = numpy.exp(-x3*x7)
    x9 = x2*x8
    x10 = mu_m - mu_s
    x11 = 2*x10*x9
    x12 = x2*(mu_s + x10*x8)
    _cols = {
        'mu_s': lambda: x2*(1 - x8),
        'mu_m': lambda: x9,
        'h10': lambda: -h10*x11*x7,
        'v_m': lambda: x11*x3*x4*x5*x6,
        'n': lambda: x12*numpy.log(x1),
        'p_ref': lambda: -n*x0*x12,
    }
    return [_cols[k]() for k in names]


def _d_nackenhorst(m, names, p, v, A, n, b0, b1, b2, p_ref, v_ref):
    x0 = p_ref**(-1.0)
    x1 = p*x0
    x2 = x1**n
    x3 = A*x2
    x4 = v_ref**(-1.0)
    x5 = numpy.log(v*x4)
    _cols = {
        'A': lambda: x2,
        'n': lambda: x3*numpy.log(x1),
        'b0': lambda: 1,
        'b1': lambda: x5,
        'b2': lambda: x5**2,
        'p_ref': lambda: -n*x0*x3,
        'v_ref': lambda: -x4*(b1 + 2*b2*x5),
    }
    return [_cols[k]() for k in names]


def _d_nackenhorst_thesis(m, names, p, v, c1, c2, c3, c4, c5, c6, c7):
    x0 = c2**(-1.0)
    x1 = p*x0
    x2 = x1**c3
    x3 = c1*x2
    x4 = c5**(-1.0)
    x5 = c7**(-1.0)
    _cols = {
        'c1': lambda: x2,
        'c2': lambda: -c3*x0*x3,
        'c3': lambda: x3*numpy.log(x1),
        'c4': lambda: numpy.log(v*x4),
        'c5': lambda: -c4*x4,
        'c6': lambda: -numpy.log(v*x5),
        'c7': lambda: c6*x5,
    }
    return [_cols[k]() for k in names]


def _d_huemer(m, names, p, v, alpha, beta, n, m_v, b, c, p_ref, v_ref):
    x0 = p_ref**(-1.0)
    x1 = p*x0
    x2 = n - 1.0
    x3 = x1**x2
    x4 = v_ref**(-1.0)
    x5 = v*x4
    x6 = m_v**(-1.0)
    x7 = x5**(-1.0*x6)
    x8 = b*x7
    x9 = x5**(-2.0*x6)
    x10 = c*x9
    x11 = x10 + x8 + 1.0
    x12 = x11**(-1.0)
    x13 = x12*x3
    x14 = alpha*x13
    x15 = (alpha*x3 + beta)/x11**2
    x16 = x15*(2.0*x10 + 1.0*x8)
    _cols = {
        'alpha': lambda: x13,
        'beta': lambda: x12,
        'n': lambda: x14*numpy.log(x1),
        'm_v': lambda: -x16*numpy.log(x5)/m_v**2,
        'b': lambda: -x15*x7,
        'c': lambda: -x15*x9,
        'p_ref': lambda: -x0*x14*x2,
        'v_ref': lambda: -x16*x4*x6,
    }
    return [_cols[k]() for k in names]


def _d_wriggers(m, names, p, v, a, b, c, d):
    x0 = p**2
    x1 = a**2*x0
    x2 = (v**2 + x1)**(-1.0)
    x3 = 2.0*a*p*v*x2
    x4 = x3**c
    x5 = x4*numpy.arctan(d*p)/p
    x6 = b*x5
    _cols = {
        'a': lambda: -0.5*c*x6*(4.0*x1*x2 - 2.0)/a,
        'b': lambda: x5,
        'c': lambda: x6*numpy.log(x3),
        'd': lambda: b*x4/(d**2*x0 + 1),
    }
    return [_cols[k]() for k in names]


def _d_park(m, names, p, v, T, n, mu_s, mu_m, h10, v_m, p0, C1, C2, T_ref):
    x0 = p0**(-1.0)
    x1 = p*x0
    x2 = x1**(-n)
    x3 = h10**2
    x4 = numpy.log(10)**(-1.0)
    x5 = v_m**(-1.0)
    x6 = T - T_ref
    x7 = C2 + x6
    x8 = x7**(-1.0)
    x9 = x6*x8
    x10 = C1*x9 - x4*numpy.log(v*x5)
    x11 = x10**2
    x12 = numpy.exp(-x11*x3)
    x13 = x12*(mu_m - mu_s)
    x14 = x2*(mu_s + x13)
    x15 = 2*x13*x2
    x16 = x10*x15*x3
    x17 = C1*x16
    _cols = {
        'n': lambda: -x14*numpy.log(x1),
        'mu_s': lambda: x2*(1 - x12),
        'mu_m': lambda: x12*x2,
        'h10': lambda: -h10*x11*x15,
        'v_m': lambda: -x16*x4*x5,
        'p0': lambda: n*x0*x14,
        'C1': lambda: -x16*x9,
        'C2': lambda: x17*x6/x7**2,
        'T_ref': lambda: -x17*x8*(x9 - 1),
    }
    return [_cols[k]() for k in names]


def _d_pacejka(m, names, s, B, C, D, E, S_h, S_v):
    x0 = S_h + s
    x1 = (B**2*x0**2 + 1)**(-1.0)
    x2 = B*x0
    x3 = x2 - numpy.arctan(x2)
    x4 = -E*x3 + x2
    x5 = numpy.arctan(x4)
    x6 = C*x5
    x7 = D*numpy.cos(x6)
    x8 = C*x7/(x4**2 + 1)
    _cols = {
        'B': lambda: x8*(-E*(-x0*x1 + x0) + x0),
        'C': lambda: x5*x7,
        'D': lambda: numpy.sin(x6),
        'E': lambda: -x3*x8,
        'S_h': lambda: B*x8*(-E*(1 - x1) + 1),
        'S_v': lambda: 1,
    }
    return [_cols[k]() for k in names]


def _d_burckhardt(m, names, s, v, c1, c2, c3, c4):
    x0 = numpy.exp(-c4*v)
    x1 = numpy.exp(-c2*s)
    x2 = 1.0 - x1
    x3 = s*x0
    _cols = {
        'c1': lambda: x0*x2,
        'c2': lambda: c1*x1*x3,
        'c3': lambda: -x3,
        'c4': lambda: -v*x0*(c1*x2 - c3*s),
    }
    return [_cols[k]() for k in names]


def _d_burckhardt_sqrt(m, names, s, c1, c2):
    _cols = {
        'c1': lambda: numpy.sqrt(s),
        'c2': lambda: -s,
    }
    return [_cols[k]() for k in names]


def _d_kiencke_daiss(m, names, s, k_s, c1, c2):
    x0 = s**2
    x1 = c1*x0 + c2*s + 1.0
    x2 = k_s/x1**2
    _cols = {
        'k_s': lambda: s/x1,
        'c1': lambda: -s**3*x2,
        'c2': lambda: -x0*x2,
    }
    return [_cols[k]() for k in names]


def _d_germann(m, names, s, a0, a1, a2):
    _cols = {
        'a0': lambda: 1,
        'a1': lambda: s,
        'a2': lambda: s**2,
    }
    return [_cols[k]() for k in names]


JACOBIANS = {
    'coulomb': ({'symbols': '|mu0||', 'mu': [1.137, 1.428]}, _d_coulomb),
    'thirion': ({'symbols': 'p|a,b||', 'mu': [0.3474264558992491, 0.2502843229909177]}, _d_thirion),
    'schallamach': ({'symbols': 'F_N|mu_ref,n|F_ref|F_N', 'mu': [1.969056743885253, 2.407049580504971]}, _d_schallamach),
    'denny': ({'symbols': 'p|a,b|E_v|', 'mu': [0.38545441279738046, 0.2752294138186394]}, _d_denny),
    'exponential-decay': ({'symbols': 'v|mu_s,mu_d,v_c,delta||', 'mu': [1.3354023245627877, 1.6273102278590814]}, _d_exponential_decay),
    'quadratic-pv': ({'symbols': 'p,v|c0,c1,c2,c3,c4,c5||', 'mu': [13.891504003000001, 22.577170734999996]}, _d_quadratic_pv),
    'thesis-poly2': ({'symbols': 'p,v|a0,a1,a2,a3,a4||', 'mu': [6.911835644078178, 10.519603876096028]}, _d_thesis_poly2),
    'thesis-poly3': ({'symbols': 'p,v|a0,a1,a2,a3,a4,a5,a6||', 'mu': [11.92612983007018, 20.74413840459603]}, _d_thesis_poly3),
    'savkoor': ({'symbols': 'p,v|mu_s,mu_m,h10,v_m,n|p_ref|p,v', 'mu': [0.4643509583982316, 0.5760622193617592]}, _d_savkoor),
    'nackenhorst': ({'symbols': 'p,v|A,n,b0,b1,b2|p_ref,v_ref|p,v', 'mu': [1.8268982664120121, 2.1417323078275334]}, _d_nackenhorst),
    'nackenhorst-thesis': ({'symbols': 'p,v|c1,c2,c3,c4,c5,c6,c7||p,v', 'mu': [1.2312035483866766, 1.4062730915649189]}, _d_nackenhorst_thesis),
    'huemer': ({'symbols': 'p,v|alpha,beta,n,m_v,b,c|p_ref,v_ref|p,v', 'mu': [0.30855086096762563, 0.35918885623371444]}, _d_huemer),
    'wriggers': ({'symbols': 'p,v|a,b,c,d||p', 'mu': [1.4600530165921597, 1.3379588364328607]}, _d_wriggers),
    'park': ({'symbols': 'p,v,T|n,mu_s,mu_m,h10,v_m|p0,C1,C2,T_ref|p,v', 'mu': [4.7902971190814885, 5.632278000197119]}, _d_park),
    'pacejka': ({'symbols': 's|B,C,D,E,S_h,S_v||', 'mu': [1.2127473283384602, 0.627521339460708]}, _d_pacejka),
    'burckhardt': ({'symbols': 's,v|c1,c2,c3,c4||', 'mu': [-0.07337738656099686, -0.04552885482524168]}, _d_burckhardt),
    'burckhardt-sqrt': ({'symbols': 's|c1,c2||', 'mu': [-0.24583822523924015, -0.5602973703645351]}, _d_burckhardt_sqrt),
    'kiencke-daiss': ({'symbols': 's|k_s,c1,c2||', 'mu': [0.31598676170309914, 0.31490605632098134]}, _d_kiencke_daiss),
    'germann': ({'symbols': 's|a0,a1,a2||', 'mu': [4.8795134120000005, 7.745515375999999]}, _d_germann),
}
