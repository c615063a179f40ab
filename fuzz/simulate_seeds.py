#!/usr/bin/env python3
"""Writes the seed inputs of the simulate fuzz target (corpus/simulate/):
byte strings that decode, by fuzz_simulate.c's decode(), into chosen setups.
Run from fuzz/ after changing decode(); the seeds are small and committed."""
import math
import struct

RIM = 0.1

def val(v, lo, hi):
    """value_in(): selector 0, then 16 bits spread over [lo, hi]."""
    u = round((v - lo) / (hi - lo) * 65535)
    return bytes([0, u >> 8, u & 0xFF])

def raw(v):
    return bytes([250]) + struct.pack('>d', v)

NAN = bytes([236])

def setup(body=None, incline=30, g=9.78, mu=0.5, e=0.3, theta0=0.0, omega0=0.0, ramp=3.2,
          paper_d=0.0265, air=None, t_max=1.0, events=32, sample_dt=None):
    b = bytearray()
    if body is None:
        b.append(0)
    else:
        radius, parts = body
        b.append(1)
        b += val(radius, 1e-3, 1.0)
        b.append(len(parts) - 1)
        for i in range(16):
            kind, mass, offset, pr, angle = parts[i] if i < len(parts) else (0, 0.0, 0.0, 0.0, 0.0)
            b.append(kind)
            b += val(mass, 0.0, 1.0) + val(offset, 0.0, radius)
            if kind != 3:
                b += val(pr, 0.0, radius - offset)
            b += val(angle, -10.0, 10.0)
    rim = body[0] if body else RIM
    b += val(math.radians(incline), 0.0, math.pi / 2) + val(g, 0.1, 100.0) + val(mu, 0.0, 2.0)
    b.append(1)  # mu_k = mu_s
    b += val(e, 0.0, 1.0) + val(theta0, -7.0, 7.0) + val(omega0, -50.0, 50.0)
    b += val(ramp, 1e-3, 20.0) + val(paper_d, 0.0, rim)
    if air is None:
        b.append(0)
    else:
        length, rho, cd, cl, spin, rr = air
        b.append(1)
        b += val(length, 0.0, 0.3) + val(rho, 0.0, 2.0) + val(cd, 0.0, 2.0) + val(cl, -1.0, 1.0)
        b += val(spin, 0.0, 1e-4) + val(rr, 0.0, 0.5 * rim)
    b += val(t_max, 1e-4, 2.0)
    b.append(events - 1)
    if sample_dt is None:
        b.append(0)
    else:
        b.append(1)
        b += val(sample_dt, 0.02, 0.5)
    b += val(1e-9, 1e-10, 1e-6) + val(1e-11, 1e-12, 1e-8) + val(1e-10, 1e-12, 1e-6) + val(1e-6, 0.0, 1e-3)
    return bytes(b)

HOOP = (0.1, [(1, 0.01, 0.0, 0.1, 0.0), (3, 0.1, 0.1, 0.0, 0.0)])
WHEEL = (0.25, [(0, 1.0, 0.0, 0.25, 0.0), (3, 0.75, 0.2, 0.0, 0.0)])

SEEDS = {
    'paper-30': setup(),
    'paper-45-sampled': setup(incline=45, sample_dt=0.05),
    'paper-15-slippery': setup(incline=15, mu=0.1, e=0.9),
    'hoop-floor': setup(body=HOOP, incline=0, omega0=8.0, paper_d=0.0),
    'wheel': setup(body=WHEEL, incline=20, mu=0.6, e=0.2, paper_d=0.0, t_max=2.0),
    'air': setup(air=(0.0555, 1.204, 0.6, 0.2, 1e-6, 0.001)),
    'uphill-start': setup(omega0=-5.0, theta0=1.0),
    'nan-incline': setup()[:1] + NAN + setup()[4:],
    'huge-gravity': setup()[:4] + raw(1e300) + setup()[7:],
}

for name, data in SEEDS.items():
    with open('corpus/simulate/' + name, 'wb') as f:
        f.write(data)
