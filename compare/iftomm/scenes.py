#!/usr/bin/env python3
"""Writes the IFToMM benchmark scenes data/iftomm/a01-pendulum.json,
a03-andrews.json, a04-bricard.json and a05-flyball-governor.json from the
problems' data (docs/iftomm.md); a02-n-four-bar.json is `braun gen
n-four-bar 40`. Run from the repository root:
    python3 compare/iftomm/scenes.py
A03: Andrews' squeezing mechanism as seven planar rigid bodies in absolute
coordinates, placed from the Test Set for IVP Solvers' initial angles.
"""
import json, math, sys

# The test set's parameters (andrews.f).
m = [0.04325, 0.00365, 0.02373, 0.00706, 0.07050, 0.00706, 0.05498]
I = [2.194e-6, 4.410e-7, 5.255e-6, 5.667e-7, 1.169e-5, 5.667e-7, 1.912e-5]
xa, ya, xb, yb, xc, yc = -0.06934, -0.00227, -0.03635, 0.03273, 0.014, 0.072
c0, l0, mom = 4530.0, 0.07785, 0.033
d, da, e, ea, rr, ra = 28e-3, 115e-4, 2e-2, 1421e-5, 7e-3, 92e-5
ss, sa, sb, sc, sd, ta, tb = 35e-3, 1874e-5, 1043e-5, 18e-3, 2e-2, 2308e-5, 916e-5
u, ua, ub, zf, zt, fa = 4e-2, 1228e-5, 449e-5, 2e-2, 4e-2, 1421e-5
# Initial angles (andrews.f, init): beta, Theta, gamma, Phi, delta, Omega, epsilon.
be, th, ga, ph, de, om, ep = (-0.0617138900142764496358948458001, 0.0,
                              0.455279819163070380255912382449, 0.222668390165885884674473185609,
                              0.487364979543842550225598953530, -0.222668390165885884674473185609,
                              1.23054744454982119249735015568)

def rot(t, x, y):
    return (math.cos(t) * x - math.sin(t) * y, math.sin(t) * x + math.cos(t) * y)

def add(p, q):
    return (p[0] + q[0], p[1] + q[1])

A, B, C = (xa, ya), (xb, yb), (xc, yc)
F = (rr * math.cos(be), rr * math.sin(be))
G = add(A, (zt * math.cos(de), zt * math.sin(de)))
H = add(A, (u * math.sin(ep), -u * math.cos(ep)))

# (name, mass, inertia, angle, centre of mass, {point: body-frame coordinates})
bodies = []
t1 = be
bodies.append(("OF", m[0], I[0], t1, (ra * math.cos(be), ra * math.sin(be)),
               {"O": (-ra, 0.0), "F": (rr - ra, 0.0)}))
t2 = be + th + math.pi
bodies.append(("FE", m[1], I[1], t2, add(F, rot(t2, da, 0.0)),
               {"F": (-da, 0.0), "E": (d - da, 0.0)}))
t3 = ga
bodies.append(("BDE", m[2], I[2], t3, add(B, rot(t3, sb, -sa)),
               {"B": (-sb, sa), "D": (sd - sb, -sc + sa), "E": (-sb, -ss + sa)}))
t4 = ph + de - math.pi / 2
bodies.append(("EG", m[3], I[3], t4, add(G, rot(t4, e - ea, 0.0)),
               {"G": (-(e - ea), 0.0), "E": (ea, 0.0)}))
t5 = de
bodies.append(("AG", m[4], I[4], t5, add(A, rot(t5, ta, tb)),
               {"A": (-ta, -tb), "G": (zt - ta, -tb)}))
t6 = om + ep
bodies.append(("HE", m[5], I[5], t6, add(H, rot(t6, zf - fa, 0.0)),
               {"H": (-(zf - fa), 0.0), "E": (fa, 0.0)}))
t7 = ep - math.pi / 2
bodies.append(("AH", m[6], I[6], t7, add(A, rot(t7, ua, ub)),
               {"A": (-ua, -ub), "H": (u - ua, -ub)}))

def num(x):
    return float(repr(x))

def world(name, point):
    for b in bodies:
        if b[0] == name:
            return add(b[4], rot(b[3], *b[5][point]))
    raise KeyError(name)

