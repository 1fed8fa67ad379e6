#!/bin/sh
# Regenerates the Gmsh fixtures of the mesh reader tests with Debian's gmsh (committed files: gmsh 4.8.4).
#   two_blocks_ascii.msh, two_blocks_binary.msh: MSH 4.1 of two_blocks.geo (16 hexahedra, 45 nodes).
set -e
cd "$(dirname "$0")"
gmsh -3 -format msh41 two_blocks.geo -o two_blocks_ascii.msh > /dev/null
gmsh -3 -format msh41 -bin two_blocks.geo -o two_blocks_binary.msh > /dev/null
