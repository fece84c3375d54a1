// Test fixture: a 20 mm cube centred on the origin (lengths in metres).
// box_20mm.brep is this geometry written by gmsh's OpenCASCADE kernel.
SetFactory("OpenCASCADE");
Box(1) = {-0.01, -0.01, -0.01, 0.02, 0.02, 0.02};
