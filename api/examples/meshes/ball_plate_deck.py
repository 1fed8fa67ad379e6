#!/usr/bin/env python3
"""Writes ball_plate.inp: the mesh part of a CalculiX deck with a hollow ball (ELSET=EBALL) above a plate
(ELSET=EPLATE), C3D8 elements, element-based *SURFACE SBALL (outer faces of the ball, S2) and SPLATE
(top faces of the plate, S2), and the material/step cards a CalculiX user would have (Stoss skips them).

The ball is a cube-sphere shell (6 patches of N x N equiangular cells, one layer), outer radius 1, inner 0.8,
centred at (0, 0, 1.05); the plate is [-2, 2]^2 x [-0.2, 0] in 8 x 8 x 1 elements. Stdlib only:
    python3 ball_plate_deck.py > ball_plate.inp
"""
import math

N = 4                      # cells per patch edge
R_OUT, R_IN = 1.0, 0.8
CENTER = (0.0, 0.0, 1.05)

nodes = []                 # (x, y, z)
index = {}                 # rounded coordinates -> node id


def node(x):
    key = tuple(round(c, 9) for c in x)
    if key not in index:
        nodes.append(x)
        index[key] = len(nodes)
    return index[key]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def sub(a, b):
    return tuple(p - q for p, q in zip(a, b))


def dot(a, b):
    return sum(p * q for p, q in zip(a, b))


# Six cube faces: (normal axis, sign); (u, v) axes chosen per face.
faces = [(0, 1), (0, -1), (1, 1), (1, -1), (2, 1), (2, -1)]
ball = []
for axis, sign in faces:
    u_axis, v_axis = [a for a in range(3) if a != axis]

    def point(i, j, r):
        a = -math.pi / 4 + math.pi / 2 * i / N
        b = -math.pi / 4 + math.pi / 2 * j / N
        d = [0.0, 0.0, 0.0]
        d[axis] = sign
        d[u_axis] = math.tan(a)
        d[v_axis] = math.tan(b)
        n = math.sqrt(dot(d, d))
        return tuple(CENTER[k] + r * d[k] / n for k in range(3))

    for i in range(N):
        for j in range(N):
            quad = [(i, j), (i + 1, j), (i + 1, j + 1), (i, j + 1)]
            inner = [point(a, b, R_IN) for a, b in quad]
            outer = [point(a, b, R_OUT) for a, b in quad]
            # Nodes 1-4 on the inner sphere, 5-8 above them on the outer one; (2-1) x (4-1) must point outwards.
            if dot(cross(sub(inner[1], inner[0]), sub(inner[3], inner[0])), sub(outer[0], inner[0])) < 0:
                inner = [inner[0], inner[3], inner[2], inner[1]]
                outer = [outer[0], outer[3], outer[2], outer[1]]
            ball.append([node(x) for x in inner + outer])

plate = []
NX, NY, NZ = 8, 8, 1
for k in range(NZ):
    for j in range(NY):
        for i in range(NX):
            def p(a, b, c):
                return node((-2 + 4 * a / NX, -2 + 4 * b / NY, -0.2 + 0.2 * c / NZ))
            plate.append([p(i, j, k), p(i + 1, j, k), p(i + 1, j + 1, k), p(i, j + 1, k),
                          p(i, j, k + 1), p(i + 1, j, k + 1), p(i + 1, j + 1, k + 1), p(i, j + 1, k + 1)])

print("*HEADING")
print("Hollow ball over a plate (written by ball_plate_deck.py)")
print("*NODE, NSET=NALL")
for n, x in enumerate(nodes, 1):
    print(f"{n}, {x[0]:.12g}, {x[1]:.12g}, {x[2]:.12g}")
print("*ELEMENT, TYPE=C3D8, ELSET=EBALL")
for e, h in enumerate(ball, 1):
    print(f"{e}, " + ", ".join(map(str, h)))
print("*ELEMENT, TYPE=C3D8, ELSET=EPLATE")
for e, h in enumerate(plate, len(ball) + 1):
    print(f"{e}, " + ", ".join(map(str, h)))
first_top = len(ball) + 1 + (NZ - 1) * NX * NY
print("*ELSET, ELSET=EPLATETOP, GENERATE")
print(f"{first_top}, {len(ball) + len(plate)}, 1")
print("*SURFACE, NAME=SBALL, TYPE=ELEMENT")
print("EBALL, S2")
print("*SURFACE, NAME=SPLATE, TYPE=ELEMENT")
print("EPLATETOP, S2")
print("*MATERIAL, NAME=RUBBERLIKE")
print("*ELASTIC")
print("10000., 0.4")
print("*DENSITY")
print("1.")
print("*SOLID SECTION, ELSET=EBALL, MATERIAL=RUBBERLIKE")
print("*SOLID SECTION, ELSET=EPLATE, MATERIAL=RUBBERLIKE")
print("*STEP, NLGEOM")
print("*DYNAMIC")
print("0.01, 1.0")
print("*END STEP")
