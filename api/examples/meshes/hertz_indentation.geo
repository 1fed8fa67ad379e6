// Hertz indentation, a quarter model: a block [0, L] x [0, L] x [-H, 0] and the lower cap of a sphere of
// radius R = 1 centred at (0, 0, R), touching the block at the origin. Structured hexahedra (extrusions with
// graded layers), fine at the origin: element edge h0 up to `fine` from the origin on the top face and to
// `zfine` in depth, then growing by the factor q per element out to L and H.
// The cap is the part of the sphere's surface within 0.4 of the axis (a = sqrt(R delta) is 0.14 at
// delta/R = 2 %), thickness 0.1 (translated upwards), and reaches 2 elements past the symmetry planes x = 0 and
// y = 0, so that the contact surface has no rim at the contact's centre. Its nodes lie on the sphere.
// Three levels (docs/measurements.md, "Hertz indentation"); regenerate with Debian's gmsh (4.8.4):
//     gmsh -3 -format msh41 -setnumber h0 0.05   hertz_indentation.geo -o hertz_coarse.msh
//     gmsh -3 -format msh41 -setnumber h0 0.03   hertz_indentation.geo -o hertz_medium.msh   (made by bench/hertz_indentation.py)
//     gmsh -3 -format msh41 -setnumber h0 0.02   hertz_indentation.geo -o hertz_fine.msh     (made by bench/hertz_indentation.py)
// Physical volumes "block" and "sphere"; physical surfaces "top", "bottom", "xmin", "ymin" (block) and "cap"
// (the sphere's spherical face) and "top" (the cap's upper face, where the motion is prescribed).
DefineConstant[ h0 = 0.05, q = 1.5, L = 20, H = 20, R = 1, fine = 0.25, zfine = 0.25, cap = 0.4, t = 0.1 ];

// Graded layers along [0, len]: n0 cells of h0 up to `fine`, then cells growing by q, scaled so the last one
// ends at len. Out: ones[] (one element per layer) and fr[] (cumulative fractions of len).
Macro Graded
  n0 = Round(fine / h0);
  k = Ceil(Log(1 + (len - n0 * h0) * (q - 1) / (h0 * q)) / Log(q));
  tail = h0 * q * (q^k - 1) / (q - 1);
  scale = (len - n0 * h0) / tail;
  ones[] = {};
  fr[] = {};
  For i In {1 : n0}
    ones[] += 1;
    fr[] += i * h0 / len;
  EndFor
  s = n0 * h0;
  For j In {1 : k}
    s += h0 * q^j * scale;
    ones[] += 1;
    fr[] += s / len;
  EndFor
  fr[#fr[] - 1] = 1;
Return

// The block: a point extruded along x, the line along y (the top face), the face down to -H.
len = L;
Call Graded;
Point(1) = {0, 0, 0};
bx[] = Extrude {L, 0, 0} { Point{1}; Layers{ones[], fr[]}; };
by[] = Extrude {0, L, 0} { Curve{bx[1]}; Layers{ones[], fr[]}; Recombine; };
len = H;
xyfine = fine;
fine = zfine;
Call Graded;
fine = xyfine;
bz[] = Extrude {0, 0, -H} { Surface{by[1]}; Layers{ones[], fr[]}; Recombine; };
// bz[0] the bottom (z = -H), bz[1] the volume, bz[2..5] the sides from the lines of by[1]'s boundary.

// The cap: the sphere's pole P = (0, 0, 0) rotated about the y axis through the centre C = (0, 0, R) gives the
// meridian in y = 0 (towards +x with a negative angle); that curve rotated about the x axis through C gives
// the surface. Arc length s = R * angle, graded as the block's top. Two elements of h0 beyond each
// symmetry plane.
len = cap;
Call Graded;
pole = newp;
Point(pole) = {0, 0, 0};
mx[] = Extrude { {0, 1, 0}, {0, 0, R}, -cap / R } { Point{pole}; Layers{ones[], fr[]}; };
neg = 2 * h0;
rim = newp;
Point(rim) = {-R * Sin(neg / R), 0, R - R * Cos(neg / R)};
mn[] = Extrude { {0, 1, 0}, {0, 0, R}, -neg / R } { Point{rim}; Layers{2}; };
c1[] = Extrude { {1, 0, 0}, {0, 0, R}, cap / R } { Curve{mx[1]}; Layers{ones[], fr[]}; Recombine; };
c2[] = Extrude { {1, 0, 0}, {0, 0, R}, cap / R } { Curve{mn[1]}; Layers{ones[], fr[]}; Recombine; };
c3[] = Extrude { {1, 0, 0}, {0, 0, R}, -neg / R } { Curve{mx[1]}; Layers{2}; Recombine; };
c4[] = Extrude { {1, 0, 0}, {0, 0, R}, -neg / R } { Curve{mn[1]}; Layers{2}; Recombine; };
v1[] = Extrude {0, 0, t} { Surface{c1[1]}; Layers{2}; Recombine; };
v2[] = Extrude {0, 0, t} { Surface{c2[1]}; Layers{2}; Recombine; };
v3[] = Extrude {0, 0, t} { Surface{c3[1]}; Layers{2}; Recombine; };
v4[] = Extrude {0, 0, t} { Surface{c4[1]}; Layers{2}; Recombine; };

Physical Volume("block") = {bz[1]};
Physical Volume("sphere") = {v1[1], v2[1], v3[1], v4[1]};
Physical Surface("top") = {by[1], v1[0], v2[0], v3[0], v4[0]};
Physical Surface("bottom") = {bz[0]};
e = 1e-6;  // the block's sides x = 0 and y = 0 (the sphere's faces there are interior or above z = 0)
Physical Surface("xmin") = Surface In BoundingBox{-e, -e, -H - e, e, L + e, e};
Physical Surface("ymin") = Surface In BoundingBox{-e, -e, -H - e, L + e, e, e};
Physical Surface("cap") = {c1[1], c2[1], c3[1], c4[1]};