# The loop closes at E, G, H within round-off (the test set's initial
# angles are consistent with B = (-0.03635, 0.03273)).
for a, b in (("FE", "BDE"), ("FE", "EG"), ("FE", "HE")):
    pa, pb = world(a, "E"), world(b, "E")
    assert math.hypot(pa[0] - pb[0], pa[1] - pb[1]) < 1e-15, (a, b)
assert math.hypot(*[p - q for p, q in zip(world("BDE", "B"), B)]) < 1e-15
assert math.hypot(*[p - q for p, q in zip(world("EG", "G"), world("AG", "G"))]) < 1e-15
assert math.hypot(*[p - q for p, q in zip(world("HE", "H"), world("AH", "H"))]) < 1e-15

out = []
out.append('{')
out.append('  "name": "a03-andrews",')
out.append('  "description": "IFToMM benchmark A03 (docs/iftomm.md): Andrews\' squeezing mechanism, '
           'seven planar rigid bodies in absolute coordinates placed from the IVP test set\'s '
           'initial angles, at rest, no gravity, torque 0.033 N m on the crank OF, spring 4530 N/m '
           '(rest 0.07785 m) from D to C; 0.03 s (test set), 0.05 s (IFToMM variant); reported: '
           'F, error max |F - F_ref| over the output grid <= 1e-3 (written by '
           'compare/iftomm/scenes.py)",')
out.append('  "ground": {"points": {"O": [0, 0], "A": [%r, %r], "B": [%r, %r], "C": [%r, %r]}},'
           % (xa, ya, xb, yb, xc, yc))
out.append('  "bodies": [')
for k, (name, mass, inertia, angle, pos, pts) in enumerate(bodies):
    p = ", ".join('"%s": [%r, %r]' % (pn, num(x), num(y)) for pn, (x, y) in pts.items())
    out.append('    {"name": "%s", "type": "rigid", "mass": %r, "inertia": %r, '
               '"position": [%r, %r], "angle": %r,\n     "points": {%s}}%s'
               % (name, mass, inertia, num(pos[0]), num(pos[1]), num(angle), p,
                  "," if k < len(bodies) - 1 else ""))
out.append('  ],')
joints = [("O", "OF.O", "ground.O"), ("F", "OF.F", "FE.F"), ("E-BDE", "FE.E", "BDE.E"),
          ("E-EG", "FE.E", "EG.E"), ("E-HE", "FE.E", "HE.E"), ("B", "BDE.B", "ground.B"),
          ("G", "EG.G", "AG.G"), ("A-AG", "AG.A", "ground.A"), ("A-AH", "AH.A", "ground.A"),
          ("H", "HE.H", "AH.H")]
out.append('  "joints": [')
for k, (name, a, b) in enumerate(joints):
    out.append('    {"name": "%s", "type": "revolute", "a": "%s", "b": "%s"}%s'
               % (name, a, b, "," if k < len(joints) - 1 else ""))
out.append('  ],')
out.append('  "effects": [')
out.append('    {"name": "spring", "type": "spring", "a": "BDE.D", "b": "ground.C", '
           '"stiffness": %r, "rest_length": %r},' % (c0, l0))
out.append('    {"name": "motor", "type": "torque", "body": "OF", "torque": %r}' % mom)
out.append('  ],')
out.append('  "report": {"F": "OF.F"}')
out.append('}')
andrews_text = "\n".join(out) + "\n"

def r(x):
    """A number as the shortest repr of its double (0 for zeros of either sign)."""
    return "0" if x == 0 else repr(float(x))

def v3(a):
    return "[%s, %s, %s]" % (r(a[0]), r(a[1]), r(a[2]))

# ---------------------------------------------------------------- A01
pendulum_text = """{
  "name": "a01-pendulum",
  "description": "IFToMM benchmark A01 (docs/iftomm.md): point mass P1 of 1 kg on a massless rod of 1 m pinned at the origin, released at rest from P1 = (1, 0), gravity 9.81 m/s^2 along -y; 2000 s over 4000 output steps (IFToMM 10 s variant); reported: P1, error max |P1 - P1_ref| <= 1e-3",
  "bodies": [
    {"name": "P1", "type": "particle", "mass": 1, "position": [1, 0]}
  ],
  "joints": [
    {"name": "rod", "type": "distance", "a": [0, 0], "b": "P1", "length": 1}
  ],
  "effects": [
    {"type": "gravity", "g": [0, -9.81]}
  ],
  "report": {"P1": "P1"}
}
"""

