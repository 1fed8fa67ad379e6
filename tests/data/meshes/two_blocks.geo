// Two unit blocks side by side, structured hexahedra (Transfinite + Recombine), for the Gmsh reader tests.
// Written to two_blocks_ascii.msh and two_blocks_binary.msh by generate.sh.
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {1, 0, 0, 1, 1, 1};
Coherence;
Transfinite Curve{:} = 3;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
e = 1e-6;
Physical Volume("left") = {1};
Physical Volume("right") = {2};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 1 - e, 2 + e, 1 + e, 1 + e};
Physical Surface("xmax") = Surface In BoundingBox{2 - e, -e, -e, 2 + e, 1 + e, 1 + e};
