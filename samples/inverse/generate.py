#!/usr/bin/env python3
"""Regenerates the inverse-modelling sample seams (mm). Run from anywhere: python3 generate.py"""
import json
import math
import os

HERE = os.path.dirname(os.path.abspath(__file__))
DENSE = 400  # polyline points per OBJ curve; the tests resample to ~100


def tennis(t, a=40.0, b=20.0):
    """Classic tennis-ball seam on the sphere of radius a + b (c^2 = 4ab keeps |p| constant)."""
    c = 2.0 * math.sqrt(a * b)
    return (a * math.cos(t) + b * math.cos(3 * t), a * math.sin(t) - b * math.sin(3 * t),
            c * math.sin(2 * t))


def tennis_d(t, a=40.0, b=20.0):
    c = 2.0 * math.sqrt(a * b)
    return (-a * math.sin(t) - 3 * b * math.sin(3 * t), a * math.cos(t) - 3 * b * math.cos(3 * t),
            2 * c * math.cos(2 * t))


def saddle(t, r=80.0, h=40.0):
    """Saddle on the cylinder of radius r: two highs and two lows."""
    return (r * math.cos(t), r * math.sin(t), h * math.cos(2 * t))


def pushed_in(t, r=80.0, h=40.0, depth=0.45, centre=math.pi / 4, half=math.pi / 5):
    """The saddle with the stretch around t = pi/4 pushed towards the axis by up to 45 %."""
    d = abs((t - centre + math.pi) % (2 * math.pi) - math.pi)
    w = math.cos(0.5 * math.pi * d / half) ** 2 if d < half else 0.0
    s = r * (1.0 - depth * w)
    return (s * math.cos(t), s * math.sin(t), h * math.cos(2 * t))


def three_lobed(t):
    """Three lobes on the curve's convex hull, rising and falling three times."""
    return (60.0 * math.cos(t) + 10.0 * math.cos(2 * t), 50.0 * math.sin(t) - 10.0 * math.sin(2 * t),
            18.0 * math.sin(3 * t))


def write_obj(name, f, comment):
    with open(os.path.join(HERE, name), "w") as out:
        out.write("# " + comment + "\n")
        for k in range(DENSE):
            p = f(2 * math.pi * k / DENSE)
            out.write("v %.9f %.9f %.9f\n" % p)
        out.write("l " + " ".join(str(k + 1) for k in range(DENSE)) + " 1\n")


def rotation(axis, angle):
    x, y, z = axis
    n = math.sqrt(x * x + y * y + z * z)
    x, y, z = x / n, y / n, z / n
    c, s = math.cos(angle), math.sin(angle)
    return [[c + x * x * (1 - c), x * y * (1 - c) - z * s, x * z * (1 - c) + y * s],
            [y * x * (1 - c) + z * s, c + y * y * (1 - c), y * z * (1 - c) - x * s],
            [z * x * (1 - c) - y * s, z * y * (1 - c) + x * s, c + z * z * (1 - c)]]


def write_rotated_bezier(name, segments=32):
    R = rotation((1.0, 2.0, 3.0), math.radians(40.0))
    T = (150.0, -80.0, 35.0)
    move = lambda p: [round(sum(R[i][j] * p[j] for j in range(3)) + T[i], 9) for i in range(3)]
    control = []
    dt = 2 * math.pi / segments
    for s in range(segments):
        t0 = s * dt
        p0, d0, d1 = tennis(t0), tennis_d(t0), tennis_d(t0 + dt)
        p1 = tennis(t0 + dt)
        c1 = [p0[i] + d0[i] * dt / 3 for i in range(3)]  # cubic Hermite interpolation
        c2 = [p1[i] - d1[i] * dt / 3 for i in range(3)]
        control += [move(p0), move(c1), move(c2)]
    with open(os.path.join(HERE, name), "w") as out:
        rows = ",\n  ".join(json.dumps(p) for p in control)
        out.write('{"units": "mm",\n "bezier": [\n  ' + rows + "\n ]}\n")


write_obj("tennis-ball.obj", tennis, "tennis-ball seam on a sphere of radius 60 mm (on-hull)")
write_obj("saddle.obj", saddle, "saddle (80 cos t, 80 sin t, 40 cos 2t) mm (on-hull)")
write_obj("pushed-in.obj", pushed_in,
          "saddle with the stretch around t = pi/4 pushed 45 % towards the axis (non-on-hull)")
write_obj("three-lobed.obj", three_lobed,
          "three lobes (60 cos t + 10 cos 2t, 50 sin t - 10 sin 2t, 18 sin 3t) mm (on-hull)")
write_rotated_bezier("rotated.json")
