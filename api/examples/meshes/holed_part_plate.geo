// A square part with a round hole through it, above a plate; structured hexahedra (Transfinite +
// Recombine + extrusion). Regenerate with Debian's gmsh (holed_part_plate.msh was written by gmsh 4.8.4):
//     gmsh -3 -format msh41 holed_part_plate.geo -o holed_part_plate.msh
// Physical volumes "part" and "plate" are the two bodies; physical surface "bottom" holds the part's lower
// face and the plate's lower face, "top" the part's upper face and the plate's upper face, so that
// part/bottom, part/top, plate/bottom and plate/top all exist.
a = 0.6;            // half width of the part
r = 0.3;            // hole radius
h = 0.3;            // part thickness
z0 = 0.03;          // gap between the part and the plate (top of the plate at z = 0)
n = 4;              // cells along a side (and a quarter arc)
m = 3;              // cells from the hole to the side

Point(1) = {0, 0, z0};
Point(2) = {a, a, z0};   Point(3) = {-a, a, z0};  Point(4) = {-a, -a, z0};  Point(5) = {a, -a, z0};
c = r / Sqrt(2);
Point(6) = {c, c, z0};   Point(7) = {-c, c, z0};  Point(8) = {-c, -c, z0};  Point(9) = {c, -c, z0};
Line(1) = {2, 3};  Line(2) = {3, 4};  Line(3) = {4, 5};  Line(4) = {5, 2};
Circle(5) = {6, 1, 7};  Circle(6) = {7, 1, 8};  Circle(7) = {8, 1, 9};  Circle(8) = {9, 1, 6};
Line(9) = {6, 2};  Line(10) = {7, 3};  Line(11) = {8, 4};  Line(12) = {9, 5};
Curve Loop(1) = {9, 1, -10, -5};   Plane Surface(1) = {1};
Curve Loop(2) = {10, 2, -11, -6};  Plane Surface(2) = {2};
Curve Loop(3) = {11, 3, -12, -7};  Plane Surface(3) = {3};
Curve Loop(4) = {12, 4, -9, -8};   Plane Surface(4) = {4};
Transfinite Curve{1:8} = n + 1;
Transfinite Curve{9:12} = m + 1;
Transfinite Surface{1:4};
Recombine Surface{1:4};
part[] = Extrude {0, 0, h} { Surface{1:4}; Layers{2}; Recombine; };

Point(101) = {-1.2, -1.2, -0.2};
pl[] = Extrude {2.4, 0, 0} { Point{101}; Layers{8}; };
ps[] = Extrude {0, 2.4, 0} { Curve{pl[1]}; Layers{8}; Recombine; };
pv[] = Extrude {0, 0, 0.2} { Surface{ps[1]}; Layers{1}; Recombine; };

Physical Volume("part") = {part[1], part[7], part[13], part[19]};
Physical Volume("plate") = {pv[1]};
Physical Surface("bottom") = {1, 2, 3, 4, ps[1]};
Physical Surface("top") = {part[0], part[6], part[12], part[18], pv[0]};