# ---------------------------------------------------------------- A04
# Rods of 1 m, 1 kg, square cross-section 0.1 m: moments about the centre
# m(a^2 + a^2)/12 along the rod, m(L^2 + a^2)/12 across it.
Ia, It = (0.1 ** 2 + 0.1 ** 2) / 12, (1 + 0.1 ** 2) / 12
# (name, centre, direction index of the rod, its proximal and distal joints
# in the body frame (= world axes initially))
rods = [("rod1", (0.5, 0, 0), 0, ("A", (-0.5, 0, 0)), ("B", (0.5, 0, 0))),
        ("rod2", (1, -0.5, 0), 1, ("B", (0, 0.5, 0)), ("C", (0, -0.5, 0))),
        ("rod3", (1, -1, 0.5), 2, ("C", (0, 0, -0.5)), ("D", (0, 0, 0.5))),
        ("rod4", (0.5, -1, 1), 0, ("D", (0.5, 0, 0)), ("E", (-0.5, 0, 0))),
        ("rod5", (0, -0.5, 1), 1, ("E", (0, -0.5, 0)), ("F", (0, 0.5, 0)))]
lines = ['{', '  "name": "a04-bricard",',
         '  "description": "IFToMM benchmark A04 (docs/iftomm.md): Bricard\'s mechanism, five rods '
         '(1 m, 1 kg, 0.1 m square section) and six revolute joints whose axes are each '
         'perpendicular to both rods they join; Gruebler counts 0 degrees of freedom, the mobility '
         'is 1 (one redundant row); at rest, gravity 9.81 m/s^2 along -y; 600 s (IFToMM 10 s '
         'variant); reported: P3, error max |P3 - P3_ref| <= 1e-3",',
         '  "ground": {"points": {"A": [0, 0, 0], "F": [0, 0, 1]}},', '  "bodies": [']
for k, (name, c, along, (pn, pp), (dn, dp)) in enumerate(rods):
    inertia = [It, It, It]
    inertia[along] = Ia
    lines.append('    {"name": "%s", "type": "rigid3d", "mass": 1, "inertia": %s, "position": %s,'
                 % (name, v3(inertia), v3(c)))
    lines.append('     "points": {"%s": %s, "%s": %s}}%s'
                 % (pn, v3(pp), dn, v3(dp), "," if k < 4 else ""))
lines.append('  ],')
lines.append('  "joints": [')
joints3 = [("A", "rod1.A", "ground.A", (0, 1, 0)), ("B", "rod1.B", "rod2.B", (0, 0, 1)),
           ("C", "rod2.C", "rod3.C", (1, 0, 0)), ("D", "rod3.D", "rod4.D", (0, 1, 0)),
           ("E", "rod4.E", "rod5.E", (0, 0, 1)), ("F", "rod5.F", "ground.F", (1, 0, 0))]
for k, (name, a, b, ax) in enumerate(joints3):
    lines.append('    {"name": "%s", "type": "revolute3d", "a": "%s", "b": "%s", "axis": [%d, %d, %d]}%s'
                 % (name, a, b, ax[0], ax[1], ax[2], "," if k < 5 else ""))
lines += ['  ],', '  "effects": [', '    {"type": "gravity", "g": [0, -9.81, 0]}', '  ],',
          '  "report": {"P3": "rod2.C"}', '}']
bricard_text = "\n".join(lines) + "\n"

# ---------------------------------------------------------------- A05
rho, w0, alpha = 3000.0, 2 * math.pi, math.radians(30)
# Shaft and rods: 3000 x 1 x 0.01 x 0.01 = 0.3 kg, moments 0.3 (0.01^2 + 0.01^2)/12
# = 5e-6 along, 0.3 (1 + 0.01^2)/12 = 0.0250025 across; slider: 3000 x 0.1^3 =
# 3 kg, 3 (0.1^2 + 0.1^2)/12 = 0.005 (written as decimals: the products in
# binary would print 3.000000000000001).
m_bar, I_bar_long, I_bar_trans, m_sl, I_sl = 0.3, 5e-6, 0.0250025, 3.0, 0.005
def spin(p):
    """Velocity of the world point p turning at w0 about z."""
    return (-w0 * p[1], w0 * p[0], 0.0)
