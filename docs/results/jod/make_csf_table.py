#!/usr/bin/python3
"""Writes a CSF table in the reference FovVideoVDP's cache format from foveal's CSF formula
(the same model as render/perception/src/csf.cpp, in NumPy), for a k_cm the reference does
not ship: release 1.0's 0.405835. docs/metrics.md ("JOD", "Release 1.0").

usage: /usr/bin/python3 make_csf_table.py K_CM OUT_DIR
writes OUT_DIR/o0_sn1_5_cm<K>_gpu0.mat and o5_... (sigma -1.5, omega 0 and 5 Hz).
"""
import os, sys
import numpy as np
import scipy.io as sio

MECH = [  # S_max, f_max (luminance dependence), bw, gamma, A'c: Mantiuk et al., CIC 2020
    ([356404, 6.2726, 0.320031, 895943, 7.77919e-05], [2.3021, 3317.45, 0.186215], 1.07516, 1.1107, 52.9768),
    ([423.978, 15.4032, 0.50343], [0.122699], 2.70669, 1.72903, 1.38437),
    ([11811.9, 196.342, 0.339396], [7.1099e-08], 5.3416, 1.47263, 0.282573),
]
LMS_TO_MECH = np.array([[1, 0.256197, 6.42477e-07], [1, -0.933541, 0.00373304], [-0.00130319, -1.1504, 1]])
XYZ_TO_LMS = np.array([[0.187596268556126, 0.585168649077728, -0.026384263306304],
                       [-0.133397430663221, 0.405505777260049, 0.034502127690364],
                       [0.000244379021663, -0.000542995890619, 0.019406849066323]])
LMS_WHITE = XYZ_TO_LMS @ np.array([0.9504, 1.0, 1.0888])


def lum_dep(p, lum):
    if len(p) == 1:
        return p[0] * np.ones_like(lum)
    a = p[0] * (1 + p[1] / lum) ** (-p[2])
    return a if len(p) == 3 else a * (1 - (1 + p[3] / lum) ** (-p[4]))


def mechanism(c, rho, area, lum):
    s_max_p, f_max_p, bw, gamma, ac = MECH[c]
    s_max, f_max = lum_dep(s_max_p, lum), lum_dep(f_max_p, lum)
    s_peak = s_max / 10 ** ((np.log10(rho) - np.log10(f_max)) ** 2 / (0.5 * 2 ** bw))
    if c > 0:
        s_peak = np.where(rho < f_max, s_max, s_peak)
    ag = area ** gamma * rho ** 2
    return s_peak * np.sqrt(ag / (ac + area * 0.65 + ag))


def spatio_velocity(rho, vel):
    v = np.maximum(vel, 0.1)
    k = 6.1 + 7.3 * np.abs(np.log10(0.7986 * v / 3)) ** 3
    return k * 0.6329 * 0.8404 * 0.7986 * v * (0.8404 * 2 * np.pi * rho) ** 2 * np.exp(-(0.8404 * 4 * np.pi * rho) / (45.9 / (0.7986 * v + 2)))


def sensitivity(rho, omega, lum, ecc, k_cm):
    m_rel = (3.67 / (ecc + 3.67)) ** k_cm
    area = np.pi * (1.5 / rho * m_rel) ** 2
    rc = rho / m_rel
    temporal = spatio_velocity(rc, omega / rc) / (spatio_velocity(rc, 0 * rc) + 1e-5)
    cc = np.array([0.698, 0.302, 0.019613]) / (lum[..., None] * LMS_WHITE)
    mech_lum = lum * (LMS_WHITE[0] + LMS_WHITE[1])
    acc = cc @ LMS_TO_MECH.T
    c = np.sqrt(sum((np.abs(acc[..., m]) * mechanism(m, rc, area, mech_lum)) ** 2 for m in range(3)))
    return np.maximum(c * np.sqrt(3) / np.linalg.norm(cc, axis=-1) * temporal, 1e-4)


def main():
    k_cm, out = float(sys.argv[1]), sys.argv[2]
    os.makedirs(out, exist_ok=True)
    n = 32
    Y = np.logspace(np.log10(0.001), np.log10(10000), n).astype(np.float32)
    rho = np.logspace(np.log10(1 / 16), np.log10(64), n).astype(np.float32)
    ecc = (np.linspace(0, np.sqrt(120), n) ** 2).astype(np.float32)
    yg, rg, eg = np.meshgrid(Y.astype(float), rho.astype(float), ecc.astype(float), indexing='ij')
    for omega in (0, 5):
        s_log = np.log2(sensitivity(rg, omega, yg, eg, k_cm)).astype(np.float32)
        lut = {'Y': Y, 'rho': rho, 'ecc': ecc, 'Y_log': np.log2(Y), 'rho_log': np.log2(rho),
               'ecc_sqrt': np.sqrt(ecc), 'S_log': s_log}
        key = ('o%g_s%g_cm%f' % (omega, -1.5, k_cm)).replace('-', 'n').replace('.', '_')
        sio.savemat(os.path.join(out, key + '_gpu0.mat'), {'lut': lut})
        print(key)


if __name__ == '__main__':
    main()
