#!/bin/sh
# Regenerates the Gmsh fixtures of the mesh reader tests with Debian's gmsh (committed files: gmsh 4.8.4).
#   two_blocks_ascii.msh, two_blocks_binary.msh: MSH 4.1 of two_blocks.geo (16 hexahedra, 45 nodes).
set -e
cd "$(dirname "$0")"
gmsh -3 -format msh41 two_blocks.geo -o two_blocks_ascii.msh > /dev/null
gmsh -3 -format msh41 -bin two_blocks.geo -o two_blocks_binary.msh > /dev/null
#   cgx_block.inp: CalculiX GraphiX (cgx 2.17) batch mesh of cgx_block.fbd, 16 C3D8 in ELSET Eall, 45 nodes.
if command -v cgx > /dev/null; then
  tmp=$(mktemp -d)
  cp cgx_block.fbd "$tmp/" && (cd "$tmp" && cgx -bg cgx_block.fbd > /dev/null 2>&1)
  mv "$tmp/all.msh" cgx_block.inp && rm -rf "$tmp"
fi
#   gmsh_box.inp: Gmsh's Abaqus export (gmsh -3 -format inp) of gmsh_box.geo: 8 C3D8 in ELSET block (and
#   Volume1), its physical surfaces bottom and top as 4 CPS4 each (ELSETs bottom, top, Surface5, Surface6),
#   and a *NSET per physical group (Mesh.SaveGroupsOfNodes); 27 nodes.
gmsh -3 -format inp gmsh_box.geo -o gmsh_box.inp > /dev/null
