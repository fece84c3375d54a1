// Test fixture: the 20 mm x 40 mm cylinder of cylinder_20x40.geo drawn in
// millimetres, as CAD models usually are. cylinder_20x40_mm.step is this
// geometry written as STEP by gmsh's OpenCASCADE kernel (which records the
// unit, mm); pack reads STEP files in metres whatever their unit.
SetFactory("OpenCASCADE");
Cylinder(1) = {0, 0, -20, 0, 0, 40, 10};
