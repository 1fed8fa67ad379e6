// A small box meshed with hexahedra (Transfinite + Recombine), exported as an Abaqus deck by Gmsh
// (generate.sh: gmsh -3 -format inp gmsh_box.geo -o gmsh_box.inp): the deck carries the physical surfaces
// as CPS4 quadrangles beside the C3D8 hexahedra, and a *NSET per physical group (Mesh.SaveGroupsOfNodes).
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 2, 1, 1};
Transfinite Curve{:} = 3;
Transfinite Surface{:};
Recombine Surface{:};
Transfinite Volume{:};
e = 1e-6;
Physical Volume("block") = {1};
Physical Surface("bottom") = Surface In BoundingBox{-e, -e, -e, 2 + e, 1 + e, e};
Physical Surface("top") = Surface In BoundingBox{-e, -e, 1 - e, 2 + e, 1 + e, 1 + e};
Mesh.SaveGroupsOfNodes = 1;