lines = ['{', '  "name": "a05-flyball-governor",',
         '  "description": "IFToMM benchmark A05 (docs/iftomm.md): stiff flyball governor; shaft '
         'and rods 1 x 0.01 x 0.01 m, slider 0.1 m cube, density 3000 kg/m^3, 5 kg point masses '
         'at the rod ends, the coupler rods replaced by spring-dampers (8e5 N/m, 4e4 N s/m, rest '
         '0.5 m); the shaft turns freely, starting at 2 pi rad/s, s = 0.5 m, alpha = 30 deg; '
         'gravity 9.81 m/s^2 along -z; 350 s (IFToMM 10 s variant); reported: S (the slider, '
         'S.z = s), error max |S - S_ref| <= 1e-3",',
         '  "bodies": [']
omega = '"omega": [0, 0, %s]' % r(w0)
lines.append('    {"name": "shaft", "type": "rigid3d", "mass": %s, "inertia": %s, "position": [0, 0, 0.5], %s,'
             % (r(m_bar), v3((I_bar_trans, I_bar_trans, I_bar_long)), omega))
lines.append('     "points": {"base": [0, 0, -0.5], "pin1": [0.05, 0, 0.5], "pin2": [-0.05, 0, 0.5]}},')
lines.append('    {"name": "slider", "type": "rigid3d", "mass": %s, "inertia": %s, "position": [0, 0, 0.5], %s,'
             % (r(m_sl), v3((I_sl, I_sl, I_sl)), omega))
lines.append('     "points": {"s1": [0.05, 0, 0], "s2": [-0.05, 0, 0]}},')
for i, sg in ((1, 1.0), (2, -1.0)):
    d = (sg * math.cos(alpha), 0.0, -math.sin(alpha))      # the rod, pin to end
    pin = (sg * 0.05, 0.0, 1.0)
    c = tuple(pin[k] + 0.5 * d[k] for k in range(3))
    end = tuple(pin[k] + d[k] for k in range(3))
    ang = alpha if sg > 0 else math.pi - alpha           # turns body x onto d about y
    quat = (math.cos(ang / 2), 0.0, math.sin(ang / 2), 0.0)
    lines.append('    {"name": "rod%d", "type": "rigid3d", "mass": %s, "inertia": %s, "position": %s,'
                 % (i, r(m_bar), v3((I_bar_long, I_bar_trans, I_bar_trans)), v3(c)))
    lines.append('     "orientation": [%s, %s, %s, %s], "velocity": %s, %s,'
                 % (r(quat[0]), r(quat[1]), r(quat[2]), r(quat[3]), v3(spin(c)), omega))
    lines.append('     "points": {"pin": [-0.5, 0, 0], "end": [0.5, 0, 0]}},')
    lines.append('    {"name": "mass%d", "type": "particle3d", "mass": 5, "position": %s, "velocity": %s}%s'
                 % (i, v3(end), v3(spin(end)), "," if i == 1 else ""))
lines += ['  ],', '  "joints": [',
          '    {"name": "pivot", "type": "revolute3d", "a": "shaft.base", "b": [0, 0, 0], "axis": [0, 0, 1]},',
          '    {"name": "slide", "type": "prismatic3d", "point": "slider", "line": "shaft.base", "axis": [0, 0, 1]},',
          '    {"name": "pin1", "type": "revolute3d", "a": "rod1.pin", "b": "shaft.pin1", "axis": [0, 1, 0]},',
          '    {"name": "pin2", "type": "revolute3d", "a": "rod2.pin", "b": "shaft.pin2", "axis": [0, 1, 0]},',
          '    {"name": "ball1", "type": "spherical", "a": "rod1.end", "b": "mass1"},',
          '    {"name": "ball2", "type": "spherical", "a": "rod2.end", "b": "mass2"}',
          '  ],', '  "effects": [', '    {"type": "gravity", "g": [0, 0, -9.81]},',
          '    {"name": "spring1", "type": "spring", "a": "slider.s1", "b": "rod1", "stiffness": 8e5, "damping": 4e4, "rest_length": 0.5},',
          '    {"name": "spring2", "type": "spring", "a": "slider.s2", "b": "rod2", "stiffness": 8e5, "damping": 4e4, "rest_length": 0.5}',
          '  ],', '  "report": {"S": "slider"}', '}']
flyball_text = "\n".join(lines) + "\n"

for name, text in (("a01-pendulum", pendulum_text), ("a03-andrews", andrews_text),
                   ("a04-bricard", bricard_text), ("a05-flyball-governor", flyball_text)):
    json.loads(text)  # well-formed
    with open("data/iftomm/%s.json" % name, "w") as f:
        f.write(text)
