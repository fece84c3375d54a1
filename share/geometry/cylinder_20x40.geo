// Test fixture: a 20 mm x 40 mm cylinder, axis z, centred on the origin
// (lengths in metres). cylinder_20x40.msh is its tetrahedral volume mesh,
// written by gmsh (-3, mesh size 4 mm).
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -0.02, 0, 0, 0.04, 0.01};
